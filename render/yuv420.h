#pragma once
// RGBA pictures to the planes of a BT.709 limited-range 4:2:0 movie, as H.264 players expect
// them (ITU-R BT.709-6, Table 3: Y = 16 + 219 E'Y, Cb and Cr = 128 + 224 E'CB and E'CR). Each
// chroma sample is the mean of its 2x2 block of pixels.
#include <cstdint>

#include "render/image.h"

namespace gs::render {

// `rgba`'s width and height must be even. Every sample is the exact value rounded to the
// nearest integer, except where that value lies within 0.02 of a half (16-bit coefficients).
void rgba_to_yuv420(const Image& rgba, std::uint8_t* y, int y_stride, std::uint8_t* cb,
                    std::uint8_t* cr, int c_stride);

}  // namespace gs::render
