// The output textures of bake_bruneton and their metadata. See the header.
#include "atmosphere/bruneton_outputs.hpp"

#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometric_tail.hpp"
#include "atmosphere/phase.hpp"

namespace skybake {

namespace {

void set_common_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                         const BrunetonTextures& out) {
  set_meta(meta, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(meta, "top_radius_m", atm.top_radius_m);
  set_meta(meta, "orders", out.orders_used);
  set_meta(meta, "last_residual", out.last_residual);
  set_meta(meta, "tolerance", spec.tolerance);
  set_meta(meta, "geometric_tail",
           geometric_tail_metadata(spec.tolerance > 0.0 && spec.geometric_tail, out.tail_factor));
  set_meta(meta, "units", std::string("relative to the sun_illuminance of the preset"));
}

// Orders >= 2 are stored divided by p_R at the unclamped nu of their slice
// (scattering_orders.hpp "Storage of orders >= 2"; scattering_texel_grid):
// nu_k = -1 + 2 k / (nu_size - 1), from -1 to 1.
void set_rayleigh_divisor_metadata(Metadata& meta) {
  set_meta(meta, "rayleigh_divisor_nu_range", glm::dvec2(-1.0, 1.0));
  set_meta(meta, "rayleigh_divisor_nu_clamped", 0);
  set_meta(meta, "rayleigh_divisor",
           "RGB holds single Rayleigh without phase + orders >= 2 divided by p_R(nu_k) = 3 (1 + "
           "nu_k^2) / (16 pi), nu_k = -1 + 2 k / (nu_size - 1) the nu of slice k as it is, not "
           "clamped to the [mu mu_s - s, mu mu_s + s] (s = sqrt((1 - mu^2) (1 - mu_s^2))) that "
           "the texel's own scattering is computed at");
}

void set_scattering_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                             const BrunetonTextures& out, const ScatteringPhases& phases,
                             bool is_mie) {
  set_meta(meta, "parameterization", std::string("bruneton_4d_scattering"));
  set_common_metadata(meta, atm, spec, out);
  set_scattering_shape_metadata(meta, out.shape);
  set_meta(
      meta, "channel_layout",
      std::string("width = nu_size*mu_s_size, height = mu_size, depth = r_size; texel (x, y, "
                  "z): nu index x / mu_s_size, mu_s index x % mu_s_size, mu index y, r index z"));
  set_meta(
      meta, "mapping",
      std::string(
          "coord(x, n) = 0.5/n + x*(1 - 1/n); H = sqrt(Rt^2 - Rb^2), rho = sqrt(r^2 - Rb^2); "
          "u_r = coord(rho/H, r_size); ground rays: d = -r*mu - sqrt(r^2*(mu^2 - 1) + Rb^2), "
          "u_mu = 0.5 - 0.5*coord((d - (r - Rb))/(rho - (r - Rb)), mu_size/2) (0 when rho == r "
          "- Rb); other rays: d = -r*mu + sqrt(r^2*(mu^2 - 1) + Rt^2), u_mu = 0.5 + "
          "0.5*coord((d - (Rt - r))/(rho + H - (Rt - r)), mu_size/2); a(m) = (-Rb*m + "
          "sqrt(Rb^2*m^2 + H^2) - (Rt - Rb))/(H - (Rt - Rb)), A = a(mu_s_min), u_mu_s = "
          "coord(max(1 - a(mu_s)/A, 0)/(1 + a(mu_s)), mu_s_size); u_nu = (nu + 1)/2, slice k "
          "at nu = -1 + 2k/(nu_size - 1), lerp between slices (Bruneton 2017)"));
  set_meta(meta, "rayleigh_scattering_per_m", phases.rayleigh_per_m);
  set_meta(meta, "mie_scattering_per_m", phases.mie_per_m);
  set_meta(meta, "mie_phase",
           std::string(phases.mie_phase == PhaseKind::henyey_greenstein ? "henyey_greenstein"
                                                                        : "cornette_shanks"));
  set_meta(meta, "mie_g", phases.mie_g);
  set_meta(meta, "ray_nodes", spec.ray_nodes);
  set_meta(meta, "density_directions", spec.density_directions);
  if (is_mie) {
    set_meta(meta, "quantity",
             std::string("single Mie scattering without its phase function, RGB; radiance = "
                         "p_M(nu) * RGB"));
    return;
  }
  if (out.mid_texel_error >= 0.0) set_meta(meta, "mid_texel_error", out.mid_texel_error);
  set_meta(meta, "mie_in_alpha", spec.combined_mie_alpha ? 1 : 0);
  set_rayleigh_divisor_metadata(meta);
  set_meta(
      meta, "quantity",
      std::string(spec.combined_mie_alpha
                      ? "RGB: single Rayleigh scattering without phase + multiple scattering / "
                        "p_R(nu); A: single Mie red without phase; radiance = p_R(nu)*RGB + "
                        "p_M(nu)*mie, mie = RGB*(A/R)*(beta_R.r/beta_M.r)*(beta_M/beta_R) "
                        "(Bodare & Sandberg eq. 19)"
                      : "RGB: single Rayleigh scattering without phase + multiple scattering "
                        "/ p_R(nu); radiance = p_R(nu)*RGB + p_M(nu)*single_mie"));
}

void set_irradiance_metadata(Metadata& meta, const Atmosphere& atm, const BrunetonSpec& spec,
                             const BrunetonTextures& out, const std::string& quantity) {
  set_meta(meta, "parameterization", std::string("bruneton_irradiance"));
  set_common_metadata(meta, atm, spec, out);
  set_meta(meta, "quantity", quantity);
  set_meta(meta, "width", spec.irradiance_width);
  set_meta(meta, "height", spec.irradiance_height);
  set_meta(meta, "mapping",
           std::string("coord(x, n) = 0.5/n + x*(1 - 1/n); u = coord(0.5 + 0.5*mu_s, width), "
                       "v = coord((r - Rb)/(Rt - Rb), height)"));
  set_meta(meta, "sun_angular_radius_rad", atm.sun_angular_radius_rad);
}

// The sky orders whose light the irradiance holds: E_1 .. E_N for N orders
// (scattering_orders.cpp take_irradiance: E_k comes from order k's sky),
// E_0 the direct sun when it is summed in.
void set_irradiance_orders_metadata(Metadata& meta, const BrunetonSpec& spec,
                                    const BrunetonTextures& out) {
  const int first = spec.irradiance_includes_direct ? 0 : 1, last = out.orders_used;
  const bool tail = spec.tolerance > 0.0 && spec.geometric_tail;
  set_meta(meta, "irradiance_orders", glm::ivec2(first, last));
  set_meta(meta, "irradiance_orders_note",
           fmt::format("sky orders {}..{} ({} scattering orders{}{}); Bruneton's reference Init(N) "
                       "holds sky orders 1..N-1, so this table matches its Init({})",
                       1, last, last, spec.irradiance_includes_direct ? ", plus the direct sun" : "",
                       tail ? ", order N times 1 + geometric_tail for the orders after it" : "",
                       last + 1));
}

}  // namespace

void assemble_bruneton_outputs(const Atmosphere& atm, const BrunetonSpec& spec,
                               const Texture& accumulated, Texture single_mie, Texture irradiance,
                               BrunetonTextures& out) {
  const ScatteringPhases phases = scattering_phases(atm);
  const size_t texel_count = accumulated.texel_count();
  out.scattering = Texture(accumulated.width, accumulated.height, accumulated.depth, 1,
                           spec.combined_mie_alpha ? std::vector<std::string>{"R", "G", "B", "A"}
                                                   : std::vector<std::string>{"R", "G", "B"});
  const int channels = out.scattering.channel_count();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, texel_count, size_t(1) << 14),
                    [&](const tbb::blocked_range<size_t>& ts) {
                      for (size_t t = ts.begin(); t != ts.end(); ++t) {
                        for (int c = 0; c < 3; ++c)
                          out.scattering.data[channels * t + c] = accumulated.data[3 * t + c];
                        if (spec.combined_mie_alpha)
                          out.scattering.data[channels * t + 3] = single_mie.data[3 * t];
                      }
                    });
  out.single_mie = std::move(single_mie);
  out.irradiance = std::move(irradiance);
  set_scattering_metadata(out.scattering.metadata, atm, spec, out, phases, false);
  set_scattering_metadata(out.single_mie.metadata, atm, spec, out, phases, true);
  set_irradiance_metadata(
      out.irradiance.metadata, atm, spec, out,
      spec.irradiance_includes_direct
          ? "ground irradiance on a horizontal surface, direct sunlight + sky orders 1..orders"
          : "indirect ground irradiance on a horizontal surface from the sky, orders 1..orders "
            "(add direct_irradiance, or E_sun*T(r, mu_s)*c(mu_s) from the transmittance LUT)");
  set_irradiance_metadata(out.direct_irradiance.metadata, atm, spec, out,
                          "direct sunlight on a horizontal surface, E_sun*T(r, mu_s)*c(mu_s), "
                          "c the cosine averaged over the sun's disk");
  set_meta(out.irradiance.metadata, "includes_direct", spec.irradiance_includes_direct ? 1 : 0);
  set_irradiance_orders_metadata(out.irradiance.metadata, spec, out);
}

}  // namespace skybake
