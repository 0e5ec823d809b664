// A 3 x 5 pixel bitmap font for the labels of PNG previews (png_preview.hpp):
// digits, upper-case letters and . , - + : _ / ( ) %; lower case is drawn as
// upper case, anything else as a blank. Glyphs are 3 pixels wide with one
// pixel between them, drawn at a whole-pixel scale.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace skybake {

// Rows of a glyph, top first, 3 bits each (bit 2 = left column); all zero
// for a character the font does not have.
const uint8_t* preview_glyph(char c);

// Pixels `text` spans at `scale`: 4 per character less the last gap.
int preview_text_width(const std::string& text, int scale);

// Draws `text` with its top-left corner at (x, y) into an RGB8 image of
// `width` x `height` pixels, in grey level `grey`; pixels outside are skipped.
void draw_preview_text(std::vector<uint8_t>& rgb, int width, int height, int x, int y,
                       const std::string& text, int scale, uint8_t grey);

}  // namespace skybake
