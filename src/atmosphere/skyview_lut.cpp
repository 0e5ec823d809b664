#include "atmosphere/skyview_lut.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/kernels/skyview_row_luminance.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/skyview_row_march.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {
namespace {

constexpr double kTwoPi = 2.0 * kPi;

// beta: angle between the nadir and the horizon as seen from radius r (the
// angular radius of the ground disk), cos(beta) = sqrt(r^2 - Rb^2) / r;
// written with atan2 to stay accurate at the ground where beta -> pi / 2.
// zenith_horizon = pi - beta: zenith angle of the horizon.
struct HorizonAngles {
  double beta;
  double zenith_horizon;
};

HorizonAngles horizon_angles(const Atmosphere& atm, double r) {
  const double rb = atm.bottom_radius_m;
  r = std::max(r, rb);
  // Far from the planet beta -> 0; keep a floor so the ground half stays invertible.
  const double beta = std::max(std::atan2(rb, safe_sqrt(r * r - rb * rb)), 1e-9);
  return {beta, kPi - beta};
}

double wrap_azimuth(double phi) {
  phi = std::fmod(phi, kTwoPi);
  if (phi < 0.0) phi += kTwoPi;
  return phi < kTwoPi ? phi : 0.0;  // -tiny + 2 pi rounds to 2 pi
}


}  // namespace

glm::dvec2 skyview_uv_from_view(const Atmosphere& atm, double r, SkyviewDirection view, int width,
                                int height) {
  const HorizonAngles a = horizon_angles(atm, r);
  const double theta = std::acos(clamp_cosine(view.mu));
  const double l = a.zenith_horizon - theta;  // latitude above the horizon
  const double x = l >= 0.0 ? 0.5 - 0.5 * std::sqrt(l / a.zenith_horizon)
                            : 0.5 + 0.5 * std::sqrt(std::min(-l / a.beta, 1.0));
  return {wrap_azimuth(view.azimuth_rad) / kTwoPi,
          texel_coord_from_unit(std::clamp(x, 0.0, 1.0), height)};
}

SkyviewDirection view_from_skyview_uv(const Atmosphere& atm, double r, glm::dvec2 uv, int width,
                                      int height) {
  const HorizonAngles a = horizon_angles(atm, r);
  const double x = std::clamp(unit_from_texel_coord(uv.y, height), 0.0, 1.0);
  const double theta = x < 0.5 ? a.zenith_horizon * (1.0 - (1.0 - 2.0 * x) * (1.0 - 2.0 * x))
                               : a.zenith_horizon + a.beta * (2.0 * x - 1.0) * (2.0 * x - 1.0);
  return {std::cos(theta), wrap_azimuth(kTwoPi * uv.x)};
}

glm::dvec2 skyview_texel_uv(const Atmosphere&, double, const SkyviewLutSpec& spec, int x, int y) {
  if (spec.convention == TableConvention::skybake)
    return {texel_center(x, spec.width), texel_center(y, spec.height)};
  // Hillaire's SkyViewLutParamsToUv: u = sqrt(0.5 - 0.5 cos phi) and the
  // latitude's x, each read through fromUnitToSubUvs.
  const double x_u = unit_of_texel(TexelPlacement::sub_uv, x, spec.width);
  const double phi = std::acos(demo_skyview_cos_azimuth_from_unit(x_u));
  return {phi / kTwoPi, skybake_coord_of_texel(TexelPlacement::sub_uv, y, spec.height)};
}

glm::dvec3 skyview_vector_from_direction(SkyviewDirection view) {
  const double sin_theta = safe_sqrt(1.0 - view.mu * view.mu);
  return {sin_theta * std::cos(view.azimuth_rad), sin_theta * std::sin(view.azimuth_rad),
          clamp_cosine(view.mu)};
}

SkyviewDirection skyview_direction_from_vectors(glm::dvec3 up, glm::dvec3 view_dir,
                                                glm::dvec3 sun_dir) {
  const double mu = clamp_cosine(glm::dot(view_dir, up));
  const glm::dvec3 view_h = view_dir - mu * up;
  glm::dvec3 sun_h = sun_dir - glm::dot(sun_dir, up) * up;
  if (glm::dot(sun_h, sun_h) < 1e-24) {
    // Sun at the zenith or nadir: every azimuth is alike; pick any reference.
    sun_h = glm::cross(up, std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
  }
  const glm::dvec3 forward = glm::normalize(sun_h);
  const glm::dvec3 side = glm::cross(up, forward);
  if (glm::dot(view_h, view_h) < 1e-30) return {mu, 0.0};
  return {mu, wrap_azimuth(std::atan2(glm::dot(view_h, side), glm::dot(view_h, forward)))};
}

namespace {

// The views' layers grouped by viewer radius: a row's march is shared by the
// layers at its radius (skyview_row_march.hpp).
struct LayersByRadius {
  std::vector<double> radii;
  std::vector<std::vector<int>> layers_at;
};

LayersByRadius group_layers_by_radius(const Atmosphere& atm, const SkyviewLutSpec& spec) {
  LayersByRadius g;
  for (int layer = 0; layer < int(spec.views.size()); ++layer) {
    const double r = atm.bottom_radius_m + std::max(spec.views[layer].altitude_m, 0.0);
    const auto it = std::find(g.radii.begin(), g.radii.end(), r);
    if (it == g.radii.end()) {
      g.radii.push_back(r);
      g.layers_at.push_back({layer});
    } else {
      g.layers_at[size_t(it - g.radii.begin())].push_back(layer);
    }
  }
  return g;
}

// Row y of every layer in `layers` (all at radius r): one march, then each
// layer's sun.
void bake_skyview_row(const Atmosphere& atm, const Texture& transmittance_lut,
                      const Texture& multiscattering_lut, const MultiscatteringMapping& mapping,
                      const SkyviewLutSpec& spec, double r, int y, const std::vector<int>& layers,
                      Texture& tex, ProgressCounter& progress) {
  const double v = skyview_texel_uv(atm, r, spec, 0, y).y;
  const double mu = view_from_skyview_uv(atm, r, {0.5, v}, spec.width, spec.height).mu;
  const SkyviewRowMarch row = march_skyview_row(atm, transmittance_lut, multiscattering_lut,
                                                mapping, r, mu, spec.steps, spec.distribution);
  // The sky is symmetric about the sun's vertical plane (the medium varies
  // with altitude only): texel width - 1 - x sees the mirror image of
  // texel x, so half the row is marched and mirrored.
  // Hillaire's half-circle layout holds each azimuth once: all of it.
  const bool mirrored = spec.convention == TableConvention::skybake;
  const int half = mirrored ? (spec.width + 1) / 2 : spec.width;
  // The row's view directions, the same for every layer at its radius.
  std::vector<double> cos_phi(size_t(half), 0.0), nu(size_t(half), 0.0);
  std::vector<glm::dvec3> view(static_cast<size_t>(half));
  for (int x = 0; x < half; ++x) {
    const SkyviewDirection d = view_from_skyview_uv(
        atm, r, {skyview_texel_uv(atm, r, spec, x, y).x, v}, spec.width, spec.height);
    view[x] = skyview_vector_from_direction(d);
    cos_phi[x] = std::cos(d.azimuth_rad);
  }
  std::vector<glm::dvec3> luminance(static_cast<size_t>(half));
  for (int layer : layers) {
    const double sun_zenith = spec.views[layer].sun_zenith_rad;
    const double cos_s = std::cos(sun_zenith), sin_s = std::sin(sun_zenith);
    const glm::dvec3 sun_dir(sin_s, 0.0, cos_s);
    for (int x = 0; x < half; ++x) nu[x] = clamp_cosine(glm::dot(view[x], sun_dir));
    if (mapping.nu_slices > 0) {
      // A view-dependent Psi_ms table: each texel reads its own nu slices.
      std::vector<glm::dvec3> scratch;
      for (int x = 0; x < half; ++x)
        luminance[size_t(x)] =
            skyview_texel_luminance(row, atm, transmittance_lut, multiscattering_lut, cos_phi[x],
                                    cos_s, sin_s, nu[x], scratch);
    } else {
      skyview_row_luminance(row, atm, transmittance_lut, multiscattering_lut, cos_phi.data(),
                            nu.data(), half, cos_s, sin_s, luminance.data());
    }
    for (int x = 0; x < half; ++x) {
      float* t = tex.texel(x, y, 0, layer);
      float* mirror = mirrored ? tex.texel(spec.width - 1 - x, y, 0, layer) : t;
      for (int c = 0; c < 3; ++c) t[c] = mirror[c] = float(luminance[x][c]);
    }
    progress.tick();
  }
}

void set_skyview_metadata(const Atmosphere& atm, const SkyviewLutSpec& spec, Metadata& m) {
  set_meta(m, "parameterization", std::string("hillaire2020_skyview"));
  set_meta(m, "u",
           std::string("azimuth_from_sun_plane_rad / (2 pi), texel i at 2 pi (i + 0.5) / "
                       "width, wraps"));
  set_meta(m, "v",
           std::string("texel_coord_from_unit(x, height); l = pi - beta - view_zenith; "
                       "x = 0.5 - 0.5 sqrt(l / (pi - beta)) if l >= 0 else "
                       "0.5 + 0.5 sqrt(-l / beta); beta = atan2(Rb, sqrt(r^2 - Rb^2))"));
  set_meta(m, "texel_coord_from_unit", std::string("0.5 / n + x * (1 - 1 / n)"));
  set_meta(m, "orientation", std::string("row 0 = zenith, last row = nadir; sun at azimuth 0"));
  if (spec.convention == TableConvention::hillaire_demo) {
    // Hillaire's SkyViewLutParamsToUv (both axes through fromUnitToSubUvs).
    set_meta(m, "convention", std::string("hillaire_demo"));
    set_meta(m, "u",
             std::string("texel_coord_from_unit(sqrt(0.5 - 0.5 cos(azimuth_from_sun_plane)), "
                         "width), the half circle, the sun at 0; clamp"));
    set_meta(m, "texel_coord_from_unit", std::string("(x * n + 0.5) / (n + 1)"));
  }
  set_meta(m, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(m, "top_radius_m", atm.top_radius_m);
  set_meta(m, "units", std::string("luminance, units of sun_illuminance; no sun disk"));
  set_meta(m, "steps", spec.steps);
  set_meta(m, "step_distribution",
           std::string(spec.distribution == StepDistribution::quadratic ? "quadratic" : "uniform"));
  // One pair of doubles per layer: the list's length varies, and EXR and VDB
  // have no list of doubles.
  for (size_t i = 0; i < spec.views.size(); ++i) {
    set_meta(m, fmt::format("layer.{}.altitude_m", i), spec.views[i].altitude_m);
    set_meta(m, fmt::format("layer.{}.sun_zenith_rad", i), spec.views[i].sun_zenith_rad);
  }
}

}  // namespace

Texture bake_skyview_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                         const Texture& multiscattering_lut, const SkyviewLutSpec& spec,
                         const BakeContext& ctx) {
  if (spec.width < 1 || spec.height < 2 || spec.views.empty())
    throw Error(
        fmt::format("skyview: expected a size of at least 1x2 and one view, got {}x{} "
                    "and {} views",
                    spec.width, spec.height, spec.views.size()));
  const int layers = int(spec.views.size());
  Texture tex(spec.width, spec.height, 1, layers, {"R", "G", "B"});
  const LayersByRadius groups = group_layers_by_radius(atm, spec);
  const MultiscatteringMapping mapping = multiscattering_mapping_of(multiscattering_lut);
  ProgressCounter progress(ctx, size_t(layers) * spec.height);
  tbb::parallel_for(0, int(groups.radii.size()) * spec.height, [&](int task) {
    const int group = task / spec.height, y = task % spec.height;
    bake_skyview_row(atm, transmittance_lut, multiscattering_lut, mapping, spec,
                     groups.radii[group], y, groups.layers_at[group], tex, progress);
  });
  set_skyview_metadata(atm, spec, tex.metadata);
  return tex;
}

glm::dvec3 lookup_skyview(const Texture& lut, int layer, const Atmosphere& atm, double r,
                          SkyviewDirection view) {
  const glm::dvec2 uv = skyview_uv_from_view(atm, r, view, lut.width, lut.height);
  return glm::dvec3(sample_bilinear(lut, uv.x, uv.y, 0, layer, true));
}

}  // namespace skybake
