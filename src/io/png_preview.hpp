// 8-bit sRGB PNG previews of any Texture, for people to look at: tone-mapped,
// slices side by side. Not a data format: nothing reads these back into a
// Texture.
//
// Layout: the preview is a grid of panels, one per shown slice (volume) or
// layer (array), or a single panel (2D); panel k sits at column k % columns,
// row k / columns with columns = min(panels, max_columns); unused cells are
// black. Texel (x, y) is pixel (x, y) of its panel (y = 0 is the top row, as
// in our EXR and DDS files; the bottom row with height_up), or the block of
// scale_x x scale_y pixels there when min_side enlarges it. A panel is
// width x height, doubled in both directions with tile_2x2 (the panel
// repeated 2x2 to eyeball seams), and with split_channels holds one grey
// sub-panel per channel side by side.
//
// Colour: 1 channel -> grey, 2 -> (c0, c1, 0), 3 or more -> (c0, c1, c2)
// (alpha and further channels are not shown; use split_channels to see them).
// Values are mapped by exposure, then the tone curve, then clamped to [0, 1]
// and encoded with the sRGB transfer function (IEC 61966-2-1), rounded.
// Bytes are deterministic: no time or software stamps.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/finite_check.hpp"
#include "core/texture.hpp"

namespace skybake {

enum class Tonemap {
  none,      // clamp to [0, 1]
  reinhard,  // x / (1 + x) (Reinhard et al. 2002, eq. 3)
  aces,      // Narkowicz 2015 fit of the ACES filmic curve
};

struct PreviewOptions {
  // Multiplier applied before the tone curve. Empty = automatic: data within
  // [0, 1] is shown as is; HDR data is scaled so its 99th percentile maps to
  // 1; signed data (any value < 0) maps [-p, p] to [0, 1] with p the 99th
  // percentile of |value|, so 0 is mid grey.
  std::optional<double> exposure;
  Tonemap tonemap = Tonemap::none;
  int max_slices = 8;           // volumes: show at most this many slices, evenly picked; 0 = all
  int max_columns = 8;          // panels per row before wrapping to the next row (>= 1)
  bool tile_2x2 = false;        // repeat each panel 2x2
  bool split_channels = false;  // one grey sub-panel per channel instead of colour
  // Small textures are enlarged: each texel becomes a block of whole pixels,
  // so that every panel axis shorter than `min_side` reaches it (each axis on
  // its own: a 1 x 128 height profile shows as 64 x 128). 0 = off.
  int min_side = 0;
  bool height_up = false;  // texture row 0 at the bottom (rows are heights, rising upward)
  // With split_channels: a band above each sub-panel names its channel (and
  // what the metadata "channel.<name>" says before any ':'), says "<v>
  // EVERYWHERE" for a constant channel (an all-zero one is correct, not
  // broken) and, with stretch_narrow, maps a [0, 1] channel whose range is
  // narrower than 0.5 from [min, max] to [0, 1], saying "<min>-<max>
  // STRETCHED".
  bool label_channels = false;
  bool stretch_narrow = false;
  // One line above each panel (layer or slice shown), by panel index: what
  // it shows (a sky preview: its sun and camera). Empty = no panel labels.
  std::vector<std::string> panel_labels;
  FiniteCheck finite = FiniteCheck::run;  // core/finite_check.hpp
};

// Where the panels go; write_png_preview draws exactly this.
struct PreviewLayout {
  std::vector<int> panels;  // the slice (volume) or layer (array) shown in each panel
  int columns = 1, rows = 1;
  int scale_x = 1, scale_y = 1;         // pixels per texel along x and y (min_side)
  int label_height = 0;                 // the label band at the top of each cell
  int cell_width = 0, cell_height = 0;  // one panel in pixels
  int width = 0, height = 0;            // the whole image
};

// The slices shown of a volume of `depth` slices: z_i = floor(i depth / n)
// for i < n = min(depth, max_slices) (all when max_slices is 0).
std::vector<int> preview_slices(int depth, int max_slices);

PreviewLayout preview_layout(const Texture& tex, const PreviewOptions& opt);

// The second line of a channel's label (label_channels): "0 EVERYWHERE" when
// lo == hi, "0.70-0.94 STRETCHED" when stretched, else "".
std::string preview_range_label(double lo, double hi, bool stretched);

// Writes the preview to exactly `path` as an RGB8 PNG.
// Throws IoError (before creating the file) when a value is NaN/Inf or the
// texture is empty, and when the file cannot be written (the partial file is removed).
void write_png_preview(const std::string& path, const Texture& tex, const PreviewOptions& opt = {});

}  // namespace skybake
