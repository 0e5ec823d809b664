// The preview labels' font (io/preview_font.hpp): glyph rows as drawn,
// widths, scale, clipping at the image's edge, blanks for unknown characters.
#include "io/preview_font.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// The image as '#' and '.' rows, for comparing with a drawing.
std::vector<std::string> ascii(const std::vector<uint8_t>& rgb, int width, int height) {
  std::vector<std::string> rows;
  for (int y = 0; y < height; ++y) {
    std::string row;
    for (int x = 0; x < width; ++x) row += rgb[(size_t(y) * width + x) * 3] ? '#' : '.';
    rows.push_back(row);
  }
  return rows;
}

TEST(PreviewFont, TextIsDrawnGlyphByGlyphWithOneColumnBetween) {
  std::vector<uint8_t> rgb(7 * 5 * 3, 0);
  draw_preview_text(rgb, 7, 5, 0, 0, "G0", 1, 255);
  EXPECT_EQ(ascii(rgb, 7, 5), (std::vector<std::string>{".##.###", "#...#.#", "#.#.#.#",
                                                         "#.#.#.#", ".##.###"}));
  EXPECT_EQ(preview_text_width("G0", 1), 7);
  EXPECT_EQ(preview_text_width("G0", 2), 14);
  EXPECT_EQ(preview_text_width("", 2), 0);
}

TEST(PreviewFont, ScaleClipsAndLowerCase) {
  std::vector<uint8_t> rgb(4 * 4 * 3, 0);
  // "-" at scale 2 is rows 4-5 of a 6 x 10 glyph; only its left 4 x 4 corner
  // from (0, -2) lands in the image: rows 2 and 3.
  draw_preview_text(rgb, 4, 4, 0, -2, "-", 2, 200);
  EXPECT_EQ(ascii(rgb, 4, 4), (std::vector<std::string>{"....", "....", "####", "####"}));
  EXPECT_EQ(rgb[(2 * 4 + 0) * 3], 200);
  // Lower case draws as upper case; an unknown character is blank.
  for (int r = 0; r < 5; ++r) EXPECT_EQ(preview_glyph('e')[r], preview_glyph('E')[r]);
  for (int r = 0; r < 5; ++r) EXPECT_EQ(preview_glyph('#')[r], 0);
}

}  // namespace
}  // namespace skybake
