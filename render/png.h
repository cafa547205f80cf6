#pragma once
// PNG files through libpng. Writes are atomic (temporary file, then rename), so an error or a
// crash never leaves a partial PNG under the requested name.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/image.h"
#include "sim/snapshot.h"

namespace gs::render {

using PngText = std::vector<std::pair<std::string, std::string>>;

// Level 1 (the default) writes a 1080p frame in ~50 ms where level 6 takes ~330 ms, and the file
// is smaller (bench case render/png_1080p). UserError naming the path on failure.
void write_png(const std::string& path, const Image& img, const PngText& text = {},
               int compression_level = 1);

// The bytes write_png would put in a file (a notebook shows a picture from them).
std::vector<std::uint8_t> encode_png(const Image& img, const PngText& text = {},
                                     int compression_level = 1);

// RGBA 8-bit; UserError naming the path if it is missing or not a PNG.
Image read_png(const std::string& path);
// The tEXt chunks of a PNG file.
PngText read_png_text(const std::string& path);

// Time, d, N, r, delta, seed (and density, speed) as far as the snapshot knows them.
PngText png_text(const SnapshotInfo& info, std::size_t particles);
// The text of a picture of these snapshots, as `render` writes it: the first one's, with Time
// listing every snapshot's time when there are several (the Fig. 1(a) overlay), and the drawn
// disc radius in pixels when it is given (> 0).
PngText png_text(const std::vector<const Snapshot*>& snaps, double disc_radius_px = 0);

// The key under which the renderer records the smallest drawn disc's radius in pixels
// (RenderInfo::disc_radius_px), so that `compare` knows what its rule can see without guessing
// the discs' size from the pixels.
inline constexpr char kDiscRadiusKey[] = "Disc radius px";
void add_disc_radius(PngText& text, double disc_radius_px);
// That radius, when the text has it as a positive number.
std::optional<double> disc_radius_of(const PngText& text);

}  // namespace gs::render
