// `grainshock movie`: runs one realisation and streams frames of the spreading front into
// DIR/movie.mp4 beside movie.toml (every setting, for --config), with checkpoints that
// `grainshock resume DIR` goes on from, or, given snapshot files, draws them in order of their
// time into DIR/movie.mp4 (see jobs/movie.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string_view>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/progress.h"
#include "io/atomic_file.h"
#include "io/output_dir.h"
#include "jobs/movie.h"
#include "sim/config.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {

using namespace jobs;
namespace {

// What a movie writes into its folder; --force removes these first, so that a folder never
// mixes two movies.
constexpr const char* kMovieOutputs[] = {
    "movie.toml", "movie.mp4", "movie.parts", "movie.checkpoint.bin", "movie.checkpoint.prev.bin",
    "frames"};

// Flags that shape a simulation: they mean nothing to stored snapshots.
constexpr std::string_view kSimulationFlags[] = {
    "--dim",         "--particles", "--density",     "--restitution", "--cutoff",
    "--speed",       "--seed",      "--realisation", "--t-max",       "--initial",
    "--temperature", "--lattice",   "--kick-site",   "--frames",      "--frame-spacing",
    "--t-start",     "--medium"};

// Writes DIR/movie.toml and returns its text.
std::string write_movie_toml(const std::filesystem::path& dir, const CLI::App& sub, bool stored) {
  const std::string text =
      "# grainshock movie: every setting that shapes the movie.\n"
      "# Again: grainshock movie --config movie.toml --out NEW; "
      "continue: grainshock resume DIR\n" +
      settings_toml(sub, stored ? std::span(kSimulationFlags) : std::span<const std::string_view>(),
                    dir);
  write_file_atomic(dir / "movie.toml", text);
  return text;
}

struct MovieJob {
  PhysicsConfig physics;
  std::string out = "grainshock-movie";
  bool force = false;
  FrontMovieOptions movie;
  std::vector<std::string> files;
  double checkpoint_every = MovieCheckpoints{}.every;
};

// Every flag of `grainshock movie` into `job`.
void add_movie_flags(CLI::App& sub, MovieJob& job) {
  input_files(sub.add_option("snapshots", job.files,
                             "Snapshot files to draw instead of simulating, in order of their "
                             "Time; movie.toml names them relative to itself"));
  add_config_option(sub);
  add_physics_options(sub, job.physics);
  add_output_options(sub, job.out, job.force, job.movie.quiet);
  add_checkpoint_option(sub, job.checkpoint_every);
  sub.add_option("--frames", job.movie.frames, "Number of frames")->capture_default_str();
  sub.add_option("--frame-spacing", job.movie.spacing,
                 "Frame times: lin (t-max/N apart) or log (from --t-start to --t-max)")
      ->capture_default_str();
  sub.add_option("--t-start", job.movie.t_start, "Time of the first frame with --frame-spacing log")
      ->capture_default_str();
  sub.add_option("--codec", job.movie.movie.codec, "h264 (falls back to mpeg4), libx264 or mpeg4")
      ->capture_default_str();
  sub.add_option("--fps", job.movie.movie.fps, "Frames per second of the movie")
      ->capture_default_str();
  sub.add_option("--crf", job.movie.movie.crf,
                 "H.264 quality, 0 (lossless) to 51; 18 looks lossless")
      ->capture_default_str();
  sub.add_option("--keyint", job.movie.movie.keyint,
                 "Frames between key frames; a killed movie goes on from the last one")
      ->capture_default_str();
  sub.add_option("--width", job.movie.movie.width, "Frame width in pixels")->capture_default_str();
  sub.add_option("--height", job.movie.movie.height, "Frame height in pixels")
      ->capture_default_str();
  sub.add_option("--camera", job.movie.camera,
                 "follow: the front, smoothly; fixed: the whole periodic box")
      ->capture_default_str();
  sub.add_option("--color-by", job.movie.colour_by,
                 "auto (scaled-speed for a kick, else speed), scaled-speed, speed, "
                 "scaled-radial-velocity, radial-velocity, first-collision, none (one colour), "
                 "or (stored snapshots) a numeric per-particle column of the files")
      ->capture_default_str();
  sub.add_option("--scale", job.movie.scale,
                 "Colour scale lin, log or auto (log for speed and first-collision, else lin)")
      ->capture_default_str();
  sub.add_option("--range", job.movie.range,
                 "Fixed colour range MIN MAX (default: the scaled fields' fixed range, else "
                 "spans every frame's 1-99 percentiles)")
      ->expected(2);
  sub.add_flag("--range-per-frame", job.movie.range_per_frame,
               "Each frame its own 1-99 percentile range");
  sub.add_flag("--inset", job.movie.inset,
               "A profile of density and mean speed against distance, bottom left");
  sub.add_option("--colormap", job.movie.colormap, "Colormap name")->capture_default_str();
  sub.add_option("--background", job.movie.background, "light or dark")->capture_default_str();
  sub.add_flag("--show-inactive", job.movie.show_inactive,
               "Also draw the particles at rest, in a faint neutral colour");
  sub.add_option("--slab", job.movie.slab,
                 "3D: keep a slab this thick through the centre, facing the camera (0: all). "
                 "Default: 6 for a kick (its shell is hollow), 0 for others' files, as OVITO "
                 "draws them")
      ->option_text("FLOAT (6 for a kick, else 0)");
  sub.add_flag("--clip", job.movie.clip,
               "3D: cut away the half nearer than the plane through the front's centre");
  sub.add_option("--azimuth", job.movie.azimuth, "3D: camera azimuth about z, degrees")
      ->capture_default_str();
  sub.add_option("--orbit", job.movie.orbit,
                 "3D: total azimuth the camera turns over the movie, degrees")
      ->capture_default_str();
  sub.add_option("--elevation", job.movie.elevation, "3D: camera elevation, degrees")
      ->capture_default_str();
  sub.add_flag("--keep-frames", job.movie.keep_frames,
               "Also write every frame as DIR/frames/*.png");
  sub.add_option("--dt", job.movie.read.dt,
                 "Stored snapshots: time step of files that give steps but no time (LAMMPS dumps "
                 "without ITEM: TIME, HOOMD GSD): time = step x DT; without it frames are "
                 "labelled by step")
      ->check(positive());
  sub.add_flag("--unwrap", job.movie.read.unwrap,
               "Stored LAMMPS dumps and others' GSD: unwrapped positions (xu, or x plus the image "
               "flags) instead of the positions in the cell, which OVITO draws by default");
  sub.add_option("--gl", job.movie.backend, "OpenGL context: auto, osmesa or egl")
      ->capture_default_str();
}

}  // namespace

void add_movie_command(CLI::App& app) {
  auto opt = std::make_shared<MovieJob>();
  auto* sub = app.add_subcommand(
      "movie",
      "Simulate one realisation and stream it into DIR/movie.mp4, or draw stored snapshots");
  add_movie_flags(*sub, *opt);
  sub->footer(
      "A simulated movie keeps a checkpoint in DIR (at the start, every --checkpoint-every "
      "seconds and on Ctrl-C) and writes its movie in parts, cut at each checkpoint, in "
      "DIR/movie.parts; `grainshock resume DIR` goes on after a stop or a kill and joins the "
      "parts into one movie.mp4 without encoding again. A stopped movie also leaves a playable "
      "movie.mp4 of its frames so far.");
  sub->callback([opt, sub] {
    opt->movie.progress = terminal_progress(opt->movie.quiet);
    opt->movie.messages = terminal_messages();
    if (!opt->files.empty()) {
      for (std::string_view name : kSimulationFlags)
        if (sub->get_option(std::string(name))->count() > 0)
          throw UsageError(std::string(name) +
                           " sets up a simulation; a movie of stored snapshots takes none");
      if (sub->get_option("--checkpoint-every")->count() > 0)
        throw UsageError(
            "--checkpoint-every: a movie of stored snapshots keeps no checkpoint (it is made "
            "again from its files)");
      // Every file is opened and the first frame read (and checked) before the folder is made.
      StoredMovie m = prepare_stored_movie(opt->files, opt->movie);
      std::error_code ec;
      const bool existed = std::filesystem::exists(opt->out, ec);
      const auto dir = prepare_output_dir(opt->out, opt->force, kMovieOutputs);
      write_movie_toml(dir, *sub, true);
      FrontMovieResult r;
      try {
        r = write_stored_movie(m, dir);
      } catch (...) {
        // A file that fails now (changed since the first pass) leaves no movie.toml, and no
        // folder if this command made it.
        std::filesystem::remove(dir / "movie.toml", ec);
        if (!existed) std::filesystem::remove(dir, ec);
        throw;
      }
      if (r.stopped) std::exit(128 + std::max(0, stop_signal()));
      return;
    }
    if (opt->movie.read.dt > 0 || opt->movie.read.unwrap)
      throw UsageError("--dt and --unwrap read stored snapshots; a simulated movie has none");
    apply_medium_default(*sub, opt->physics);
    // Everything typed is checked before the folder is made or anything runs.
    validate(opt->physics);
    check_front_movie(opt->physics, opt->movie);
    const auto dir = prepare_output_dir(opt->out, opt->force, kMovieOutputs);
    lock_output_dir(dir);
    remove_leftovers(dir);
    const MovieCheckpoints checkpoints{write_movie_toml(dir, *sub, false), opt->checkpoint_every};
    const FrontMovieResult r = write_front_movie(opt->physics, opt->movie, dir, &checkpoints);
    if (r.stopped) throw Exit{kExitInterrupted};
  });
}

bool is_movie_folder(const std::filesystem::path& dir) {
  return std::filesystem::exists(dir / "movie.toml");
}

int resume_movie(const std::filesystem::path& dir, bool quiet, double checkpoint_every) {
  const auto file = dir / "movie.toml";
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  CLI::App app;
  auto* sub = app.add_subcommand("movie");
  MovieJob job;
  add_movie_flags(*sub, job);
  parse_settings_file(app, "movie", file);
  if (!job.files.empty())
    throw UserError("'" + dir.string() +
                    "' holds a movie of stored snapshots, which keeps no checkpoint; make it "
                    "again with: grainshock movie --config " +
                    file.string() + " --out " + dir.string() + " --force");
  validate(job.physics);
  job.movie.quiet = quiet;
  job.movie.progress = terminal_progress(quiet);
  job.movie.messages = terminal_messages();
  lock_output_dir(dir);
  remove_leftovers(dir);
  const MovieCheckpoints checkpoints{text.str(), checkpoint_every};
  const FrontMovieResult r = resume_front_movie(job.physics, job.movie, dir, checkpoints);
  return r.stopped ? kExitInterrupted : kExitSuccess;
}

}  // namespace gs::app
