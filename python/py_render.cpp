// grainshock.render, grainshock.Image and grainshock.compare: the renderer (render/renderer.h)
// with the choices of `grainshock render` (render/render_choices.h), and the golden-image rule
// (render/image_compare.h). One GL context per backend is made on first use and kept for the
// life of the process, as a movie keeps its one.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "python/py_image.h"
#include "python/py_module.h"
#include "render/image_compare.h"
#include "render/render_choices.h"
#include "render/renderer.h"
#include "sim/error.h"

namespace gs::py {
namespace {

render::Renderer& renderer_for(render::Backend backend) {
  // Never destroyed: at interpreter exit the GL library may be torn down before static
  // destructors run (an exit-time crash seen once under ctest); the OS reclaims the context.
  static auto* renderers = new std::map<render::Backend, std::unique_ptr<render::Renderer>>;
  auto& r = (*renderers)[backend];
  if (!r) r = std::make_unique<render::Renderer>(backend);
  return *r;
}

std::vector<std::shared_ptr<Snapshot>> snapshots_of(const pb::object& obj) {
  std::vector<std::shared_ptr<Snapshot>> out;
  if (pb::isinstance<Snapshot>(obj)) {
    out.push_back(obj.cast<std::shared_ptr<Snapshot>>());
  } else {
    for (auto item : obj) out.push_back(item.cast<std::shared_ptr<Snapshot>>());
  }
  if (out.empty()) throw UserError("render: no snapshot given");
  return out;
}

PyImage render_snapshots(const pb::object& snapshots, const render::RenderChoices& given) {
  render::RenderChoices c = given;
  const auto backend = render::settle_choices(c);
  const auto owned = snapshots_of(snapshots);
  std::vector<const Snapshot*> ptrs;
  for (const auto& s : owned) ptrs.push_back(s.get());
  render::settle_for_snapshots(c, ptrs, "the snapshot");
  PyImage out;
  double disc_radius_px = 0;
  {
    pb::gil_scoped_release release;
    render::Renderer& r = renderer_for(backend);
    out.image = r.render(ptrs, c.style, c.view);
    disc_radius_px = r.last().disc_radius_px;
  }
  out.text = render::png_text(ptrs, disc_radius_px);
  return out;
}

PyImage image_from_array(const pb::array& array) {
  auto a = pb::array_t<std::uint8_t, pb::array::c_style | pb::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 ||
      a.shape(1) < 1)
    throw UserError("Image.from_array: the array must be (H, W, 3) or (H, W, 4) of uint8");
  const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
  const int k = static_cast<int>(a.shape(2));
  PyImage out;
  out.image = render::Image(w, h);
  auto r = a.unchecked<3>();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = out.image.pixel(x, y);
      for (int j = 0; j < 4; ++j) p[j] = j < k ? r(y, x, j) : 255;
    }
  return out;
}

// compare() takes Images, PNG paths or arrays alike.
render::Image image_of(const pb::object& obj) {
  if (pb::isinstance<PyImage>(obj)) return obj.cast<const PyImage&>().image;
  if (pb::isinstance<pb::str>(obj) || pb::hasattr(obj, "__fspath__"))
    return render::read_png(pb::str(obj).cast<std::string>());
  return image_from_array(obj.cast<pb::array>()).image;
}

struct Comparison {
  render::ImageComparison result;
  PyImage diff;
};

pb::object rgb_view(pb::object self, int channels) {
  const auto& img = self.cast<const PyImage&>().image;
  return view(img.rgba.data(), {img.height, img.width, channels}, {4L * img.width, 4, 1}, self);
}

}  // namespace

void bind_render(pb::module_& m) {
  pb::class_<PyImage>(m, "Image", "An RGBA picture, as rendered or read from a PNG")
      .def_property_readonly("array", [](pb::object self) { return rgb_view(self, 3); },
                             "(H, W, 3) uint8 read-only view, top row first")
      .def_property_readonly("rgba", [](pb::object self) { return rgb_view(self, 4); },
                             "(H, W, 4) uint8 read-only view")
      .def_property_readonly("width", [](const PyImage& i) { return i.image.width; })
      .def_property_readonly("height", [](const PyImage& i) { return i.image.height; })
      .def_property_readonly("text", [](const PyImage& i) { return i.text; },
                             "the PNG text chunks (key, value) written with it")
      .def(
          "save",
          [](const PyImage& i, const std::filesystem::path& path, int compression) {
            if (compression < 0 || compression > 9)
              throw UserError("--compression: " + std::to_string(compression) +
                              " not in range [0 - 9]");
            pb::gil_scoped_release release;
            render::write_png(path.string(), i.image, i.text, compression);
          },
          pb::arg("path"), pb::arg("compression") = 1,
          "Writes a PNG (atomically), with the text chunks `grainshock render` writes")
      .def(
          "_repr_png_",
          [](const PyImage& i) {
            const auto bytes = render::encode_png(i.image, i.text);
            return pb::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          },
          "PNG bytes, for Jupyter's display")
      .def_static(
          "load",
          [](const std::filesystem::path& path) {
            PyImage i;
            i.image = render::read_png(path.string());
            i.text = render::read_png_text(path.string());
            return i;
          },
          pb::arg("path"), "Reads a PNG file")
      .def_static("from_array", &image_from_array, pb::arg("array"),
                  "An Image of an (H, W, 3) or (H, W, 4) uint8 array (copied)")
      .def("__repr__", [](const PyImage& i) {
        return "<grainshock.Image " + std::to_string(i.image.width) + "x" +
               std::to_string(i.image.height) + ">";
      });

  const render::RenderChoices def;
  m.def(
      "_render",
      [](const pb::object& snapshots, const std::string& color_by, int width, int height,
         pb::object inset, const std::string& colormap, const std::string& background,
         const std::string& scale, std::vector<double> range, std::vector<double> percentiles,
         bool range_per_frame, const std::string& framing, std::vector<double> centre,
         double zoom, double azimuth, double elevation, double distance, double fov,
         std::optional<double> slab, bool clip, bool show_inactive, bool colorbar, bool time_label, bool legend,
         bool scale_bar, int msaa, const std::string& font, const std::string& backend) {
        render::RenderChoices c;
        c.colour_by = color_by;
        c.view.width = width;
        c.view.height = height;
        if (!inset.is_none()) (inset.cast<bool>() ? c.inset : c.no_inset) = true;
        c.colormap = colormap;
        c.background = background;
        c.scale = scale;
        if (!range.empty() && range.size() != 2)
          throw UserError("--range: give two numbers, MIN MAX");
        if (!percentiles.empty() && percentiles.size() != 2)
          throw UserError("--percentiles: give two numbers, LOW HIGH");
        c.range = range;
        c.percentiles = percentiles;
        c.style.range_per_frame = range_per_frame;
        c.framing = framing;
        if (!centre.empty() && centre.size() != 2 && centre.size() != 3)
          throw UserError("--centre: give 2 or 3 numbers");
        c.centre = centre;
        c.view.zoom = zoom;
        c.view.azimuth = azimuth;
        c.view.elevation = elevation;
        c.view.distance = distance;
        c.view.fov = fov;
        c.slab = slab;
        c.view.clip = clip;
        c.style.show_inactive = show_inactive;
        c.no_colorbar = !colorbar;
        c.no_time = !time_label;
        c.no_legend = !legend;
        c.style.scale_bar = scale_bar;
        c.style.msaa = msaa;
        c.style.font = font;
        c.backend = backend;
        return render_snapshots(snapshots, c);
      },
      pb::arg("snapshots"), pb::kw_only(), pb::arg("color_by") = def.colour_by,
      pb::arg("width") = def.view.width, pb::arg("height") = def.view.height,
      pb::arg("inset") = pb::none(), pb::arg("colormap") = def.colormap,
      pb::arg("background") = def.background, pb::arg("scale") = def.scale,
      pb::arg("range") = std::vector<double>{}, pb::arg("percentiles") = std::vector<double>{},
      pb::arg("range_per_frame") = false, pb::arg("framing") = def.framing,
      pb::arg("centre") = std::vector<double>{}, pb::arg("zoom") = def.view.zoom,
      pb::arg("azimuth") = def.view.azimuth, pb::arg("elevation") = def.view.elevation,
      pb::arg("distance") = def.view.distance, pb::arg("fov") = def.view.fov,
      pb::arg("slab") = pb::none(), pb::arg("clip") = false,
      pb::arg("show_inactive") = false, pb::arg("colorbar") = true,
      pb::arg("time_label") = true, pb::arg("legend") = true, pb::arg("scale_bar") = false,
      pb::arg("msaa") = def.style.msaa, pb::arg("font") = def.style.font,
      pb::arg("backend") = def.backend,
      "The renderer behind `grainshock render` (see grainshock.render for the arguments)");

  pb::class_<Comparison>(m, "Comparison", "The golden-image rule's verdict on two pictures")
      .def_property_readonly("alike", [](const Comparison& c) { return c.result.match(); },
                             "True when no blob of differing pixels exceeds the limits")
      .def_property_readonly(
          "fraction",
          [](const Comparison& c) {
            return c.result.pixels ? double(c.result.differing) / double(c.result.pixels) : 1.0;
          },
          "fraction of pixels that neither picture explains from the other")
      .def_property_readonly("differing", [](const Comparison& c) { return c.result.differing; })
      .def_property_readonly("blobs", [](const Comparison& c) { return c.result.blobs; })
      .def_property_readonly("largest_blob_pixels",
                             [](const Comparison& c) { return c.result.largest.pixels; })
      .def_property_readonly("largest_blob_mass",
                             [](const Comparison& c) { return c.result.largest.mass; })
      .def_property_readonly("same_size", [](const Comparison& c) { return c.result.same_size; })
      .def_property_readonly("max_channel_difference",
                             [](const Comparison& c) { return c.result.max_channel_difference; })
      .def_property_readonly("psnr", [](const Comparison& c) { return c.result.psnr; },
                             "dB, inf when identical")
      .def_property_readonly("ssim", [](const Comparison& c) { return c.result.ssim; })
      .def_property_readonly("diff", [](const Comparison& c) { return c.diff; },
                             "Image: differing pixels in red over a faded copy of `actual`")
      .def("__bool__", [](const Comparison& c) { return c.result.match(); })
      .def("__repr__", [](const Comparison& c) {
        return std::string("<grainshock.Comparison alike=") + (c.result.match() ? "True" : "False") +
               " differing=" + std::to_string(c.result.differing) + ">";
      });

  const render::CompareOptions cdef;
  m.def(
      "compare",
      [](const pb::object& expected, const pb::object& actual, int tolerance, long max_blob_pixels,
         long max_blob_mass) {
        const render::Image e = image_of(expected), a = image_of(actual);
        // As `grainshock compare` (exit 2): pictures of different sizes cannot be compared.
        if (e.width != a.width || e.height != a.height)
          throw UserError("pictures of different sizes cannot be compared: " +
                          std::to_string(e.width) + "x" + std::to_string(e.height) + " and " +
                          std::to_string(a.width) + "x" + std::to_string(a.height));
        const render::CompareOptions o{tolerance, max_blob_pixels, max_blob_mass};
        Comparison c;
        pb::gil_scoped_release release;
        c.result = render::compare_images(e, a, o);
        c.diff.image = render::diff_image(e, a, o);
        return c;
      },
      pb::arg("expected"), pb::arg("actual"), pb::kw_only(),
      pb::arg("tolerance") = cdef.channel_tolerance,
      pb::arg("max_blob_pixels") = cdef.max_blob_pixels,
      pb::arg("max_blob_mass") = cdef.max_blob_mass,
      R"(Compares two pictures as `grainshock compare` and the golden tests do.

expected, actual: Image, PNG path or (H, W, 3|4) uint8 array. Returns a Comparison with
.alike, .fraction, .psnr, .ssim and .diff (an Image).)");
}

}  // namespace gs::py
