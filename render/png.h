#pragma once
// PNG files through libpng. Writes are atomic (temporary file, then rename), so an error or a
// crash never leaves a partial PNG under the requested name.
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

// RGBA 8-bit; UserError naming the path if it is missing or not a PNG.
Image read_png(const std::string& path);
// The tEXt chunks of a PNG file.
PngText read_png_text(const std::string& path);

// Time, d, N, r, delta, seed (and density, speed) as far as the snapshot knows them.
PngText png_text(const SnapshotInfo& info, std::size_t particles);

}  // namespace gs::render
