#include "clouds/height_gradients.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

namespace {
const char* const kChannelNames[4] = {"R", "G", "B", "A"};
const char* const kTypeNames[4] = {"stratus", "stratocumulus", "cumulus", "cumulonimbus"};
}  // namespace

std::vector<SpecProblem> spec_problems(const HeightGradientsSpec& spec) {
  std::vector<SpecProblem> out;
  if (spec.height < 1 || spec.height > 4096)
    out.push_back({"size", fmt::format("expected 1 .. 4096 rows, got {}", spec.height)});
  for (int c = 0; c < 4; ++c)
    for (const SpecProblem& p : ramp_problems(spec.ramps[c], kTypeNames[c])) out.push_back(p);
  return out;
}

Texture bake_height_gradients(const HeightGradientsSpec& spec) {
  const auto problems = spec_problems(spec);
  if (!problems.empty())
    throw Error(fmt::format("height_gradients: {}: {}", problems[0].field, problems[0].message));
  Texture tex(1, spec.height, 1, 1, {"R", "G", "B", "A"});
  for (int j = 0; j < spec.height; ++j) {
    const double h = height_from_row(j, spec.height);
    for (int c = 0; c < 4; ++c)
      tex.at(0, j, 0, 0, c) = float(compute_height_density(spec.ramps[c], h));
  }
  Metadata& m = tex.metadata;
  set_meta(m, "product", "height_gradients");
  set_meta(m, "v", "v = h, row 0 = bottom of the layer, row j holds h = (j + 0.5) / rows");
  for (int c = 0; c < 4; ++c) {
    const HeightRamp& r = spec.ramps[c];
    set_meta(m, fmt::format("channel.{}", kChannelNames[c]),
             fmt::format("{} density: smoothstep({}, {}, h) - smoothstep({}, {}, h)", kTypeNames[c],
                         r.a, r.b, r.c, r.d));
  }
  return tex;
}

}  // namespace skybake
