// The height gradients of the standard cloud types as one small table, for
// engines that blend them by weight (Schneider, GPU Pro 7 sec. 4.3.2: "at
// runtime we compute a weighted sum of the three functions", the weights
// coming from the weather map's cloud type, sec. 4.3.3).
//
//   R  stratus       G  stratocumulus       B  cumulus       A  cumulonimbus
//
// each the density profile smoothstep(a, b, h) - smoothstep(c, d, h) of
// height_profile.hpp with the preset's ramps (the same values as the R
// channel of the cloud_types texture's first four columns).
// Shape: 1 x `height` texels, RGBA, values in [0, 1]; row 0 is the bottom of
// the layer, row j holds h = (j + 0.5) / height (v = h). Pure function.
#pragma once

#include <array>

#include "clouds/height_profile.hpp"
#include "core/texture.hpp"

namespace skybake {

struct HeightGradientsSpec {
  int height = 128;  // rows, >= 1
  // stratus, stratocumulus, cumulus, cumulonimbus
  std::array<HeightRamp, 4> ramps = {
      default_cloud_types()[0].density, default_cloud_types()[1].density,
      default_cloud_types()[2].density, default_cloud_types()[3].density};
};

std::vector<SpecProblem> spec_problems(const HeightGradientsSpec& spec);

// Channels "R", "G", "B", "A"; metadata: product, channel meanings and
// ramps, the v mapping. Throws Error when spec_problems() is not empty.
Texture bake_height_gradients(const HeightGradientsSpec& spec);

}  // namespace skybake
