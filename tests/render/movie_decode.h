#pragma once
// Test helpers: decode a whole movie with render::MovieReader and compare pictures.
#include <cstdint>
#include <filesystem>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
}

#include "render/image.h"

namespace gs::render {

// PSNR over the RGB channels of the top-left w x h of both images, 99 dB when identical.
double psnr(const Image& a, const Image& b, int w, int h);

struct Decoded {
  AVCodecID codec = AV_CODEC_ID_NONE;
  int width = 0, height = 0;
  AVRational avg_frame_rate{0, 1}, r_frame_rate{0, 1};
  double duration = 0;         // seconds, as a player shows it
  std::int64_t nb_frames = 0;  // as the container says
  int frames = 0;              // as decoded
  AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
  AVColorSpace space = AVCOL_SPC_UNSPECIFIED;
  AVColorPrimaries primaries = AVCOL_PRI_UNSPECIFIED;
  AVColorTransferCharacteristic trc = AVCOL_TRC_UNSPECIFIED;
  std::vector<int> centre_luma;  // Y at the picture centre, per frame
  Image rgb;                     // the frame asked for, back to RGB (BT.709, limited range)
};

// Decodes the whole movie (failing the current test on an error); frame `keep`, in
// presentation order, is converted back to RGBA with BT.709 limited-range coefficients.
Decoded decode_movie(const std::filesystem::path& path, int keep = -1);

}  // namespace gs::render
