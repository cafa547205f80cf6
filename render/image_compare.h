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
#include <algorithm>
#include <limits>

#include "render/image.h"

namespace gs::render {

struct CompareOptions {
  int channel_tolerance = 10;  // of 255, largest of R, G, B, beyond every blend of neighbours
  long max_blob_pixels = 5;    // a blob with more differing pixels than this is a difference
  long max_blob_mass = 150;    // so is one whose differences beyond the tolerance sum to more
};

// A connected (8-neighbour) group of differing pixels.
struct Blob {
  long pixels = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // bounding box, inclusive, row 0 at the top
  int peak = 0;                          // largest unexplained channel difference in it
  long mass = 0;                         // sum of the unexplained differences beyond tolerance
};

struct ImageComparison {
  bool same_size = false;
  long pixels = 0;
  long differing = 0;  // pixels that neither picture explains from the other (the rule above)
  long blobs = 0;      // connected groups of them
  Blob largest;        // the one that exceeds the limits most (most pixels, else most mass)
  long max_pixels = 0, max_mass = 0;  // the limits of the options
  // True when the blob is within both limits.
  bool within(const Blob& b) const { return excess_of(b) <= 1; }
  // How far a blob is from the limits: the larger of pixels / max_pixels and mass / max_mass.
  double excess_of(const Blob& b) const {
    return std::max(double(b.pixels) / double(std::max(1L, max_pixels)),
                    double(b.mass) / double(std::max(1L, max_mass)));
  }
  int max_channel_difference = 0;  // pixel by pixel, before the neighbourhood
  double mse = 0;  // mean squared difference over R, G, B, in levels^2
  double psnr = std::numeric_limits<double>::infinity();  // dB, +inf when identical
  double ssim = 1;
  bool match() const { return same_size && within(largest); }
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

// Differing pixels (by the rule above) in red over a faded grey copy of `actual`; all red when
// the sizes differ.
Image diff_image(const Image& expected, const Image& actual, const CompareOptions& options = {});

// Totals of a frame-by-frame comparison of two movies: the movies are alike when they have the
// same number of frames and every frame is alike.
struct SequenceComparison {
  int frames = 0;  // compared
  bool same_count = true;
  bool same_size = true;
  int worst_frame = -1;  // the frame with the largest blob
  ImageComparison worst;  // that frame's comparison
  bool all_match = true;
  int max_channel_difference = 0;
  double sum_mse = 0, sum_ssim = 0;

  void add(const ImageComparison& c);
  bool match() const { return same_count && same_size && all_match; }
  double psnr() const { return frames ? psnr_of_mse(sum_mse / frames) : psnr_of_mse(0); }
  double mean_ssim() const { return frames ? sum_ssim / frames : 1; }
};

}  // namespace gs::render
