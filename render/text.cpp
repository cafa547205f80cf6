#include "render/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>

#include "sim/error.h"

namespace gs::render {
namespace {

std::vector<char32_t> decode_utf8(const std::string& s) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : c < 0xE0 ? 1 : c < 0xF0 ? 2 : 3;
    char32_t cp = extra == 0 ? c : extra == 1 ? (c & 0x1F) : extra == 2 ? (c & 0x0F) : (c & 0x07);
    ++i;
    for (; extra > 0 && i < s.size(); --extra, ++i)
      cp = (cp << 6) | (static_cast<unsigned char>(s[i]) & 0x3F);
    out.push_back(cp);
  }
  return out;
}

}  // namespace

Font::Font(const std::string& path) {
  FT_Library lib = nullptr;
  if (FT_Init_FreeType(&lib)) throw UserError("cannot initialise FreeType");
  FT_Face face = nullptr;
  if (FT_New_Face(lib, path.c_str(), 0, &face)) {
    FT_Done_FreeType(lib);
    throw UserError("cannot open font '" + path + "' (Debian package fonts-dejavu-core)");
  }
  library_ = lib;
  face_ = face;
  set_pixel_size(16);
}

Font::~Font() {
  FT_Done_Face(static_cast<FT_Face>(face_));
  FT_Done_FreeType(static_cast<FT_Library>(library_));
}

void Font::set_pixel_size(int px) {
  px = std::max(px, 4);
  if (px == px_) return;
  px_ = px;
  FT_Set_Pixel_Sizes(static_cast<FT_Face>(face_), 0, static_cast<FT_UInt>(px));
}

int Font::ascent() const {
  return static_cast<int>(static_cast<FT_Face>(face_)->size->metrics.ascender >> 6);
}
int Font::descent() const {
  return static_cast<int>(-(static_cast<FT_Face>(face_)->size->metrics.descender >> 6));
}

const Font::Glyph& Font::glyph(char32_t c) {
  auto key = std::pair{px_, c};
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  auto face = static_cast<FT_Face>(face_);
  Glyph g;
  if (!FT_Load_Char(face, c, FT_LOAD_RENDER)) {
    const FT_GlyphSlot slot = face->glyph;
    g.left = slot->bitmap_left;
    g.top = slot->bitmap_top;
    g.width = static_cast<int>(slot->bitmap.width);
    g.rows = static_cast<int>(slot->bitmap.rows);
    g.advance = static_cast<int>(slot->advance.x >> 6);
    g.coverage.resize(static_cast<std::size_t>(g.width) * g.rows);
    for (int y = 0; y < g.rows; ++y)
      std::copy_n(slot->bitmap.buffer + y * slot->bitmap.pitch, g.width,
                  g.coverage.begin() + static_cast<std::ptrdiff_t>(y) * g.width);
  }
  return cache_.emplace(key, std::move(g)).first->second;
}

int Font::width(const std::string& utf8) {
  int w = 0;
  for (char32_t c : decode_utf8(utf8)) w += glyph(c).advance;
  return w;
}

void Font::draw(Image& img, int x, int baseline, const std::string& utf8,
                std::array<std::uint8_t, 3> colour, float alpha) {
  for (char32_t c : decode_utf8(utf8)) {
    const Glyph& g = glyph(c);
    for (int gy = 0; gy < g.rows; ++gy) {
      const int py = baseline - g.top + gy;
      if (py < 0 || py >= img.height) continue;
      for (int gx = 0; gx < g.width; ++gx) {
        const int px = x + g.left + gx;
        if (px < 0 || px >= img.width) continue;
        const float a = alpha * g.coverage[static_cast<std::size_t>(gy) * g.width + gx] / 255.0f;
        if (a <= 0) continue;
        std::uint8_t* p = img.pixel(px, py);
        for (int k = 0; k < 3; ++k)
          p[k] = static_cast<std::uint8_t>(p[k] + a * (colour[k] - p[k]) + 0.5f);
      }
    }
    x += g.advance;
  }
}

}  // namespace gs::render
