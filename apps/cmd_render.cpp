// grainshock render: snapshot file(s) -> one PNG. Several snapshots make the Fig. 1(a) overlay.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <set>

#include "apps/cli.h"
#include "apps/commands.h"
#include "io/snapshot_file.h"
#include "render/colormap.h"
#include "render/field.h"
#include "render/png.h"
#include "render/renderer.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs::app {

void add_render_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> inputs;
    std::string out;
    render::Style style;
    render::View view;
    std::vector<double> range, percentiles, centre;
    std::string colormap = "magma", colour_by = "auto", background = "light", scale = "auto";
    std::string framing = "fit", backend = "auto";
    bool no_colorbar = false, no_time = false, no_legend = false;
    bool inset = false, no_inset = false;
    int compression = 1;
    std::size_t frame = 0;
    ReadOptions read;
  };
  auto opt = std::make_shared<Options>();
  auto* sub = app.add_subcommand("render", "Draw snapshot file(s) into a PNG");
  add_config_option(*sub);
  sub->add_option("snapshots", opt->inputs,
                  "Snapshot file(s): extended XYZ, LAMMPS dump or GSD; several make one picture, "
                  "one colour per time")
      ->required();
  sub->add_option("--frame", opt->frame, "Frame of a multi-frame file, counted from 0")
      ->capture_default_str();
  sub->add_option("--dim", opt->read.dim, "Dimension of the files, if not the one they state")
      ->check(CLI::Range(1, 3));
  sub->add_option("--dt", opt->read.dt,
                  "Time step of files that give steps but no time (LAMMPS dumps without ITEM: "
                  "TIME, HOOMD GSD): time = step x DT; without it such frames are labelled by step")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--unwrap", opt->read.unwrap,
                "LAMMPS dumps and others' GSD: unwrapped positions (xu, or x plus the image "
                "flags) instead of the positions in the cell, which OVITO draws by default");
  sub->add_option("--out", opt->out, "PNG file to write")->required();
  sub->add_option("--width", opt->view.width, "Picture width in pixels")->capture_default_str();
  sub->add_option("--height", opt->view.height, "Picture height in pixels")->capture_default_str();
  std::string maps;
  for (const auto& n : render::Colormap::names()) maps += (maps.empty() ? "" : ", ") + n;
  sub->add_option("--colormap", opt->colormap, "One of " + maps)->capture_default_str();
  sub->add_option("--color-by", opt->colour_by,
                  "auto (scaled-speed for a kick, else speed), scaled-speed, speed, "
                  "scaled-radial-velocity, radial-velocity, first-collision, none (one colour), "
                  "or the name of a numeric per-particle column of the file")
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
  // The default of `movie` and of a run's pictures too: a kick's shell is hollow, so drawn whole
  // it shows only its outer skin; the slab shows the band itself.
  opt->view.slab = 6;
  sub->add_option("--slab", opt->view.slab,
                  "3D: keep a slab this thick through the centre, facing the camera (0: all)")
      ->capture_default_str();
  sub->add_flag("--no-colorbar", opt->no_colorbar, "Leave out the colour bar");
  sub->add_flag("--no-time", opt->no_time, "Leave out the time label");
  sub->add_flag("--no-legend", opt->no_legend, "Leave out the legend of the multi-time overlay");
  sub->add_flag("--clip", opt->view.clip,
                "3D: cut away the half nearer than the plane through the centre facing the camera");
  sub->add_flag("--scale-bar", opt->style.scale_bar,
                "A scale bar in particle diameters (3D: at the centre's distance)");
  sub->add_option("--msaa", opt->style.msaa, "3D: samples per pixel (0 for none)")
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
    auto& st = o.style;
    st.colormap = o.colormap;
    // An unknown field is reported once the snapshot is read, with the fields it has.
    for (render::Field f : render::all_fields())
      if (o.colour_by == render::field_name(f)) st.field = f;
    st.background = render::parse_background(o.background);
    st.scale = render::parse_scale(o.scale, st.field);
    if (!o.range.empty()) st.range = std::pair{o.range[0], o.range[1]};
    if (!o.percentiles.empty())
      st.percentile_low = o.percentiles[0], st.percentile_high = o.percentiles[1];
    st.colorbar = !o.no_colorbar;
    st.time_label = !o.no_time;
    st.legend = !o.no_legend;
    if (o.framing == "fit")
      o.view.framing = render::Framing::Fit;
    else if (o.framing == "box")
      o.view.framing = render::Framing::Box;
    else
      throw UserError("unknown --framing '" + o.framing + "' (use fit or box)");
    if (!o.centre.empty())
      o.view.centre =
          Eigen::Vector3d(o.centre[0], o.centre[1], o.centre.size() > 2 ? o.centre[2] : 0);
    if (!(o.view.zoom > 0)) throw UserError("--zoom must be positive");
    if (!(o.view.fov > 0 && o.view.fov < 180)) throw UserError("--fov must be between 0 and 180");
    if (o.view.slab < 0 || o.view.distance < 0)
      throw UserError("--slab and --distance must be >= 0");
    if (o.inset && o.no_inset) throw UserError("--inset and --no-inset exclude each other");
    // Everything the user typed is checked before any file is read or GL context made.
    render::check_size(o.view.width, o.view.height, 16384);
    render::check_style(st);
    const auto backend = render::parse_backend(o.backend);

    std::vector<Snapshot> snaps;
    snaps.reserve(o.inputs.size());
    for (const auto& path : o.inputs) snaps.push_back(read_snapshot(path, o.read, o.frame));
    // A run's own snapshot (it names its seed) is drawn as the run drew it: with the inset.
    st.inset = o.inset || (!o.no_inset && snaps.front().info.seed.has_value());
    // One snapshot is coloured by a field (several by time): the first file read decides what
    // "auto" means, and names what it lacks.
    if (snaps.size() == 1) {
      st.field = render::choose_field(o.colour_by, snaps.front(), o.inputs.front());
      if (st.field == render::Field::Column) st.column = o.colour_by;
      st.scale = render::parse_scale(o.scale, st.field);
      render::check_style(st);
    }
    // What the readers assumed where the files say nothing, each sentence once.
    std::set<std::string> said;
    for (std::size_t k = 0; k < snaps.size(); ++k)
      for (const auto& note : snaps[k].notes)
        if (said.insert(note).second)
          std::fprintf(stderr, "grainshock: %s: %s\n", o.inputs[k].c_str(), note.c_str());
    std::vector<const Snapshot*> ptrs;
    for (const auto& s : snaps) ptrs.push_back(&s);

    render::Renderer renderer(backend);
    const render::Image img = renderer.render(ptrs, st, o.view);
    auto text = render::png_text(snaps.front().info, snaps.front().size());
    if (snaps.size() > 1) {
      std::string times;
      for (const auto& s : snaps) times += (times.empty() ? "" : ",") + format_double(s.info.time);
      for (auto& [k, v] : text)
        if (k == "Time") v = times;
    }
    render::write_png(o.out, img, text, o.compression);
  });
}

}  // namespace gs::app
