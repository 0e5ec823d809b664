#include "verify/query_points.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/error_stats.hpp"
#include "core/math.hpp"

namespace skybake {

RadiusCosine transmittance_query(const Atmosphere& atm, size_t index) {
  // Any table size maps the unit square the same way: the mapping's inverse
  // is exact, so a 2x2 "table" turns (x_mu, x_r) into (r, mu).
  const glm::dvec2 uv(texel_coord_from_unit(query_unit(index, 0), 2),
                      texel_coord_from_unit(query_unit(index, 1), 2));
  RadiusCosine q;
  r_mu_from_transmittance_uv(atm, uv, 2, 2, q.r, q.mu);
  return q;
}

RadiusCosine multiscattering_query(const Atmosphere& atm, size_t index) {
  const double shell = atm.top_radius_m - atm.bottom_radius_m;
  return {atm.bottom_radius_m + query_unit(index, 10) * shell, 2.0 * query_unit(index, 11) - 1.0};
}

SkyviewQueryPoint skyview_query(const Atmosphere& atm, const std::vector<SkyviewView>& views,
                                size_t index) {
  const int layers = int(views.size());
  SkyviewQueryPoint q;
  q.layer = std::min(int(query_unit(index, 20) * layers), layers - 1);
  q.r = atm.bottom_radius_m + std::max(views[size_t(q.layer)].altitude_m, 0.0);
  q.view = {2.0 * query_unit(index, 21) - 1.0, 2.0 * kPi * query_unit(index, 22)};
  return q;
}

AerialQueryPoint aerial_query(const Atmosphere& atm, const AerialPerspectiveSpec& spec,
                              size_t index) {
  AerialQueryPoint q;
  q.position = {0.0, 0.0, atm.bottom_radius_m + std::max(spec.camera.altitude_m, 0.0)};
  q.screen_uv = {query_unit(index, 30), query_unit(index, 31)};
  q.view_dir = view_dir_from_screen_uv(spec.camera, q.screen_uv);
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, q.position, q.view_dir);
  const double reach =
      span.exits_on_ground ? std::min(span.t_exit, spec.depth_range_m) : spec.depth_range_m;
  q.distance_m = query_unit(index, 32) * reach;
  return q;
}

ViewQuery view_query(const Atmosphere& atm, size_t index, uint32_t first_dim, double mu_s_min) {
  ViewQuery q;
  const double u = query_unit(index, first_dim);
  q.altitude_m = (atm.top_radius_m - atm.bottom_radius_m) * u * u;
  q.r = atm.bottom_radius_m + q.altitude_m;
  q.mu = 2.0 * query_unit(index, first_dim + 1) - 1.0;
  q.mu_s = mu_s_min + (1.0 - mu_s_min) * query_unit(index, first_dim + 2);
  q.nu = nu_from_azimuth(q.mu, q.mu_s, 2.0 * kPi * query_unit(index, first_dim + 3));
  q.hits_ground = ray_intersects_ground(atm.bottom_radius_m, q.r, q.mu);
  return q;
}

double nu_from_azimuth(double mu, double mu_s, double phi) {
  return clamp_cosine(mu * mu_s + safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s)) * std::cos(phi));
}

RadiusCosine irradiance_query(const Atmosphere& atm, size_t index, double mu_s_min) {
  const double u = query_unit(index, 60);
  return {atm.bottom_radius_m + (atm.top_radius_m - atm.bottom_radius_m) * u * u,
          mu_s_min + (1.0 - mu_s_min) * query_unit(index, 61)};
}

AltitudeSunCosine gathering_query(const Atmosphere& atm, size_t index) {
  return {h_from_scattering3d_u(atm, texel_coord_from_unit(query_unit(index, 80), 2), 2),
          mu_s_from_scattering3d_u(texel_coord_from_unit(query_unit(index, 81), 2), 2)};
}

}  // namespace skybake
