// The movie encoder of `grainshock movie` (render/movie_writer.h) for grainshock.Movie, which
// renders snapshots into it (python/grainshock/__init__.py). The file appears complete under its
// name at finish(), or not at all.
#include <memory>
#include <string>

#include "python/py_image.h"
#include "python/py_module.h"
#include "render/movie_writer.h"
#include "sim/error.h"

namespace gs::py {

void bind_movie(pb::module_& m) {
  const render::MovieOptions def;
  pb::class_<render::MovieWriter>(m, "_MovieWriter", "FFmpeg encoder of grainshock.Movie")
      .def(pb::init([](const std::string& path, int width, int height, double fps,
                       const std::string& codec, int crf, const std::string& preset) {
             render::MovieOptions o;
             o.width = width;
             o.height = height;
             o.fps = fps;
             o.codec = codec;
             o.crf = crf;
             o.preset = preset;
             return std::make_unique<render::MovieWriter>(path, o);
           }),
           pb::arg("path"), pb::arg("width"), pb::arg("height"), pb::arg("fps") = def.fps,
           pb::arg("codec") = def.codec, pb::arg("crf") = def.crf,
           pb::arg("preset") = def.preset)
      .def(
          "add",
          [](render::MovieWriter& w, const PyImage& frame, int width, int height) {
            // The writer takes a wrong size for a bug; from Python it is a wrong input.
            if (frame.image.width != width || frame.image.height != height)
              throw UserError("Movie.add: a " + std::to_string(frame.image.width) + "x" +
                              std::to_string(frame.image.height) + " frame in a " +
                              std::to_string(width) + "x" + std::to_string(height) + " movie");
            render::Image copy = frame.image;
            pb::gil_scoped_release release;
            w.add(std::move(copy));
          },
          pb::arg("image"), pb::arg("width"), pb::arg("height"))
      .def("finish", [](render::MovieWriter& w) {
        pb::gil_scoped_release release;
        w.finish();
      })
      .def("discard", &render::MovieWriter::discard)
      .def_property_readonly("frames", &render::MovieWriter::frames_added)
      .def_property_readonly("encoder", &render::MovieWriter::encoder_name);
}

}  // namespace gs::py
