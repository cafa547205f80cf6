#pragma once
// PNG files through libpng. Writes are atomic (temporary file, then rename), so an error or a
// crash never leaves a partial PNG under the requested name.
#include <cstdint>
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
// listing every snapshot's time when there are several (the Fig. 1(a) overlay).
PngText png_text(const std::vector<const Snapshot*>& snaps);

}  // namespace gs::render
