// grainshock render: snapshot file(s) -> one PNG. Several snapshots make the Fig. 1(a) overlay.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "apps/cli.h"
#include "apps/commands.h"
#include "io/atomic_file.h"
#include "io/snapshot_file.h"
#include "render/colormap.h"
#include "render/field.h"
#include "render/gltf.h"
#include "render/png.h"
#include "render/render_choices.h"
#include "render/renderer.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::app {

void add_render_command(CLI::App& app) {
  struct Options : render::RenderChoices {
    std::vector<std::string> inputs;
    std::string out;
    int compression = 1;
    long long frame = -1;  // the last, as grainshock.read, ASE and OVITO take it
    ReadOptions read;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand("render", "Draw snapshot file(s) into a PNG");
  add_config_option(*sub);
  sub->add_option("snapshots", opt->inputs,
                  "Snapshot file(s): extended XYZ, LAMMPS dump or GSD; several make one picture, "
                  "one colour per time")
      ->required();
  sub->add_option("--frame", opt->frame,
                  "Frame of a multi-frame file, counted from 0; negative from the end (-1: the "
                  "last), as ASE counts. Default: the last, as Python's grainshock.read")
      ->capture_default_str();
  sub->add_option("--dim", opt->read.dim, "Dimension of the files, if not the one they state")
      ->check(CLI::Range(1, 3));
  sub->add_option("--dt", opt->read.dt,
                  "Time step of files that give steps but no time (LAMMPS dumps without ITEM: "
                  "TIME, HOOMD GSD): time = step x DT; without it such frames are labelled by step")
      ->check(positive());
  sub->add_flag("--unwrap", opt->read.unwrap,
                "LAMMPS dumps and others' GSD: unwrapped positions (xu, or x plus the image "
                "flags) instead of the positions in the cell, which OVITO draws by default");
  sub->add_option("--out", opt->out,
                  "PNG file to write (NAME.png), or NAME.glb: the 3D scene as glTF 2.0 (one "
                  "snapshot; spheres instanced, each with its PNG colour)")
      ->required()
      ->check(CLI::Validator(
          [](std::string& text) {
            const bool glb = text.size() > 4 && text.compare(text.size() - 4, 4, ".glb") == 0;
            if (glb || png_name()(text).empty()) return std::string();
            return "'" + text + "' ends in neither .png (a picture) nor .glb (a 3D scene)";
          },
          "FILE.png|FILE.glb", "picture or scene name"));
  sub->add_option("--width", opt->view.width, "Picture width in pixels")->capture_default_str();
  sub->add_option("--height", opt->view.height, "Picture height in pixels")->capture_default_str();
  std::string maps;
  for (const auto& n : render::Colormap::names()) maps += (maps.empty() ? "" : ", ") + n;
  sub->add_option("--colormap", opt->colormap, "One of " + maps)->capture_default_str();
  sub->add_option("--color-by", opt->colour_by,
                  "auto (scaled-speed for a kick, else speed; type for a file without velocities), "
                  "scaled-speed, speed, scaled-radial-velocity, radial-velocity, first-collision, "
                  "type (LAMMPS type, GSD typeid, XYZ species: a colour-blind-safe palette and a "
                  "legend), none (one colour), or the name of a numeric per-particle column of "
                  "the file")
      ->capture_default_str();
  sub->add_option("--range", opt->range,
                  "Fixed colour range MIN MAX (default: the scaled fields' fixed range, else "
                  "percentiles)")
      ->expected(2);
  sub->add_flag("--range-per-frame", opt->style.range_per_frame,
                "Percentiles of this snapshot even for a scaled field");
  sub->add_option("--percentiles", opt->percentiles,
                  "Automatic range from these percentiles of the shown values")
      ->expected(2)
      ->default_str("1 99");
  sub->add_option("--scale", opt->scale,
                  "Colour scale lin, log or auto (log for speed and first-collision, else lin)")
      ->capture_default_str();
  sub->add_flag("--inset", opt->inset,
                "A profile of density and mean speed against distance, bottom left (the default "
                "for a run's own snapshots, whose --png frames have it)");
  sub->add_flag("--no-inset", opt->no_inset, "Leave out the inset, also for a run's snapshots");
  sub->add_flag("--show-inactive", opt->style.show_inactive,
                "Also draw particles that never collided, in a faint neutral colour");
  sub->add_option("--background", opt->background, "light or dark")->capture_default_str();
  sub->add_option("--framing", opt->framing,
                  "fit: the active particles with a margin; box: the whole periodic box")
      ->capture_default_str();
  sub->add_option("--centre,--center", opt->centre, "Explicit picture centre X Y [Z]")
      ->expected(2, 3);
  sub->add_option("--zoom", opt->view.zoom, "Magnification relative to the framing")
      ->capture_default_str();
  sub->add_option("--azimuth", opt->view.azimuth, "3D: camera azimuth about z, degrees")
      ->capture_default_str();
  sub->add_option("--elevation", opt->view.elevation, "3D: camera elevation, degrees")
      ->capture_default_str();
  sub->add_option("--distance", opt->view.distance, "3D: camera distance (0: fitted)")
      ->capture_default_str();
  sub->add_option("--fov", opt->view.fov, "3D: vertical field of view, degrees")
      ->capture_default_str();
  sub->add_option("--slab", opt->slab,
                  "3D: keep a slab this thick through the centre, facing the camera (0: all). "
                  "Default: 6 for a kick's snapshot (its shell is hollow), 0 for others' files, "
                  "as OVITO draws them; what a slab leaves out is said once");
  sub->add_flag("--no-colorbar", opt->no_colorbar, "Leave out the colour bar");
  sub->add_flag("--no-time", opt->no_time, "Leave out the time label");
  sub->add_flag("--no-legend", opt->no_legend, "Leave out the legend of the multi-time overlay");
  sub->add_flag("--clip", opt->view.clip,
                "3D: cut away the half nearer than the plane through the centre facing the camera");
  sub->add_flag("--scale-bar", opt->style.scale_bar,
                "A scale bar in particle diameters (3D: at the centre's distance)");
  sub->add_option("--msaa", opt->style.msaa, "3D: samples per pixel, 0 (none) to 64")
      ->capture_default_str();
  sub->add_option("--font", opt->style.font, "TrueType font for the annotations")
      ->capture_default_str();
  sub->add_option("--gl", opt->backend, "OpenGL context: auto, osmesa or egl")
      ->capture_default_str();
  sub->add_option("--compression", opt->compression, "PNG compression level 0-9")
      ->capture_default_str()
      ->check(CLI::Range(0, 9));

  sub->callback([opt] {
    auto& o = *opt;
    // Everything the user typed is checked before any file is read or GL context made.
    const auto backend = render::settle_choices(o);
    // Reading a large file takes seconds: a stop between (or inside, io/) exits 130, no PNG.
    install_stop_handlers();
    std::vector<Snapshot> snaps;
    snaps.reserve(o.inputs.size());
    for (const auto& path : o.inputs) {
      snaps.push_back(read_snapshot(path, o.read, o.frame));
      throw_if_stopped();
    }
    std::vector<const Snapshot*> ptrs;
    for (const auto& s : snaps) ptrs.push_back(&s);
    render::settle_for_snapshots(o, ptrs, o.inputs.front());
    if (!o.note.empty())
      std::fprintf(stderr, "grainshock: %s: %s\n", o.inputs.front().c_str(), o.note.c_str());
    // What the readers assumed where the files say nothing, each sentence once.
    std::set<std::string> said;
    for (std::size_t k = 0; k < snaps.size(); ++k)
      for (const auto& note : snaps[k].notes)
        if (said.insert(note).second)
          std::fprintf(stderr, "grainshock: %s: %s\n", o.inputs[k].c_str(), note.c_str());

    if (o.out.size() > 4 && o.out.compare(o.out.size() - 4, 4, ".glb") == 0) {
      if (snaps.size() != 1) throw UsageError("--out " + o.out + ": a scene holds one snapshot");
      write_file_atomic(o.out, render::glb_scene(snaps.front(), o.style));
      return;
    }
    render::Renderer renderer(backend);
    const render::Image img = renderer.render(ptrs, o.style, o.view);
    throw_if_stopped();
    // Below a pixel of radius one particle is a speck that a golden comparison cannot see move
    // (a 20000-disc box drawn whole at 640x480, 0.73 px, hid 12 of 12 one-disc moves).
    if (snaps.size() == 1)
      if (const std::string cut = render::cut_note(o.style, snaps.front(), renderer.last().camera);
          !cut.empty())
        std::fprintf(stderr, "grainshock: %s: %s\n", o.inputs.front().c_str(), cut.c_str());
    const double r_px = renderer.last().disc_radius_px;
    if (r_px > 0 && r_px < 1)
      std::fprintf(stderr,
                   "grainshock: warning: discs of %.2g px radius: one particle is below what the "
                   "picture or `grainshock compare` can show (zoom in or draw it larger)\n",
                   r_px);
    render::write_png(o.out, img, render::png_text(ptrs, r_px), o.compression);
  });
}

}  // namespace gs::app
