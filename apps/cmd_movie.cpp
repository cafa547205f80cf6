// `grainshock movie`: runs one realisation and streams frames of the spreading front into
// DIR/movie.mp4 beside movie.toml (every setting, for --config), or, given snapshot files, draws
// them in order of their time into DIR/movie.mp4 (see apps/front_movie.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string_view>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "apps/front_movie.h"
#include "sim/config.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {
namespace {

// What a movie writes into its folder; --force removes these first, so that a folder never
// mixes two movies.
constexpr const char* kMovieOutputs[] = {"movie.toml", "movie.mp4", "frames"};

// Flags that shape a simulation: they mean nothing to stored snapshots.
constexpr std::string_view kSimulationFlags[] = {
    "--dim",       "--particles", "--density",       "--restitution",
    "--cutoff",    "--speed",     "--seed",          "--realisation",
    "--t-max",     "--initial",   "--temperature",   "--lattice",
    "--kick-site", "--frames",    "--frame-spacing", "--t-start"};

void write_movie_toml(const std::filesystem::path& dir, const CLI::App& sub, bool stored) {
  write_file_atomic(dir / "movie.toml",
                    "# grainshock movie: every setting that shapes the movie.\n"
                    "# Again: grainshock movie --config movie.toml --out NEW\n" +
                        settings_toml(sub, stored ? std::span(kSimulationFlags)
                                                  : std::span<const std::string_view>()));
}

}  // namespace

void add_movie_command(CLI::App& app) {
  struct Options {
    PhysicsConfig physics;
    std::string out = "grainshock-movie";
    bool force = false;
    FrontMovieOptions movie;
    std::vector<std::string> files;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand(
      "movie",
      "Simulate one realisation and stream it into DIR/movie.mp4, or draw stored snapshots");
  sub->add_option("snapshots", opt->files,
                  "Snapshot files to draw instead of simulating, in order of their Time");
  add_config_option(*sub);
  add_physics_options(*sub, opt->physics);
  add_output_options(*sub, opt->out, opt->force, opt->movie.quiet);
  sub->add_option("--frames", opt->movie.frames, "Number of frames")->capture_default_str();
  sub->add_option("--frame-spacing", opt->movie.spacing,
                  "Frame times: lin (t-max/N apart) or log (from --t-start to --t-max)")
      ->capture_default_str();
  sub->add_option("--t-start", opt->movie.t_start,
                  "Time of the first frame with --frame-spacing log")
      ->capture_default_str();
  sub->add_option("--codec", opt->movie.movie.codec, "h264 (falls back to mpeg4), libx264 or mpeg4")
      ->capture_default_str();
  sub->add_option("--fps", opt->movie.movie.fps, "Frames per second of the movie")
      ->capture_default_str();
  sub->add_option("--crf", opt->movie.movie.crf,
                  "H.264 quality, 0 (lossless) to 51; 18 looks lossless")
      ->capture_default_str();
  sub->add_option("--width", opt->movie.movie.width, "Frame width in pixels")
      ->capture_default_str();
  sub->add_option("--height", opt->movie.movie.height, "Frame height in pixels")
      ->capture_default_str();
  sub->add_option("--camera", opt->movie.camera,
                  "follow: the front, smoothly; fixed: the whole periodic box")
      ->capture_default_str();
  sub->add_option("--color-by", opt->movie.colour_by,
                  "auto (scaled-speed for a kick, else speed), scaled-speed, speed, "
                  "scaled-radial-velocity, radial-velocity, first-collision, none (one colour), "
                  "or (stored snapshots) a numeric per-particle column of the files")
      ->capture_default_str();
  sub->add_option("--scale", opt->movie.scale,
                  "Colour scale lin, log or auto (log for speed and first-collision, else lin)")
      ->capture_default_str();
  sub->add_option("--range", opt->movie.range,
                  "Fixed colour range MIN MAX (default: the scaled fields' fixed range, else "
                  "spans every frame's 1-99 percentiles)")
      ->expected(2);
  sub->add_flag("--range-per-frame", opt->movie.range_per_frame,
                "Each frame its own 1-99 percentile range");
  sub->add_flag("--inset", opt->movie.inset,
                "A profile of density and mean speed against distance, bottom left");
  sub->add_option("--colormap", opt->movie.colormap, "Colormap name")->capture_default_str();
  sub->add_option("--background", opt->movie.background, "light or dark")->capture_default_str();
  sub->add_flag("--show-inactive", opt->movie.show_inactive,
                "Also draw the particles at rest, in a faint neutral colour");
  sub->add_option("--slab", opt->movie.slab,
                  "3D: keep a slab this thick through the centre, facing the camera (0: all)")
      ->capture_default_str();
  sub->add_flag("--clip", opt->movie.clip,
                "3D: cut away the half nearer than the plane through the front's centre");
  sub->add_option("--azimuth", opt->movie.azimuth, "3D: camera azimuth about z, degrees")
      ->capture_default_str();
  sub->add_option("--orbit", opt->movie.orbit,
                  "3D: total azimuth the camera turns over the movie, degrees")
      ->capture_default_str();
  sub->add_option("--elevation", opt->movie.elevation, "3D: camera elevation, degrees")
      ->capture_default_str();
  sub->add_flag("--keep-frames", opt->movie.keep_frames,
                "Also write every frame as DIR/frames/*.png");
  sub->add_option("--gl", opt->movie.backend, "OpenGL context: auto, osmesa or egl")
      ->capture_default_str();
  sub->callback([opt, sub] {
    if (!opt->files.empty()) {
      for (std::string_view name : kSimulationFlags)
        if (sub->get_option(std::string(name))->count() > 0)
          throw UserError(std::string(name) +
                          " sets up a simulation; a movie of stored snapshots takes none");
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
    // Everything typed is checked before the folder is made or anything runs.
    validate(opt->physics);
    check_front_movie(opt->physics, opt->movie);
    const auto dir = prepare_output_dir(opt->out, opt->force, kMovieOutputs);
    write_movie_toml(dir, *sub, false);
    const FrontMovieResult r = write_front_movie(opt->physics, opt->movie, dir);
    if (r.stopped) throw Exit{kExitInterrupted};
  });
}

}  // namespace gs::app
