#include "apps/run_flags.h"

#include <string>
#include <vector>

#include "apps/cli.h"
#include "io/snapshot_writer.h"
#include "io/trajectory.h"
#include "sim/error.h"

namespace gs::app {

using namespace jobs;

void add_run_flags(CLI::App& sub, RunOptions& o) {
  add_config_option(sub);
  add_physics_options(sub, o.plan.physics);
  sub.add_option("--per-decade", o.plan.per_decade, "Samples per decade of the logarithmic grid")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub.add_option("--sample-every", o.plan.sample_every,
                 "Also sample every DT (linear grid; 0: none)")
      ->check(non_negative())
      ->capture_default_str();
  sub.add_option("--snapshot-times", o.plan.snapshot_times, "Write snapshots at these times")
      ->delimiter(',');
  sub.add_option_function<std::string>(
         "--snapshot-format",
         [&o](const std::string& v) {
           if (v != "xyz" && v != "ovito-xyz" && v != "gsd")
             throw CLI::ValidationError("--snapshot-format",
                                        "'" + v + "' is not xyz, ovito-xyz or gsd");
           o.plan.snapshots.format = parse_snapshot_format(v);
         },
         "xyz: extended XYZ for ASE (OVITO shows 2D as a thin layer); ovito-xyz: 2D as OVITO's "
         "2D form (pos:R:2, which ASE cannot read); gsd: HOOMD GSD, binary, 32-bit floats")
      ->option_text("xyz|ovito-xyz|gsd (xyz)");
  sub.add_option_function<std::string>(
         "--snapshot-particles",
         [&o](const std::string& v) {
           if (v != "all" && v != "active")
             throw CLI::ValidationError("--snapshot-particles", "'" + v + "' is not all or active");
           parse_snapshot_particles(v, o.plan.snapshots);
         },
         "all, or active: only the particles that have collided (pictures and fronts, not "
         "packing, which needs the gas at rest)")
      ->option_text("all|active (all)");
  sub.add_option_function<std::string>(
         "--trajectory",
         [&o](const std::string& v) {
           if (v.empty()) return o.trajectory.clear();  // none, as run.toml says when unset
           const bool plain = !v.empty() && v[0] != '.' &&
                              v.find_first_not_of(
                                  "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                  "0123456789._-") == std::string::npos;
           if (!plain)
             throw CLI::ValidationError(
                 "--trajectory",
                 "'" + v + "' is not a file name in the run folder (letters, digits, . _ -)");
           trajectory_format(v);  // UserError for another extension
           o.trajectory = v;
         },
         "Also write every snapshot time into DIR/FILE, one trajectory that OVITO and ASE open as "
         "a sequence: FILE.gsd (HOOMD GSD) or FILE.xyz (extended XYZ)")
      ->option_text("FILE.gsd|FILE.xyz");
  sub.add_flag("--png", o.png,
               "Draw every snapshot into frames/*.png (colour = v / v_rms for a kick, speed for a "
               "thermal gas) and overlay them all");
  sub.add_flag("--compare-elastic", o.compare_elastic,
               "Also run the same kick with r = 1 to half of t-max, like the paper's Fig. 1(b)");
  sub.add_flag("--movie", o.movie,
               "Also write movie.mp4 of the front (the defaults of `grainshock movie`)");
  sub.add_flag("--movie-inset", o.movie_inset,
               "With --movie: the profile across the band in a corner (as in the Fig. 1 job)");
  sub.add_option("--width", o.width, "Width of the pictures in pixels")->capture_default_str();
  sub.add_option("--height", o.height, "Height of the pictures in pixels")->capture_default_str();
}

bool apply_fig1_rule(const CLI::App& sub, RunOptions& o) {
  for (const char* name : {"--t-max", "--snapshot-times", "--png", "--compare-elastic", "--movie"})
    if (sub.get_option(name)->count() > 0) return false;
  use_fig1_job(o);
  return true;
}

RunOptions read_run_file(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw UserError("'" + file.parent_path().string() + "' is not a run folder (no run.toml)");
  CLI::App app;
  auto* sub = app.add_subcommand("run");
  RunOptions o;
  add_run_flags(*sub, o);
  parse_settings_file(app, "run", file);
  apply_fig1_rule(*sub, o);
  // No --medium default here: run.toml states the medium, and one written before the medium
  // existed has no key and ran in the box, PhysicsConfig's own default.
  return o;
}

}  // namespace gs::app
