// The weather map: where clouds are, whether they rain, and of which type
// (Schneider, GPU Pro 7 sec. 4.3.3 and SIGGRAPH 2015 slides; Hillaire 2016
// sec. 5.3.1 for the Frostbite variant). A tileable 2D texture covering
// world_size_km x world_size_km (60 km in Horizon Zero Dawn), repeated over
// the world.
//
// Layouts (channels, values in [0, 1]):
//   schneider  R coverage, G precipitation, B cloud type (0 stratus,
//              0.5 stratocumulus, 1 cumulus).
//   frostbite  R density (the coverage), G type coordinate into the
//              cloud_types texture: u = (index + 0.5) / type_count with the
//              fractional type index 0 stratus, 1 stratocumulus, 2 cumulus,
//              3 cumulonimbus (cloud_types.hpp type_u_from_index).
//
// Signals, each a periodic Perlin fBm (noise/fbm.hpp; gain 0.5) with an
// integer number of cells across the map, period = round(world_size_km /
// feature_km), so every signal tiles; each is divided by its largest |value|
// over the map, so n in [-1, 1]:
//   coverage       c = clamp(0.5 + contrast (n_c - t), 0, 1), then the rain rule.
//                  The threshold t is solved on the baked texels (bisection on
//                  the exact mean, which falls monotonically with t) so that
//                  the mean of the final R equals coverage.mean: error below
//                  1e-6 in float data, half an 8-bit step in unorm8 files.
//   precipitation m = (1 - correlation) n_p + correlation n_c (rain follows
//                  the thick clouds); p = 1 on the round(area N) texels of
//                  largest m, a linear ramp down to 0 over the next
//                  round(edge N) texels' range of m, 0 elsewhere (N texels).
//                  area 0 = no precipitation anywhere.
//   type           clamp(mean + variation n_t, 0, 1), then the rain rule.
//
// The rain rule (Schneider: "where the chance of rain is 100%, we bias cloud
// type to cumulonimbus and cloud coverage to at least 70%"), on EVERY texel:
//   coverage = max(c, 0.7 p)           -> p = 1 gives coverage >= 0.7
//   type     = (1 - p) type + p        -> p = 1 gives type = 1 exactly
// In Schneider's layout cumulonimbus is not a B value of its own: B = 1 is
// the tall (cumulus) end, and a texel with G = 1 and B = 1 is a
// cumulonimbus; engines with a cumulonimbus gradient select it by G. In the
// Frostbite layout the index moves to the cumulonimbus column itself:
//   index = (1 - p) 2 type + 3 p       -> p = 1 gives index 3 exactly.
//
// Octaves whose cells would span fewer than 2 texels are dropped (recorded
// in the metadata as octaves_used.*): they would only alias.
// Threading: tbb::parallel_for over rows; the threshold search sums per-row
// partial sums in row order, so the output is identical for any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/bake_context.hpp"
#include "core/texture.hpp"
#include "noise/noise_volume.hpp"  // SpecProblem

namespace skybake {

enum class WeatherLayout { schneider, frostbite };

// Coverage never goes below kRainCoverage * precipitation (Schneider 4.3.3).
constexpr float kRainCoverage = 0.7f;

struct WeatherCoverage {
  double mean = 0.5;         // mean coverage of the map, [0, 1]
  double feature_km = 12.0;  // size of the largest cloud features, km
  int octaves = 4;           // fBm octaves, 1 .. 8
  double contrast = 2.0;     // slope of the cloud edge: > 0; larger = sharper edges
};

struct WeatherPrecipitation {
  double area = 0.0;         // fraction of the map where precipitation is 1, [0, 1]
  double edge = 0.05;        // fraction of the map in the ramp around it, [0, 1 - area]
  double feature_km = 20.0;  // size of rain regions, km
  int octaves = 3;           // fBm octaves, 1 .. 8
  double correlation = 0.5;  // weight of the coverage noise in the rain noise, [0, 1]
};

struct WeatherType {
  double mean = 0.5;         // mean cloud type: 0 stratus, 0.5 stratocumulus, 1 cumulus
  double variation = 0.3;    // half range of the type noise around the mean, [0, 1]
  double feature_km = 30.0;  // size of regions of one type, km
  int octaves = 2;           // fBm octaves, 1 .. 8
};

struct WeatherSpec {
  int size = 512;               // texels per axis (square map)
  uint32_t seed = 0;            // any value; same seed, same map
  double world_size_km = 60.0;  // the map covers world_size_km on each axis
  WeatherLayout layout = WeatherLayout::schneider;
  int type_count = 4;  // frostbite: columns of the cloud_types texture, >= 4
  WeatherCoverage coverage;
  WeatherPrecipitation precipitation;
  WeatherType type;
};

std::vector<SpecProblem> spec_problems(const WeatherSpec& spec);

// Cells across the map for a feature size, >= 1, and the feature size those
// cells really give (the inverse on the integer periods).
int period_from_feature_km(double world_size_km, double feature_km);
inline double feature_km_from_period(double world_size_km, int period) {
  return world_size_km / period;
}

// The rain rule (see above).
inline float coverage_with_rain(float coverage, float precipitation) {
  return coverage > kRainCoverage * precipitation ? coverage : kRainCoverage * precipitation;
}
inline float type_with_rain(float type, float precipitation) {
  return (1.0f - precipitation) * type + precipitation;
}
// Fractional index into the cloud_types columns for the Frostbite layout.
inline double frostbite_type_index(float type, float precipitation) {
  return (1.0 - double(precipitation)) * 2.0 * double(type) + 3.0 * double(precipitation);
}

// Channels "R", "G", "B" (schneider) or "R", "G" (frostbite); metadata:
// product, layout, world size and texel size, seed, per signal its period,
// octaves and achieved statistics, the rain rule, channel meanings.
// Throws Error when spec_problems() is not empty.
Texture bake_weather_map(const WeatherSpec& spec, const BakeContext& ctx);

}  // namespace skybake
