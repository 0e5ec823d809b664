// The preview labels' bitmap font (preview_font.hpp).
#include "io/preview_font.hpp"

#include <cctype>

namespace skybake {

namespace {

struct Glyph {
  char c;
  uint8_t rows[5];
};

// Each row: 3 bits, left column in bit 2.
constexpr Glyph kGlyphs[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}},
    {'3', {7, 1, 7, 1, 7}}, {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}},
    {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}}, {'8', {7, 5, 7, 5, 7}},
    {'9', {7, 5, 7, 1, 7}}, {'A', {2, 5, 7, 5, 5}}, {'B', {6, 5, 6, 5, 6}},
    {'C', {3, 4, 4, 4, 3}}, {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}},
    {'F', {7, 4, 6, 4, 4}}, {'G', {3, 4, 5, 5, 3}}, {'H', {5, 5, 7, 5, 5}},
    {'I', {7, 2, 2, 2, 7}}, {'J', {1, 1, 1, 5, 2}}, {'K', {5, 5, 6, 5, 5}},
    {'L', {4, 4, 4, 4, 7}}, {'M', {5, 7, 7, 5, 5}}, {'N', {6, 5, 5, 5, 5}},
    {'O', {2, 5, 5, 5, 2}}, {'P', {6, 5, 6, 4, 4}}, {'Q', {2, 5, 5, 6, 3}},
    {'R', {6, 5, 6, 5, 5}}, {'S', {3, 4, 2, 1, 6}}, {'T', {7, 2, 2, 2, 2}},
    {'U', {5, 5, 5, 5, 7}}, {'V', {5, 5, 5, 5, 2}}, {'W', {5, 5, 7, 7, 5}},
    {'X', {5, 5, 2, 5, 5}}, {'Y', {5, 5, 2, 2, 2}}, {'Z', {7, 1, 2, 4, 7}},
    {'.', {0, 0, 0, 0, 2}}, {',', {0, 0, 0, 2, 4}}, {'-', {0, 0, 7, 0, 0}}, {'+', {0, 2, 7, 2, 0}},
    {':', {0, 2, 0, 2, 0}}, {'_', {0, 0, 0, 0, 7}}, {'/', {1, 1, 2, 4, 4}},
    {'(', {1, 2, 2, 2, 1}}, {')', {4, 2, 2, 2, 4}}, {'%', {5, 1, 2, 4, 5}},
};

constexpr uint8_t kBlank[5] = {0, 0, 0, 0, 0};

}  // namespace

const uint8_t* preview_glyph(char c) {
  const char u = char(std::toupper((unsigned char)c));
  for (const Glyph& g : kGlyphs)
    if (g.c == u) return g.rows;
  return kBlank;
}

int preview_text_width(const std::string& text, int scale) {
  return text.empty() ? 0 : (4 * int(text.size()) - 1) * scale;
}

void draw_preview_text(std::vector<uint8_t>& rgb, int width, int height, int x, int y,
                       const std::string& text, int scale, uint8_t grey) {
  for (size_t i = 0; i < text.size(); ++i) {
    const uint8_t* rows = preview_glyph(text[i]);
    const int gx = x + int(i) * 4 * scale;
    for (int r = 0; r < 5; ++r)
      for (int col = 0; col < 3; ++col) {
        if (!(rows[r] & (4 >> col))) continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx) {
            const int px = gx + col * scale + sx, py = y + r * scale + sy;
            if (px < 0 || py < 0 || px >= width || py >= height) continue;
            uint8_t* p = &rgb[(size_t(py) * size_t(width) + size_t(px)) * 3];
            p[0] = p[1] = p[2] = grey;
          }
      }
  }
}

}  // namespace skybake
