#pragma once
// Comparison of two pictures, as `grainshock compare` and the golden-image tests do it.
//
// Rule: a pixel differs when any of R, G, B differs by more than 24 (of 255); two images are
// alike when they have the same size and at most 0.1% of their pixels differ. Why: llvmpipe's
// output moves with Mesa and LLVM versions and with the CPU's vector width (AVX2 vs AVX-512 change
// rounding and which edge pixels a triangle covers), so antialiased rims shift by a fraction of
// a pixel and by a few levels; a movie re-encoded at high quality moves colours at edges by a few
// levels too. The tolerance absorbs those. A real regression changes whole discs: the golden
// scenes draw discs of at least 5 px radius on 256x256 pictures, so one disc moved by its
// diameter changes >= 2 * 78 pixels and one disc recoloured changes ~78 pixels by far more than
// 24, both above the 65 pixels (0.1%) allowed; the comparator's own tests check exactly that.
//
// PSNR and SSIM are reported beside the rule, not part of it: they summarise how far apart two
// pictures are where the rule only says alike or not.
#include <limits>

#include "render/image.h"

namespace gs::render {

struct CompareOptions {
  int channel_tolerance = 24;             // of 255, per R, G, B
  double max_differing_fraction = 0.001;  // of the pixels
};

struct ImageComparison {
  bool same_size = false;
  long pixels = 0;
  long differing = 0;  // pixels beyond the channel tolerance
  long allowed = 0;    // the most differing pixels the options allow
  int max_channel_difference = 0;
  double mse = 0;  // mean squared difference over R, G, B, in levels^2
  double psnr = std::numeric_limits<double>::infinity();  // dB, +inf when identical
  double ssim = 1;
  bool match() const { return same_size && differing <= allowed; }
  double differing_fraction() const { return pixels ? double(differing) / double(pixels) : 0; }
};

// Everything above for two pictures; only same_size (false) when their sizes differ.
ImageComparison compare_images(const Image& expected, const Image& actual,
                               const CompareOptions& options = {});

// 10 log10(255^2 / mse): +inf for mse = 0.
double psnr_of_mse(double mse);

// Mean SSIM of Wang, Bovik, Sheikh and Simoncelli, IEEE Trans. Image Process. 13, 600 (2004):
// on BT.709 luma, with their 11x11 Gaussian window (sigma 1.5), K1 = 0.01, K2 = 0.03, L = 255,
// averaged over the window positions inside the picture (no padding, no downsampling). A picture
// smaller than the window is one window. Sizes must agree.
double ssim(const Image& a, const Image& b);

// Differing pixels in red over a faded grey copy of `actual`; pixels outside `expected` count as
// differing.
Image diff_image(const Image& expected, const Image& actual, int channel_tolerance = 24);

// Totals of a frame-by-frame comparison of two movies: the movies are alike when they have the
// same number of frames and every frame is alike.
struct SequenceComparison {
  int frames = 0;  // compared
  bool same_count = true;
  bool same_size = true;
  int worst_frame = -1;  // the frame with the largest differing fraction
  double worst_fraction = 0;
  bool all_match = true;
  int max_channel_difference = 0;
  double sum_mse = 0, sum_ssim = 0;

  void add(const ImageComparison& c);
  bool match() const { return same_count && same_size && all_match; }
  double psnr() const { return frames ? psnr_of_mse(sum_mse / frames) : psnr_of_mse(0); }
  double mean_ssim() const { return frames ? sum_ssim / frames : 1; }
};

}  // namespace gs::render
