// Table conventions of the Hillaire-family tables (transmittance,
// multiscattering, sky-view, aerial perspective): where each texel sits on
// the table's axes, so that a renderer reads it at the right physical point
// (docs/runtime.md "Using skybake's tables in a renderer derived from
// Hillaire's demo", docs/decisions/table-convention-key.md).
//
//   skybake        the tables' own layouts (each baker's header): texel i of
//                  n on a unit axis x in [0, 1] at x = i / (n - 1), read at
//                  u = 0.5 / n + x (1 - 1 / n) (Bruneton 2017
//                  GetTextureCoordFromUnitRange); the sky-view azimuth over
//                  the full circle, linear aerial-perspective slices.
//   hillaire_demo  the layouts the run-time reads of Hillaire's public demo
//                  (UnrealEngineSkyAtmosphere, Hillaire 2020) expect, at the
//                  shapes it hard-codes:
//     transmittance     u = x_mu, v = x_r read directly (the sub-uv remap of
//                       LutTransmittanceParamsToUv is off): texel i holds
//                       x = (i + 0.5) / n.
//     multiscattering   x read at u = (x n + 0.5) / (n + 1)
//                       (fromUnitToSubUvs), both axes linear; texel i holds
//                       x = ((i + 0.5)(n + 1) / n - 0.5) / n. A square table
//                       (one resolution constant for both axes).
//     sky-view          both axes through fromUnitToSubUvs like the
//                       multiscattering table; the azimuth over the half
//                       circle, x = sqrt(0.5 - 0.5 cos phi), the sun at x = 0;
//                       the latitude skybake's; 192 x 108.
//     aerial perspective  squared slices: slice k of n at distance
//                       ((k + 0.5) / n)^2 R, R = n x 4 km (32 slices, 128 km),
//                       read at w = sqrt(d / R); A = 1 - mean RGB
//                       transmittance (opacity); a froxel whose end lies
//                       within 10 m of the ground or below it is moved
//                       radially to 11 m above the ground and its path runs
//                       straight to there; 32 x 32 x 32.
// His writers place multiscattering and sky-view texels at x = i / (n - 1)
// while his readers expect the sub-uv positions above: the convention
// follows the readers, which is what a renderer runs every frame.
#pragma once

#include <optional>
#include <string>

#include "core/math.hpp"
#include "core/texture.hpp"

namespace skybake {

enum class TableConvention { skybake, hillaire_demo };

// "skybake", "hillaire_demo".
const char* table_convention_name(TableConvention c);
// Empty for another name.
std::optional<TableConvention> find_table_convention(const std::string& name);
// Throws Error for another name.
TableConvention table_convention_from_name(const std::string& name);
// The metadata key "convention" of a baked table; skybake when absent.
TableConvention table_convention_of(const Texture& lut);

// Where texel i of an n-texel axis sits on the unit axis x in [0, 1].
enum class TexelPlacement {
  ends,     // x = i / (n - 1): skybake's
  centres,  // x = (i + 0.5) / n: read at u = x
  sub_uv,   // x = ((i + 0.5)(n + 1) / n - 0.5) / n: read at u = (x n + 0.5) / (n + 1)
};

double unit_of_texel(TexelPlacement p, int i, int n);
// The texture coordinate at which a reader of placement p reads x.
double texture_coord_of_unit(TexelPlacement p, double x, int n);
// The texture coordinate of skybake's layout (texel_coord_from_unit) of the
// point texel i of placement p holds: what skybake's inverse mappings take.
// (i + 0.5) / n itself for ends, bit for bit.
double skybake_coord_of_texel(TexelPlacement p, int i, int n);

// The demo's shapes and constants (RenderSkyRayMarching.hlsl, RenderSkyCommon.hlsl).
constexpr int kDemoSkyviewWidth = 192;
constexpr int kDemoSkyviewHeight = 108;
constexpr int kDemoAerialSize = 32;            // froxels on each axis, AP_SLICE_COUNT slices
constexpr double kDemoAerialSliceM = 4e3;      // AP_KM_PER_SLICE
constexpr double kDemoGroundOffsetM = 10.0;    // PLANET_RADIUS_OFFSET
constexpr double kDemoGroundLiftM = 1.0;       // added above the offset when a froxel is moved

// Sky-view azimuth, hillaire_demo: x = sqrt(0.5 - 0.5 cos phi), phi in [0, pi]
// from the sun's vertical plane, and back.
double demo_skyview_unit_from_cos_azimuth(double cos_phi);
double demo_skyview_cos_azimuth_from_unit(double x);

// Aerial-perspective slices, hillaire_demo: slice k of n at ((k + 0.5) / n)^2
// range_m; a distance d read at w = sqrt(d / range_m).
double demo_aerial_slice_distance(int k, int n, double range_m);
double demo_aerial_w_from_distance(double d, double range_m);

}  // namespace skybake
