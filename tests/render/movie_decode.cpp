#include "tests/render/movie_decode.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "render/image_compare.h"
#include "render/movie_reader.h"

namespace gs::render {

double psnr(const Image& a, const Image& b, int w, int h) {
  auto crop = [w, h](const Image& src) {
    Image c(w, h);
    for (int y = 0; y < h; ++y) std::copy_n(src.pixel(0, y), 4 * w, c.pixel(0, y));
    return c;
  };
  return std::min(99.0, compare_images(crop(a), crop(b)).psnr);
}

Decoded decode_movie(const std::filesystem::path& path, int keep) {
  Decoded out;
  try {
    MovieReader reader(path);
    const MovieInfo& i = reader.info();
    out.codec = AVCodecID(i.codec_id);
    out.width = i.width;
    out.height = i.height;
    out.avg_frame_rate = {i.avg_rate_num, i.avg_rate_den};
    out.r_frame_rate = {i.r_rate_num, i.r_rate_den};
    out.duration = i.duration;
    out.nb_frames = i.nb_frames;
    out.range = AVColorRange(i.color_range);
    out.space = AVColorSpace(i.color_space);
    out.primaries = AVColorPrimaries(i.color_primaries);
    out.trc = AVColorTransferCharacteristic(i.color_trc);
    while (reader.next()) {
      if (out.frames == keep) out.rgb = reader.rgb();
      out.centre_luma.push_back(reader.luma(i.width / 2, i.height / 2));
      ++out.frames;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
  return out;
}

}  // namespace gs::render
