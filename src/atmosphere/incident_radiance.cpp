// The incident radiance of order k - 1 that the scattering density reads:
// the direction grid, its bands cut at the horizon, the ground's light and
// the ground rows per opacity. See the header and scattering_orders.hpp.
#include "atmosphere/incident_radiance.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/nu_slices.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

glm::dvec3 sun_direction(double mu_s) {
  return {safe_sqrt(1.0 - mu_s * mu_s), 0.0, mu_s};
}

}  // namespace

glm::dvec3 GroundIrradiance::irradiance(const Atmosphere& atm, const Texture& transmittance_lut,
                                        double mu_s) const {
  if (table) return lookup_irradiance(*table, atm, atm.bottom_radius_m, mu_s);
  return compute_direct_irradiance(atm, transmittance_lut, atm.bottom_radius_m, mu_s);
}

SphereGrid sphere_grid(int bands) {
  SphereGrid g;
  g.bands = std::max(1, bands);
  g.azimuths = 2 * g.bands;
  const double d_theta = kPi / g.bands, d_phi = 2.0 * kPi / g.azimuths;
  for (int l = 0; l < g.bands; ++l) {
    const double theta = (l + 0.5) * d_theta;
    const double area = d_phi * (std::cos(l * d_theta) - std::cos((l + 1) * d_theta));
    for (int m = 0; m < g.azimuths; ++m) {
      const double phi = (m + 0.5) * d_phi;
      g.directions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                std::cos(theta));
      g.solid_angle.push_back(area);
    }
  }
  return g;
}

// See the header for the parts and why.
std::vector<BandPart> band_parts(const Atmosphere& atm, double r, double theta0, double theta1,
                                 bool with_transmittance) {
  const double rb = atm.bottom_radius_m;
  const double horizon = kPi - std::asin(std::min(1.0, rb / r));  // zenith angle of the horizon
  const double width = theta1 - theta0;
  const int steps = theta0 - width < horizon && horizon < theta1 + width ? kIncidentSubBands : 1;
  std::vector<double> cuts;
  for (int k = 0; k <= steps; ++k) cuts.push_back(theta0 + width * k / steps);
  if (horizon > theta0 && horizon < theta1) {
    cuts.push_back(horizon);
    std::sort(cuts.begin(), cuts.end());
  }
  const double band = std::cos(theta0) - std::cos(theta1);
  std::vector<BandPart> parts;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (!(cuts[k + 1] > cuts[k])) continue;
    BandPart p;
    p.theta = 0.5 * (cuts[k] + cuts[k + 1]);
    p.share = (std::cos(cuts[k]) - std::cos(cuts[k + 1])) / band;
    const double mu = std::cos(p.theta);
    p.hits = ray_intersects_ground(rb, r, mu);
    if (p.hits) p.d = distance_to_bottom_boundary(rb, r, mu);
    if (p.hits && with_transmittance)
      p.T_ground = ray_transmittance(atm, r, mu, p.d, kGroundRayNodes);
    parts.push_back(p);
  }
  return parts;
}

std::vector<glm::dvec3> ground_row_opacity(const Atmosphere& atm, const ScatteringShape& shape) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  std::vector<glm::dvec3> opacity(size_t(shape.r_size) * shape.mu_size, glm::dvec3(0.0));
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int y = 0; y < shape.mu_size; ++y) {
      const size_t row = size_t(z) * shape.mu_size + y;
      if (!texels.ray_hits_ground[row]) continue;
      const double r = texels.r[z], mu = texels.mu[row];
      const double d = distance_to_bottom_boundary(atm.bottom_radius_m, r, mu);
      opacity[row] = 1.0 - ray_transmittance(atm, r, mu, d, kGroundRayNodes);
    }
  });
  return opacity;
}

Texture divide_ground_rows_by_opacity(const Texture& table, const ScatteringShape& shape,
                                      const std::vector<glm::dvec3>& opacity) {
  Texture out = table;
  divide_ground_rows_by_opacity_in_place(out, shape, opacity);
  return out;
}

void divide_ground_rows_by_opacity_in_place(Texture& out, const ScatteringShape& shape,
                                            const std::vector<glm::dvec3>& opacity) {
  const int channels = std::min(out.channel_count(), 3);
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int y = 0; y < shape.mu_size; ++y) {
      const glm::dvec3 o = opacity[size_t(z) * shape.mu_size + y];
      if (o == glm::dvec3(0.0)) continue;  // a sky row (or a ray of zero length)
      for (int x = 0; x < shape.texture_width(); ++x) {
        float* texel = out.texel(x, y, z);
        for (int c = 0; c < channels; ++c) texel[c] = o[c] > 0.0 ? float(texel[c] / o[c]) : 0.0f;
      }
    }
  });
}


std::vector<std::vector<BandPart>> grid_band_parts(const Atmosphere& atm, double r,
                                                   const SphereGrid& grid,
                                                   const ScatteringOrder& previous) {
  const bool ground_reflects = atm.ground_albedo != glm::dvec3(0.0);
  const double d_theta = kPi / grid.bands;
  std::vector<std::vector<BandPart>> parts(grid.bands);
  for (int l = 0; l < grid.bands; ++l)
    parts[l] = band_parts(atm, r, l * d_theta, (l + 1) * d_theta,
                          ground_reflects || previous.ground_rows_per_opacity);
  return parts;
}

std::vector<glm::dvec3> compute_incident_radiance(const Atmosphere& atm,
                                                  const Texture& transmittance_lut,
                                                  const ScatteringShape& shape,
                                                  const ScatteringOrder& previous,
                                                  const GroundIrradiance& ground, double r,
                                                  double mu_s, const SphereGrid& grid) {
  return compute_incident_radiance(atm, transmittance_lut, shape, previous, ground, r, mu_s, grid,
                                   grid_band_parts(atm, r, grid, previous));
}

std::vector<glm::dvec3> compute_incident_radiance(
    const Atmosphere& atm, const Texture& transmittance_lut, const ScatteringShape& shape,
    const ScatteringOrder& previous, const GroundIrradiance& ground, double r, double mu_s,
    const SphereGrid& grid, const std::vector<std::vector<BandPart>>& band_parts_at_r) {
  const double rb = atm.bottom_radius_m;
  const glm::dvec3 sun = sun_direction(mu_s);
  const glm::dvec3 albedo_over_pi = atm.ground_albedo / kPi;
  const bool ground_reflects = atm.ground_albedo != glm::dvec3(0.0);
  const double d_phi = 2.0 * kPi / grid.azimuths;
  const int half = grid.azimuths / 2;
  std::vector<glm::dvec3> L(grid.directions.size()), radiance(half);
  std::vector<double> cos_phi(half), sin_phi(half);
  for (int m = 0; m < half; ++m) {
    cos_phi[m] = std::cos((m + 0.5) * d_phi);
    sin_phi[m] = std::sin((m + 0.5) * d_phi);
  }
  NuSlices slices;
  for (int l = 0; l < grid.bands; ++l) {
    const std::vector<BandPart>& parts = band_parts_at_r[l];
    std::fill(radiance.begin(), radiance.end(), glm::dvec3(0.0));
    for (const BandPart& p : parts) {
      const double sin_t = std::sin(p.theta), mu = std::cos(p.theta);
      // r, mu and mu_s are the part's for every azimuth; only nu turns.
      slices.read(previous, shape,
                  scattering_taps(shape, scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s,
                                                                           1.0, p.hits)));
      // Azimuths m and azimuths - 1 - m mirror each other about the sun's plane.
      for (int m = 0; m < half; ++m) {
        const glm::dvec3 w(sin_t * cos_phi[m], sin_t * sin_phi[m], mu);
        const double nu = glm::dot(w, sun);
        glm::dvec3 part = slices.radiance_at_nu(previous, shape, nu);
        if (p.hits && previous.ground_rows_per_opacity) part *= 1.0 - p.T_ground;
        if (p.hits && ground_reflects) {
          const double mu_s_ground = clamp_cosine((r * mu_s + p.d * nu) / rb);
          part +=
              p.T_ground * albedo_over_pi * ground.irradiance(atm, transmittance_lut, mu_s_ground);
        }
        radiance[m] += p.share * part;
      }
    }
    for (int m = 0; m < half; ++m) {
      L[size_t(l) * grid.azimuths + m] = radiance[m];
      L[size_t(l) * grid.azimuths + (grid.azimuths - 1 - m)] = radiance[m];
    }
  }
  return L;
}

}  // namespace skybake
