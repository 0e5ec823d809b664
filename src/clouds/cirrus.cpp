#include "clouds/cirrus.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "clouds/field_stats.hpp"
#include "core/error.hpp"
#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"  // cell_coord_from_texel

namespace skybake {

namespace {

constexpr uint32_t kStreakStream = 0x63697272;  // "cirr"
constexpr uint32_t kCellStream = 0x63656c6c;    // "cell"
constexpr uint32_t kSheetStream = 0x73686565;   // "shee"

struct LayerName {
  const char* field;
  const CirrusLayer CirrusSpec::*layer;
};
constexpr LayerName kLayers[3] = {{"streaks", &CirrusSpec::streaks},
                                  {"cirrocumulus", &CirrusSpec::cirrocumulus},
                                  {"altostratus", &CirrusSpec::altostratus}};

glm::vec2 cells_at(const CirrusLayer& l, int x, int y, const CirrusSpec& s) {
  return {cell_coord_from_texel(x, s.width, l.period.x),
          cell_coord_from_texel(y, s.height, l.period.y)};
}

// The layer with the octaves that alias dropped (field_stats.hpp).
CirrusLayer within_size(CirrusLayer l, const CirrusSpec& s) {
  l.octaves = std::min(octaves_within_size(l.period.x, l.octaves, s.width),
                       octaves_within_size(l.period.y, l.octaves, s.height));
  return l;
}

}  // namespace

std::vector<SpecProblem> spec_problems(const CirrusSpec& spec) {
  std::vector<SpecProblem> out;
  if (spec.width < 2 || spec.width > 8192 || spec.height < 2 || spec.height > 8192)
    out.push_back(
        {"size", fmt::format("expected 2 .. 8192 per axis, got {}x{}", spec.width, spec.height)});
  for (const LayerName& l : kLayers) {
    const CirrusLayer& layer = spec.*(l.layer);
    const std::string at = l.field;
    for (int axis = 0; axis < 2; ++axis)
      if (layer.period[axis] < 1 || layer.period[axis] > 256)
        out.push_back({fmt::format("{}.period[{}]", at, axis),
                       fmt::format("expected 1 .. 256 cells, got {}", layer.period[axis])});
    if (layer.octaves < 1 || layer.octaves > kMaxOctaves)
      out.push_back(
          {at + ".octaves", fmt::format("expected 1 .. {}, got {}", kMaxOctaves, layer.octaves)});
    if (!(layer.coverage >= 0.0 && layer.coverage <= 1.0))
      out.push_back(
          {at + ".coverage", fmt::format("expected a value in [0, 1], got {}", layer.coverage)});
  }
  return out;
}

Texture bake_cirrus(const CirrusSpec& spec, const BakeContext& ctx) {
  const auto problems = spec_problems(spec);
  if (!problems.empty())
    throw Error(fmt::format("cirrus: {}: {}", problems[0].field, problems[0].message));
  const int w = spec.width, h = spec.height;
  const size_t count = size_t(w) * size_t(h);
  TexelVector streaks(count), cells(count), sheets(count);
  const uint32_t streak_seed = stream_seed(spec.seed, kStreakStream);
  const uint32_t cell_seed = stream_seed(spec.seed, kCellStream);
  const uint32_t sheet_seed = stream_seed(spec.seed, kSheetStream);
  const CirrusLayer s = within_size(spec.streaks, spec);
  const CirrusLayer c = within_size(spec.cirrocumulus, spec);
  const CirrusLayer a = within_size(spec.altostratus, spec);
  ProgressCounter progress(ctx, size_t(h));
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      streaks[i] =
          1.0f - std::abs(perlin_fbm2(cells_at(s, x, y, spec), s.period, s.octaves, streak_seed));
      cells[i] = worley_fbm2(cells_at(c, x, y, spec), c.period, c.octaves, cell_seed);
      sheets[i] = perlin_fbm2(cells_at(a, x, y, spec), a.period, a.octaves, sheet_seed);
    }
    progress.tick();
  });
  keep_top_fraction(streaks, spec.streaks.coverage);
  keep_top_fraction(cells, spec.cirrocumulus.coverage);
  keep_top_fraction(sheets, spec.altostratus.coverage);

  Texture tex(w, h, 1, 1, {"R", "G", "B"});
  for (size_t i = 0; i < count; ++i) {
    tex.data[3 * i] = streaks[i];
    tex.data[3 * i + 1] = cells[i];
    tex.data[3 * i + 2] = sheets[i];
  }
  Metadata& m = tex.metadata;
  set_meta(m, "product", "cirrus");
  set_meta(m, "tiling", "periodic on x, y");
  set_meta(m, "seed", int(spec.seed));  // at most 2^31 - 1 (the schemas): an int
  set_meta(m, "channel.R", "cirrus streaks: ridged Perlin fBm 1 - |n|, fibres along x");
  set_meta(m, "channel.G", "cirrocumulus cells: inverted Worley fBm");
  set_meta(m, "channel.B", "altostratus sheets: Perlin fBm");
  const char* channels[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const CirrusLayer& l = spec.*(kLayers[c].layer);
    set_meta(m, fmt::format("period.{}", channels[c]), l.period);
    set_meta(m, fmt::format("octaves.{}", channels[c]), l.octaves);
    set_meta(m, fmt::format("octaves_used.{}", channels[c]), within_size(l, spec).octaves);
    set_meta(m, fmt::format("coverage.{}", channels[c]), l.coverage);
  }
  set_meta(m, "encoding",
           "per channel clamp((v - q) / (max - q), 0, 1), q chosen so that a fraction coverage "
           "of the texels is above 0");
  return tex;
}

}  // namespace skybake
