#pragma once
// Comparison of two pictures, as `grainshock compare` and the golden-image tests do it.
//
// Rule. A pixel of one picture is explained by the other when it lies within `channel_tolerance`
// (10 of 255, largest of R, G, B) of some blend of the other's pixel at the same place with its
// neighbours of one quadrant (the convex hull, in RGB, of the pixel, the one beside it, the one
// above or below and the diagonal one: any bilinear mix of them, which is what a shift of less
// than a pixel in that direction produces, rims where two or three discs meet included). A pixel
// differs when either picture leaves it unexplained (so a disc that vanished and one that
// appeared both count); the outermost rows and columns are left out (what a shift brings in
// there comes from outside). Differing pixels are grouped into 8-connected blobs; the pictures
// are alike when no blob has more than `max_blob_pixels` (5) pixels nor a `mass` (the sum of its
// pixels' unexplained amounts beyond the tolerance) above `max_blob_mass` (150, levels x pixels).
// Both limits are absolute, as browser reftests count pixels, so the rule does not loosen with
// the picture's size.
//
// Why. The old rule (0.1% of pixels beyond 24) allowed 2000 pixels at 1920x1080: one disc moved
// by two diameters, 15 discs moved, a recolour from v/v_rms 0.1 to 1.4 and a missing label all
// passed. What must pass is what llvmpipe does as Mesa, LLVM and the CPU's vector width change
// (antialiased rims moved by a fraction of a pixel, by up to ~100 levels at a rim: more than a
// recolour changes) and what a re-encode at CRF <= 12 does (a few levels everywhere, up to ~50 at
// edges): both are blends of neighbouring colours, which the quadrant hull explains, and leave
// only scattered blobs of at most 4 px whose mass is below 30. What must fail, measured on frames
// of a kick (tests/render/test_compare_kick.cpp, 640x480 to 3840x2160, discs of 1.5 and 10 px):
// one disc moved by a diameter leaves a blob of 4 px and mass ~490 (1.5 px discs) to 340 px;
// one disc recoloured by a tenth of magma's range moves its colour by 28 levels, no blend of its
// neighbours, a blob of 7 px (1.5 px discs) to 320 px; a changed digit of the time label a blob
// of mass >= 330 even at 640x480, a missing label one of 48 px or more. The size limit catches
// faint but whole changes (a recolour), the mass limit small but strong ones (a moved tiny disc,
// a glyph). The margins are narrow at 1.5 px radius (7 px against 5 allowed, 4 px against 5 for
// the re-encode): below that a disc is too small to tell from its rim's noise.
//
// PSNR and SSIM are reported beside the rule, not part of it: they summarise how far apart two
// pictures are where the rule only says alike or not.
#include <algorithm>
#include <limits>

#include "render/image.h"

namespace gs::render {

// Below this disc radius (pixels) the rule cannot be trusted to see one particle move: a
// 20000-disc box at t = 2000 drawn whole with its resting discs, one disc at a time moved by a
// diameter, 12 times: 0 of 12 caught at 0.73, 0.91 and 1.17 px radius, 10 of 12 at 1.46 px, 12
// of 12 at 1.83 px (and 1.5 px is where the margins above were measured).
// `compare` says so in its line when a picture's text (render/png.h, kDiscRadiusKey) records
// discs smaller than this.
inline constexpr double kSmallestSeenDiscPx = 1.5;

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
