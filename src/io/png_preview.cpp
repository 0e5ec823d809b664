// PNG previews: panel layout, automatic exposure, tone curves and sRGB
// encoding as documented in png_preview.hpp; our own PNG encoder over zlib.
#include "io/png_preview.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
#include <variant>

#include <fmt/format.h>
#include <zlib.h>

#include "core/error.hpp"
#include "io/preview_font.hpp"

namespace skybake {

namespace {

// The value mapping before the tone curve: v' = offset + scale * v.
struct Exposure {
  double scale = 1.0;
  double offset = 0.0;
};

// The channels drawn: the first three in colour mode, all when split.
int shown_channels(const Texture& tex, const PreviewOptions& opt) {
  return opt.split_channels ? tex.channel_count() : std::min(tex.channel_count(), 3);
}

// The texture slab (z or layer) behind a panel.
const float* panel_texel(const Texture& tex, int panel, int x, int y) {
  return tex.is_volume() ? tex.texel(x, y, panel, 0) : tex.texel(x, y, 0, panel);
}

// 99th percentile of `values` (nearest rank), which it reorders.
double percentile99(std::vector<float>& values) {
  const size_t k = size_t(0.99 * double(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

Exposure auto_exposure(const Texture& tex, const PreviewLayout& layout, int shown) {
  std::vector<float> values;
  values.reserve(layout.panels.size() * tex.width * tex.height * shown);
  for (int panel : layout.panels)
    for (int y = 0; y < tex.height; ++y)
      for (int x = 0; x < tex.width; ++x)
        for (int c = 0; c < shown; ++c) values.push_back(panel_texel(tex, panel, x, y)[c]);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  if (*lo >= 0.0f && *hi <= 1.0f) return {};
  if (*lo < 0.0f) {  // signed: [-p, p] -> [0, 1]
    for (float& v : values) v = std::fabs(v);
    const double p = percentile99(values);
    return p > 0.0 ? Exposure{0.5 / p, 0.5} : Exposure{0.5 / std::fabs(*lo), 0.5};
  }
  const double top = *hi;
  const double p = percentile99(values);
  return {1.0 / (p > 0.0 ? p : top)};
}

double tone_curve(double x, Tonemap tonemap) {
  switch (tonemap) {
    case Tonemap::none:
      return x;
    case Tonemap::reinhard:
      return x > 0.0 ? x / (1.0 + x) : 0.0;
    case Tonemap::aces:  // Narkowicz 2015, "ACES Filmic Tone Mapping Curve"
      x = std::max(x, 0.0);
      return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  }
  return x;
}

// IEC 61966-2-1 sRGB transfer function, then 8-bit rounding.
uint8_t srgb8(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return uint8_t(std::lround(s * 255.0));
}

// Draws panel `k` into the RGB8 image; channel c mapped by e[c].
void draw_panel(std::vector<uint8_t>& rgb, const PreviewLayout& layout, const Texture& tex,
                const PreviewOptions& opt, const std::vector<Exposure>& e, int k) {
  const int shown = shown_channels(tex, opt);
  const int tiles = opt.tile_2x2 ? 2 : 1;
  const int sub_panels = opt.split_channels ? shown : 1;
  const int x0 = (k % layout.columns) * layout.cell_width;
  const int y0 = (k / layout.columns) * layout.cell_height + layout.label_height;
  const int w = tex.width * layout.scale_x, h = tex.height * layout.scale_y;  // one tile
  std::vector<uint8_t> mapped(shown);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int tx_ = x / layout.scale_x, ty_ = y / layout.scale_y;
      const float* v =
          panel_texel(tex, layout.panels[k], tx_, opt.height_up ? tex.height - 1 - ty_ : ty_);
      for (int c = 0; c < shown; ++c)
        mapped[c] = srgb8(tone_curve(e[c].offset + e[c].scale * v[c], opt.tonemap));
      for (int s = 0; s < sub_panels; ++s) {
        uint8_t px[3] = {mapped[0], mapped[0], mapped[0]};  // one channel: grey
        if (opt.split_channels)
          px[0] = px[1] = px[2] = mapped[s];
        else if (shown > 1)
          px[1] = mapped[1], px[2] = shown > 2 ? mapped[2] : 0;
        for (int ty = 0; ty < tiles; ++ty)
          for (int tx = 0; tx < tiles; ++tx) {
            const size_t px_x = x0 + (s * tiles + tx) * w + x;
            const size_t px_y = y0 + ty * h + y;
            std::copy(px, px + 3, &rgb[(px_y * layout.width + px_x) * 3]);
          }
      }
    }
}

// Pixels of the label band: two lines of 5-pixel glyphs at scale 2, 2 pixels
// around each line.
constexpr int kLabelScale = 2;
constexpr int kLabelLine = 5 * kLabelScale + 2;

// Smallest and largest value of channel c over the shown panels.
std::pair<float, float> channel_range(const Texture& tex, const PreviewLayout& layout, int c) {
  float lo = tex.data.empty() ? 0.0f : panel_texel(tex, layout.panels[0], 0, 0)[c], hi = lo;
  for (int panel : layout.panels)
    for (int y = 0; y < tex.height; ++y)
      for (int x = 0; x < tex.width; ++x) {
        const float v = panel_texel(tex, panel, x, y)[c];
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
  return {lo, hi};
}

// A split channel's mapping: the common one, or [lo, hi] -> [0, 1] for a
// narrow [0, 1] channel under stretch_narrow (its label says so).
bool stretches(const PreviewOptions& opt, float lo, float hi) {
  return opt.stretch_narrow && !opt.exposure && lo >= 0.0f && hi <= 1.0f && hi > lo &&
         hi - lo < 0.5f;
}

// The first label line: the channel's name and what its metadata says of
// it before any ':' ("G erosion"), upper case.
std::string channel_title(const Texture& tex, int c) {
  std::string title = tex.channels[c];
  const auto it = tex.metadata.find("channel." + tex.channels[c]);
  if (it != tex.metadata.end())
    if (const std::string* text = std::get_if<std::string>(&it->second))
      title += " " + text->substr(0, text->find(':'));
  return title;
}

// Draws `line` in the band of the sub-panel at (x, y), `w` pixels wide: at
// the label scale when it fits, else at 1, cut at the sub-panel's edge.
void draw_label_line(std::vector<uint8_t>& rgb, const PreviewLayout& layout, int x, int y, int w,
                     std::string line) {
  const int scale = preview_text_width(line, kLabelScale) + 2 <= w ? kLabelScale : 1;
  const size_t fits = size_t(std::max(0, (w - 2 + 1) / (4 * scale)));
  if (line.size() > fits) line.resize(fits);
  draw_preview_text(rgb, layout.width, layout.height, x + 1, y + 1, line, scale, 255);
}

void draw_labels(std::vector<uint8_t>& rgb, const PreviewLayout& layout, const Texture& tex,
                 const PreviewOptions& opt, const std::vector<std::string>& ranges) {
  const int tiles = opt.tile_2x2 ? 2 : 1;
  const int w = tex.width * layout.scale_x * tiles;
  for (int k = 0; k < int(layout.panels.size()); ++k) {
    const int x0 = (k % layout.columns) * layout.cell_width;
    int y0 = (k / layout.columns) * layout.cell_height;
    if (!opt.panel_labels.empty()) {
      const size_t panel = size_t(layout.panels[k]);
      if (panel < opt.panel_labels.size())
        draw_label_line(rgb, layout, x0, y0, layout.cell_width, opt.panel_labels[panel]);
      y0 += kLabelLine;
    }
    for (int c = 0; c < int(ranges.size()); ++c) {
      draw_label_line(rgb, layout, x0 + c * w, y0, w, channel_title(tex, c));
      draw_label_line(rgb, layout, x0 + c * w, y0 + kLabelLine, w, ranges[c]);
    }
  }
}

void append_u32_be(std::string& out, uint32_t v) {
  const char b[4] = {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  out.append(b, 4);
}

// One chunk: length, type, data, CRC-32 of type and data (PNG spec sec. 5.3).
void put_chunk(std::string& out, const char type[4], const std::string& data) {
  append_u32_be(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.append(type, 4);
  out += data;
  const auto* p = reinterpret_cast<const Bytef*>(out.data() + start);
  append_u32_be(out, uint32_t(crc32(crc32(0L, Z_NULL, 0), p, uInt(out.size() - start))));
}

// The row filtered with one filter type (PNG spec sec. 9.2): a = left, b =
// up, c = up-left (0 before the first pixel). Each type is its own loop,
// without a switch per byte, so that the compiler vectorizes it.
void filter_row(uint8_t type, const uint8_t* row, const uint8_t* up, size_t stride,
                uint8_t* out) {
  const size_t head = std::min<size_t>(3, stride);
  switch (type) {
    case 0:
      std::copy(row, row + stride, out);
      return;
    case 1:
      std::copy(row, row + head, out);
      for (size_t i = 3; i < stride; ++i) out[i] = uint8_t(row[i] - row[i - 3]);
      return;
    case 2:
      for (size_t i = 0; i < stride; ++i) out[i] = uint8_t(row[i] - up[i]);
      return;
    case 3:
      for (size_t i = 0; i < head; ++i) out[i] = uint8_t(row[i] - up[i] / 2);
      for (size_t i = 3; i < stride; ++i) out[i] = uint8_t(row[i] - (row[i - 3] + up[i]) / 2);
      return;
    default:
      for (size_t i = 0; i < head; ++i) out[i] = uint8_t(row[i] - up[i]);  // Paeth of (0, b, 0)
      for (size_t i = 3; i < stride; ++i) {
        const int a = row[i - 3], b = up[i], c = up[i - 3];
        const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
        out[i] = uint8_t(row[i] - (pa <= pb && pa <= pc ? a : pb <= pc ? b : c));
      }
  }
}

// Filter byte + filtered row (PNG spec sec. 9): every row tries the five
// filters and keeps the one with the least sum of |signed bytes|, the usual
// heuristic (deterministic: ties go to the lower filter type).
void filter_rows(const std::vector<uint8_t>& rgb, int width, int height, std::string& out) {
  const size_t stride = size_t(width) * 3;
  std::vector<uint8_t> zero(stride, 0), trial(stride), best(stride);
  out.reserve(out.size() + (stride + 1) * height);
  for (int y = 0; y < height; ++y) {
    const uint8_t* row = &rgb[y * stride];
    const uint8_t* up = y > 0 ? &rgb[(y - 1) * stride] : zero.data();
    uint64_t best_cost = ~uint64_t(0);
    uint8_t best_type = 0;
    for (uint8_t type = 0; type < 5; ++type) {
      filter_row(type, row, up, stride, trial.data());
      uint64_t cost = 0;
      for (size_t i = 0; i < stride; ++i) cost += uint64_t(std::abs(int(int8_t(trial[i]))));
      if (cost < best_cost) best_cost = cost, best_type = type, best.swap(trial);
    }
    out.push_back(char(best_type));
    out.append(reinterpret_cast<const char*>(best.data()), stride);
  }
}

// zlib's level 3: on the shipped previews within -5%..+9% of level 6's size
// for a third of its time (docs/decisions/noise-set-speed.md).
constexpr int kZlibLevel = 3;

// An RGB8 PNG: signature, IHDR, sRGB, one IDAT (zlib at a fixed level, so the
// bytes depend only on the pixels), IEND. No time or text chunks.
void write_png_rgb8(const std::string& path, const std::vector<uint8_t>& rgb, int width,
                    int height) {
  std::string ihdr;
  append_u32_be(ihdr, uint32_t(width));
  append_u32_be(ihdr, uint32_t(height));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, deflate, adaptive, no interlace
  std::string raw;
  filter_rows(rgb, width, height, raw);
  uLongf packed_size = compressBound(uLong(raw.size()));
  std::string idat(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(idat.data()), &packed_size,
                reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), kZlibLevel) != Z_OK)
    throw IoError(fmt::format("{}: cannot compress the PNG pixels", path));
  idat.resize(packed_size);

  std::string file("\x89PNG\r\n\x1a\n", 8);
  put_chunk(file, "IHDR", ihdr);
  put_chunk(file, "sRGB", std::string(1, '\0'));  // perceptual rendering intent
  put_chunk(file, "IDAT", idat);
  put_chunk(file, "IEND", "");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(file.data(), std::streamsize(file.size()));
  out.close();
  if (!out) {
    const std::string reason = std::strerror(errno);
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: cannot write PNG: {}", path, reason));
  }
}

}  // namespace

std::string preview_range_label(double lo, double hi, bool stretched) {
  if (lo == hi) return fmt::format("{} EVERYWHERE", float(lo));
  if (stretched) return fmt::format("{:.2f}-{:.2f} STRETCHED", lo, hi);
  return "";
}

std::vector<int> preview_slices(int depth, int max_slices) {
  const int n = max_slices > 0 ? std::min(depth, max_slices) : depth;
  std::vector<int> z(n);
  for (int i = 0; i < n; ++i) z[i] = int((int64_t(i) * depth) / n);
  return z;
}

PreviewLayout preview_layout(const Texture& tex, const PreviewOptions& opt) {
  PreviewLayout layout;
  if (tex.is_volume())
    layout.panels = preview_slices(tex.depth, opt.max_slices);
  else
    for (int l = 0; l < tex.layers; ++l) layout.panels.push_back(l);
  const int n = int(layout.panels.size());
  layout.columns = std::min(n, std::max(opt.max_columns, 1));
  layout.rows = (n + layout.columns - 1) / layout.columns;
  const int tiles = opt.tile_2x2 ? 2 : 1;
  const int sub_panels = opt.split_channels ? shown_channels(tex, opt) : 1;
  // Whole pixels per texel, each axis to min_side (ceil(min_side / side)).
  layout.scale_x = std::max(1, (opt.min_side + tex.width - 1) / tex.width);
  layout.scale_y = std::max(1, (opt.min_side + tex.height - 1) / tex.height);
  layout.label_height = (opt.label_channels && opt.split_channels ? 2 * kLabelLine : 0) +
                        (opt.panel_labels.empty() ? 0 : kLabelLine);
  layout.cell_width = tex.width * layout.scale_x * tiles * sub_panels;
  layout.cell_height = tex.height * layout.scale_y * tiles + layout.label_height;
  layout.width = layout.columns * layout.cell_width;
  layout.height = layout.rows * layout.cell_height;
  return layout;
}

void write_png_preview(const std::string& path, const Texture& tex, const PreviewOptions& opt) {
  if (tex.width < 1 || tex.height < 1 || tex.depth < 1 || tex.layers < 1 || tex.channels.empty() ||
      tex.data.size() != tex.texel_count() * tex.channels.size())
    throw IoError(fmt::format("{}: expected a non-empty texture, got {} with {} channels", path,
                              tex.shape_string(), tex.channels.size()));
  if (tex.is_volume() && tex.is_array())
    throw IoError(fmt::format("{}: expected a volume or a 2D array, got both ({})", path,
                              tex.shape_string()));
  if (opt.finite == FiniteCheck::run) check_finite(tex, path);
  const PreviewLayout layout = preview_layout(tex, opt);
  const int shown = shown_channels(tex, opt);
  const Exposure common = opt.exposure ? Exposure{*opt.exposure} : auto_exposure(tex, layout, shown);
  std::vector<Exposure> e(size_t(shown), common);
  std::vector<std::string> ranges;
  if (opt.label_channels && opt.split_channels)
    for (int c = 0; c < shown; ++c) {
      const auto [lo, hi] = channel_range(tex, layout, c);
      const bool stretched = stretches(opt, lo, hi);
      if (stretched) e[c] = {1.0 / (double(hi) - lo), -double(lo) / (double(hi) - lo)};
      ranges.push_back(preview_range_label(lo, hi, stretched));
    }
  std::vector<uint8_t> rgb(size_t(layout.width) * layout.height * 3, 0);
  for (int k = 0; k < int(layout.panels.size()); ++k) draw_panel(rgb, layout, tex, opt, e, k);
  if (layout.label_height > 0) draw_labels(rgb, layout, tex, opt, ranges);

  write_png_rgb8(path, rgb, layout.width, layout.height);
}

}  // namespace skybake
