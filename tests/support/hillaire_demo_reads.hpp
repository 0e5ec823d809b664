// The run-time reads of Hillaire's public demo (UnrealEngineSkyAtmosphere,
// Hillaire 2020), written out independently of src/ from the demo's
// formulas, for the tests that check skybake's tables in the
// "hillaire_demo" convention: each function says which of his shader
// functions it stands for. Lengths in any one unit (his shaders use km,
// these are given m). Textures are sampled as his samplerLinearClamp does:
// bilinear (trilinear for a volume), clamp to edge. Header only.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "core/texture.hpp"

namespace skybake::demo_reads {

constexpr double kPiDemo = 3.14159265358979323846;

// His fromUnitToSubUvs: a unit value x read through a texture of n texels.
inline double sub_uv(double x, double n) { return (x + 0.5 / n) * (n / (n + 1.0)); }
// Its inverse: the unit value a texture coordinate holds for that read.
inline double unit_at_sub_uv(double u, double n) { return (u * (n + 1.0) - 0.5) / n; }

// LutTransmittanceParamsToUv: (view height, cos view zenith) -> uv, read as is.
inline glm::dvec2 transmittance_uv(double bottom, double top, double height, double cos_zenith) {
  const double h = std::sqrt(std::max(0.0, top * top - bottom * bottom));
  const double rho = std::sqrt(std::max(0.0, height * height - bottom * bottom));
  const double disc = height * height * (cos_zenith * cos_zenith - 1.0) + top * top;
  const double d = std::max(0.0, -height * cos_zenith + std::sqrt(std::max(disc, 0.0)));
  const double d_min = top - height, d_max = rho + h;
  return {(d - d_min) / (d_max - d_min), rho / h};
}

// UvToLutTransmittanceParams without its (commented-out) sub-uv line: the
// (height, cos zenith) a uv stands for.
inline glm::dvec2 transmittance_params(double bottom, double top, glm::dvec2 uv) {
  const double h = std::sqrt(top * top - bottom * bottom);
  const double rho = h * uv.y;
  const double height = std::sqrt(rho * rho + bottom * bottom);
  const double d_min = top - height, d_max = rho + h;
  const double d = d_min + uv.x * (d_max - d_min);
  const double mu = d == 0.0 ? 1.0 : (h * h - rho * rho - d * d) / (2.0 * height * d);
  return {height, std::clamp(mu, -1.0, 1.0)};
}

// GetMultipleScattering's uv at radius r for a sun of zenith cosine mu_s,
// MultiScatteringLUTRes = n.
inline glm::dvec2 multiscattering_uv(double bottom, double top, double r, double mu_s, int n) {
  const double x = std::clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
  const double y = std::clamp((r - bottom) / (top - bottom), 0.0, 1.0);
  return {sub_uv(x, n), sub_uv(y, n)};
}

// SkyViewLutParamsToUv (NONLINEARSKYVIEWLUT on) at viewer radius r: cos
// view zenith, cos of the azimuth between the view and the sun (his
// lightViewCosAngle), whether the view meets the ground; a w x h table.
inline glm::dvec2 skyview_uv(double bottom, double r, bool hits_ground, double cos_zenith,
                             double cos_light_view, int w = 192, int h = 108) {
  const double v_horizon = std::sqrt(std::max(0.0, r * r - bottom * bottom));
  const double beta = std::acos(v_horizon / r);
  const double zenith_horizon = kPiDemo - beta;
  const double theta = std::acos(std::clamp(cos_zenith, -1.0, 1.0));
  double y;
  if (!hits_ground) {
    const double c = 1.0 - std::sqrt(std::max(0.0, 1.0 - theta / zenith_horizon));
    y = 0.5 * c;
  } else {
    y = 0.5 * std::sqrt(std::max(0.0, (theta - zenith_horizon) / beta)) + 0.5;
  }
  const double x = std::sqrt(std::max(0.0, -cos_light_view * 0.5 + 0.5));
  return {sub_uv(x, w), sub_uv(y, h)};
}

// The view (cos zenith, cos light-view azimuth) the reader above maps to a
// uv: his UvToSkyViewLutParams with the reader's sub-uv inverse.
inline glm::dvec2 skyview_params(double bottom, double r, glm::dvec2 uv, int w = 192,
                                 int h = 108) {
  const double x = unit_at_sub_uv(uv.x, w), y = unit_at_sub_uv(uv.y, h);
  const double v_horizon = std::sqrt(std::max(0.0, r * r - bottom * bottom));
  const double beta = std::acos(v_horizon / r);
  const double zenith_horizon = kPiDemo - beta;
  double cos_zenith;
  if (y < 0.5) {
    const double c = 1.0 - 2.0 * y;
    cos_zenith = std::cos(zenith_horizon * (1.0 - c * c));
  } else {
    const double c = 2.0 * y - 1.0;
    cos_zenith = std::cos(zenith_horizon + beta * c * c);
  }
  return {cos_zenith, -(x * x * 2.0 - 1.0)};
}

// The aerial-perspective read of RenderRayMarchingPS (FASTAERIALPERSPECTIVE):
// slice = d / km_per_slice, before half a slice the read is taken at half a
// slice and scaled by 2 slice; w = sqrt(slice / slices).
struct AerialRead {
  double w;
  double weight;
};
inline AerialRead aerial_read(double distance, double per_slice, int slices = 32) {
  double slice = distance / per_slice, weight = 1.0;
  if (slice < 0.5) {
    weight = std::clamp(slice * 2.0, 0.0, 1.0);
    slice = 0.5;
  }
  return {std::sqrt(slice / slices), weight};
}

// RenderCameraVolumePS: slice k's distance, ((k + 0.5) / slices)^2 slices per_slice.
inline double aerial_slice_distance(int k, double per_slice, int slices = 32) {
  const double s = (k + 0.5) / slices;
  return s * s * slices * per_slice;
}

// RenderCameraVolumePS's ground: a froxel end within `offset` of the ground
// (or below) is moved radially to offset + lift above it. Returns the new
// end point (planet-centred), or `end` itself.
inline glm::dvec3 aerial_ground_move(glm::dvec3 end, double bottom, double offset, double lift) {
  if (glm::length(end) > bottom + offset) return end;
  return glm::normalize(end) * (bottom + offset + lift);
}

// samplerLinearClamp on a 2D texture (one layer of an array).
inline glm::dvec4 sample_clamp(const Texture& t, double u, double v, int layer = 0, int z = 0) {
  const auto axis = [](double c, int n, int& i0, int& i1, double& f) {
    const double x = std::clamp(c * n - 0.5, 0.0, double(n - 1));
    i0 = int(std::floor(x));
    i1 = std::min(i0 + 1, n - 1);
    f = x - i0;
  };
  int x0, x1, y0, y1;
  double fx, fy;
  axis(u, t.width, x0, x1, fx);
  axis(v, t.height, y0, y1, fy);
  glm::dvec4 out(0.0);
  const int channels = std::min(4, t.channel_count());
  for (int c = 0; c < channels; ++c) {
    const double a = t.at(x0, y0, z, layer, c) * (1 - fx) + t.at(x1, y0, z, layer, c) * fx;
    const double b = t.at(x0, y1, z, layer, c) * (1 - fx) + t.at(x1, y1, z, layer, c) * fx;
    out[c] = a * (1 - fy) + b * fy;
  }
  return out;
}

// samplerLinearClamp on a volume.
inline glm::dvec4 sample_clamp_3d(const Texture& t, double u, double v, double w) {
  const double z = std::clamp(w * t.depth - 0.5, 0.0, double(t.depth - 1));
  const int z0 = int(std::floor(z)), z1 = std::min(z0 + 1, t.depth - 1);
  const double f = z - z0;
  return sample_clamp(t, u, v, 0, z0) * (1 - f) + sample_clamp(t, u, v, 0, z1) * f;
}

}  // namespace skybake::demo_reads
