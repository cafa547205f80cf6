#pragma once
// Text drawn straight into an Image with FreeType, from a font file opened by path (no
// fontconfig), so the same words look the same on every machine with the same font.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/image.h"

namespace gs::render {

class Font {
 public:
  // UserError naming the path if FreeType cannot open it.
  explicit Font(const std::string& path);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  void set_pixel_size(int px);
  int pixel_size() const { return px_; }
  int ascent() const;   // pixels above the baseline
  int descent() const;  // pixels below the baseline (positive)
  int width(const std::string& utf8);
  // Blends the text with its baseline starting at (x, baseline); alpha in [0, 1].
  void draw(Image& img, int x, int baseline, const std::string& utf8,
            std::array<std::uint8_t, 3> colour, float alpha = 1);

 private:
  struct Glyph {
    int left = 0, top = 0, width = 0, rows = 0, advance = 0;  // pixels
    std::vector<std::uint8_t> coverage;
  };
  const Glyph& glyph(char32_t c);

  void* library_ = nullptr;  // FT_Library
  void* face_ = nullptr;     // FT_Face
  int px_ = 0;
  std::map<std::pair<int, char32_t>, Glyph> cache_;
};

}  // namespace gs::render
