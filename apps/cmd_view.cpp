// grainshock view: folders or snapshot files -> one self-contained HTML page.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>

#include "apps/cli.h"
#include "apps/commands.h"
#include "jobs/view_job.h"
#include "render/colormap.h"

namespace gs::app {

void add_view_command(CLI::App& app) {
  auto opt = std::make_shared<jobs::ViewOptions>();
  auto* sub = app.add_subcommand(
      "view",
      "Write one self-contained HTML page (offline) of a run, ensemble, figures or movie "
      "folder, or of snapshot files: every frame with a time slider, the plots, the report");
  sub->add_option("inputs", opt->inputs,
                  "Folders (run, ensemble, figures, movie, or any folder of snapshot files) or "
                  "snapshot files (extended XYZ, LAMMPS dump, GSD; several frames each too)")
      ->required();
  sub->add_option("--out", opt->out, "The page to write (NAME.html)")->required();
  sub->add_option("--max-mb", opt->max_mb,
                  "Size budget of the page in MB: frames beyond it are left out evenly in time")
      ->capture_default_str();
  sub->add_option("--dim", opt->read.dim, "Dimension of the files, if not the one they state")
      ->check(CLI::Range(1, 3));
  sub->add_option("--dt", opt->read.dt,
                  "Time step of files that give steps but no time: time = step x DT")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--unwrap", opt->read.unwrap,
                "LAMMPS dumps and others' GSD: unwrapped positions instead of those in the cell");
  auto& c = opt->choices;
  std::string maps;
  for (const auto& n : render::Colormap::names()) maps += (maps.empty() ? "" : ", ") + n;
  sub->add_option("--colormap", c.colormap, "One of " + maps)->capture_default_str();
  sub->add_option("--color-by", c.colour_by,
                  "As for render: auto, scaled-speed, speed, scaled-radial-velocity, "
                  "radial-velocity, first-collision, none, or a numeric column of the file")
      ->capture_default_str();
  sub->add_option("--range", c.range, "Fixed colour range MIN MAX")->expected(2);
  sub->add_flag("--range-per-frame", c.style.range_per_frame,
                "Percentiles of each frame even for a scaled field");
  sub->add_option("--percentiles", c.percentiles, "Automatic range from these percentiles")
      ->expected(2)
      ->default_str("1 99");
  sub->add_option("--scale", c.scale, "Colour scale lin, log or auto")->capture_default_str();
  sub->add_option("--background", c.background, "light or dark")->capture_default_str();
  sub->add_flag("--show-inactive", c.style.show_inactive,
                "Also the particles that never collided, in a faint grey (a larger page)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing but errors");
  sub->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    const jobs::ViewResult r = jobs::write_view(*opt);
    if (opt->quiet) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "grainshock: %s: %.3g MB, %zu frames, written in %.3g s\n",
                 opt->out.c_str(), r.bytes / 1e6, r.frames, s);
    if (!r.dropped.empty()) {
      std::fprintf(stderr, "grainshock: %zu frames left out for --max-mb %g:", r.dropped.size(),
                   opt->max_mb);
      for (const auto& d : r.dropped) std::fprintf(stderr, " [%s]", d.c_str());
      std::fprintf(stderr, "\n");
    }
  });
}

}  // namespace gs::app
