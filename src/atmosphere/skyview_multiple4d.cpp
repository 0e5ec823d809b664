// Sky-view layers with the 4D iteration's orders >= 2; see the header.
#include "atmosphere/skyview_multiple4d.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "core/math.hpp"

namespace skybake {

glm::dvec3 lookup_field_multiple_scattering(const Atmosphere& atm, const ConvergedField& field,
                                            double r, SkyviewDirection view,
                                            double sun_zenith_rad) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  const glm::dvec3 w = skyview_vector_from_direction(view);
  const glm::dvec3 sun(std::sin(sun_zenith_rad), 0.0, std::cos(sun_zenith_rad));
  const double mu = clamp_cosine(w.z), mu_s = clamp_cosine(sun.z);
  const double nu = clamp_cosine(glm::dot(w, sun));
  const bool hits = ray_intersects_ground(atm.bottom_radius_m, r, mu);
  const ScatteringOrder multiple{nullptr, nullptr, &field.multiple, &field.phases};
  return glm::max(multiple.radiance_at(atm, field.shape, r, mu, mu_s, nu, hits), glm::dvec3(0.0));
}

Texture bake_skyview_lut_multiple4d(const Atmosphere& atm, const Texture& transmittance_lut,
                                    const ConvergedField& field, const SkyviewLutSpec& spec,
                                    const BakeContext& ctx) {
  // Psi_ms = 0 everywhere: the march gives single scattering alone.
  const Texture no_multiscattering(2, 2, 1, 1, {"R", "G", "B"});
  Texture tex = bake_skyview_lut(atm, transmittance_lut, no_multiscattering, spec, ctx);
  const int layers = int(spec.views.size());
  tbb::parallel_for(0, layers * spec.height, [&](int row) {
    const int layer = row / spec.height, y = row % spec.height;
    const SkyviewView& v = spec.views[size_t(layer)];
    const double r = atm.bottom_radius_m + std::max(v.altitude_m, 0.0);
    for (int x = 0; x < spec.width; ++x) {
      const SkyviewDirection d = view_from_skyview_uv(
          atm, r, skyview_texel_uv(atm, r, spec, x, y), spec.width, spec.height);
      const glm::dvec3 m = lookup_field_multiple_scattering(atm, field, r, d, v.sun_zenith_rad);
      float* t = tex.texel(x, y, 0, layer);
      for (int c = 0; c < 3; ++c) t[c] = float(double(t[c]) + m[c]);
    }
  });
  Metadata& meta = tex.metadata;
  set_meta(meta, "multiple_scattering", std::string("scattering4d"));
  set_meta(meta, "multiple_scattering_source",
           std::string("orders >= 2 of a 4D order iteration in memory (sum of DeltaS_k with the "
                       "geometric tail), read at each texel's (r, mu, mu_s, nu)"));
  set_meta(meta, "scattering_shape",
           std::to_string(field.shape.r_size) + "x" + std::to_string(field.shape.mu_size) + "x" +
               std::to_string(field.shape.mu_s_size) + "x" + std::to_string(field.shape.nu_size));
  set_meta(meta, "orders_used", field.orders_used);
  set_meta(meta, "last_residual", field.last_residual);
  set_meta(meta, "energy_out_over_in", field.energy_out_over_in);
  return tex;
}

}  // namespace skybake
