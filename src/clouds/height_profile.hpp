// Density-height profiles of cloud types (Schneider, GPU Pro 7 sec. 4.3.2) and
// the erosion amount over height (Hillaire 2016 sec. 5.3.1), shared by the
// cloud_types and height_gradients bakers.
//
// h is the normalized height in the cloud layer: 0 at its bottom, 1 at its
// top. The public ports of Schneider's three gradients write each one as
//
//   density(h) = smoothstep(a, b, h) - smoothstep(c, d, h)
//
// (docs/reference.md "Weather and cloud-type textures"): density rises from 0 at
// h = a to 1 at h = b, stays 1 up to c and falls back to 0 at d. With
// 0 <= a < b <= c < d <= 1 (ramp_problems) the value lies in [0, 1] and is
// exactly 0 for h <= a and h >= d: both smoothsteps are then exactly 0 or
// exactly 1. The erosion amount (0 smooth, 1 fully eroded by the detail
// noise) goes linearly from `erosion_base` at h = a to `erosion_top` at
// h = d and is constant outside.
#pragma once

#include <string>
#include <vector>

#include "noise/noise_volume.hpp"  // SpecProblem

namespace skybake {

struct HeightRamp {
  double a = 0.0;  // normalized height where density starts to rise from 0
  double b = 0.0;  // ... where it reaches 1
  double c = 1.0;  // ... where it starts to fall
  double d = 1.0;  // ... where it is back to 0
};

struct CloudTypeProfile {
  std::string name;           // "stratus", ...; lower-case, unique in a set
  HeightRamp density;         // density over normalized height
  double erosion_base = 0.5;  // erosion amount at h = density.a, in [0, 1]
  double erosion_top = 0.5;   // erosion amount at h = density.d, in [0, 1]
};

// The four standard types in texture order (x): stratus, stratocumulus,
// cumulus, cumulonimbus. Density ramps: the public ports of Schneider's
// gradients for the first three (docs/reference.md);
// cumulonimbus (0.01, 0.04, 0.9, 1.0) is ours: a column that fills the whole
// layer and is dense from near its base. Erosion: stratus 0.2 -> 0.4 (smooth
// sheets), stratocumulus 0.5 -> 0.6, cumulus 0.8 -> 0.6 (wispy bases,
// billowing tops, Schneider 4.3.4), cumulonimbus 0.7 -> 0.3 (smoother anvil).
// schemas/clouds.schema.json holds the same numbers as preset defaults.
std::vector<CloudTypeProfile> default_cloud_types();

// Hermite smoothstep: 0 for x <= e0, 1 for x >= e1, 3t^2 - 2t^3 between.
// Requires e0 < e1.
double smoothstep(double e0, double e1, double x);

// smoothstep(a, b, h) - smoothstep(c, d, h), in [0, 1] for a valid ramp.
double compute_height_density(const HeightRamp& ramp, double h);

// Erosion amount at h: erosion_base at h <= a, erosion_top at h >= d, linear between.
double compute_height_erosion(const CloudTypeProfile& type, double h);

// Normalized height of the centre of row j of `rows` (row 0 = bottom of the
// layer): h = (j + 0.5) / rows, and its inverse.
inline double height_from_row(int j, int rows) {
  return (j + 0.5) / rows;
}
inline double row_from_height(double h, int rows) {
  return h * rows - 0.5;
}

// Rules a ramp must follow: 0 <= a < b <= c < d <= 1, all finite. `field`
// names the ramp in messages ("types[1].density").
std::vector<SpecProblem> ramp_problems(const HeightRamp& ramp, const std::string& field);

// ramp_problems of every type, erosion in [0, 1], names non-empty and unique.
std::vector<SpecProblem> cloud_type_problems(const std::vector<CloudTypeProfile>& types);

}  // namespace skybake
