#include "atmosphere/sky_integrator.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/kernels/sun_and_psi_ms_reads.hpp"
#include "atmosphere/medium_block.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/segment_sources.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/kernels/exp_block.hpp"
#include "core/math.hpp"
#include "core/scratch.hpp"

namespace skybake {
namespace {

// One medium component as the march needs it: its profile, its coefficients
// and sigma_s * phase for this ray's scattering cosine (constant along a
// straight ray under a directional sun).
struct RayComponent {
  const DensityProfile* density;
  glm::dvec3 scattering;
  glm::dvec3 extinction;
  glm::dvec3 scattering_phase;
};

// segments_block's arrays, one entry per segment (end_*: per end), the first
// entries of each (core/scratch.hpp: kept from march to march, never shrunk).
struct BlockScratch {
  MediumBlock medium;
  std::vector<double> h, r, mu_s, density, em, end_r, end_mu_s;
  std::vector<glm::dvec3> sigma_s, sigma_t, sigma_s_phase, sun, ms, end_sun, end_ms;
};

struct MarchState {
  glm::dvec3 luminance{0.0};
  glm::dvec3 transmittance{1.0};
};

class RayMarcher {
 public:
  // `mapping`: the multiscattering table's, parsed by the caller, or null.
  RayMarcher(const Atmosphere& atm, const Texture& transmittance_lut,
             const Texture* multiscattering_lut, glm::dvec3 origin, glm::dvec3 dir,
             glm::dvec3 sun_dir, const MultiscatteringMapping* mapping = nullptr)
      : atm_(atm),
        tlut_(transmittance_lut),
        mslut_(multiscattering_lut),
        msmap_(!multiscattering_lut ? MultiscatteringMapping{}
               : mapping            ? *mapping
                                    : multiscattering_mapping_of(*multiscattering_lut)),
        origin_(origin),
        dir_(dir),
        sun_(sun_dir) {
    const double nu = clamp_cosine(glm::dot(dir, sun_dir));
    msview_ = multiscattering_view(msmap_, nu);
    components_.reserve(atm.components.size());
    for (const MediumComponent& c : atm.components) {
      const glm::dvec3 ext = c.scattering_per_m + c.absorption_per_m;
      if (ext == glm::dvec3(0.0) || c.density.layers.empty()) continue;  // absent: costs nothing
      components_.push_back({&c.density, c.scattering_per_m, ext,
                             c.scattering_per_m * phase_function(c.phase, c.g, nu)});
    }
  }

  bool empty() const { return components_.empty(); }

  // Integrates the segment [a, b] (distances from the origin) with the medium
  // sampled at its midpoint.
  void segment(double a, double b, MarchState& st) const {
    const double dt = b - a;
    if (!(dt > 0.0)) return;
    const glm::dvec3 p = origin_ + (0.5 * (a + b)) * dir_;
    const double r = std::max(glm::length(p), atm_.bottom_radius_m);
    const double h = r - atm_.bottom_radius_m;
    glm::dvec3 sigma_s(0.0), sigma_t(0.0), sigma_s_phase(0.0);
    for (const RayComponent& c : components_) {
      const double d = density_at(*c.density, h);
      if (d == 0.0) continue;
      sigma_s += d * c.scattering;
      sigma_t += d * c.extinction;
      sigma_s_phase += d * c.scattering_phase;
    }
    if (sigma_t == glm::dvec3(0.0)) return;  // empty here: no source, no attenuation
    const double mu_s = clamp_cosine(glm::dot(p, sun_) / r);
    glm::dvec3 source = lookup_sun_transmittance(tlut_, atm_, r, mu_s) * sigma_s_phase;
    if (mslut_)
      source += psi_ms(r, mu_s, glm::dot(p, dir_) / r) * sigma_s;  // eq. 11
    const SegmentWeights w = segment_weights(sigma_t, dt);
    st.luminance += st.transmittance * atm_.sun_illuminance * source * w.weight;
    st.transmittance *= w.transmittance;
  }

  // n segments over [t0, t1] placed by `dist`; a segment that holds one of
  // the ascending distances `cuts` is integrated as two (or more) pieces.
  // With `block` or `at_ends`, segments_block integrates them.
  // With `finite` (IntegrationOptions::finite_tables), the block march
  // reads no source that is multiplied by 0.
  void march(double t0, double t1, int n, StepDistribution dist, MarchState& st,
             const std::vector<double>& cuts = {}, bool block = false, bool at_ends = false,
             const CachedFiniteCheck* finite = nullptr) const {
    block = block || at_ends;
    if (empty() || !(t1 > t0)) return;
    n = std::max(n, 1);
    // block: the segments' ends, t0 first, kept by each thread from march to
    // march (the references march hundreds of short rays: no allocation each).
    thread_local std::vector<double> ends;
    ends.clear();
    if (block) ends.push_back(t0);
    const auto emit = [&](double a, double b) {
      if (block)
        ends.push_back(b);
      else
        segment(a, b, st);
    };
    double a = t0;
    size_t cut = 0;
    for (int i = 1; i <= n; ++i) {
      double x = double(i) / n;
      if (dist == StepDistribution::quadratic) x *= x;
      const double b = i == n ? t1 : t0 + (t1 - t0) * x;
      for (; cut < cuts.size() && cuts[cut] < b; ++cut)
        if (cuts[cut] > a) {
          emit(a, cuts[cut]);
          a = cuts[cut];
        }
      emit(a, b);
      a = b;
    }
    if (block) segments_block(ends, st, at_ends, finite);
  }

  // segment() over [ends[i], ends[i + 1]] for every i, in order, with the
  // media's exponentials and the weights' expm1s taken in blocks
  // (IntegrationOptions::block_exponentials); `at_ends`: the sources read at
  // the ends instead (IntegrationOptions::sources_at_ends).
  void segments_block(const std::vector<double>& ends, MarchState& st, bool at_ends,
                      const CachedFiniteCheck* finite) const {
    // Scratch kept by each thread from march to march (no allocation per ray).
    thread_local BlockScratch b;
    media_block(ends, b);
    DarkSegments dark{ends.size() - 1, false};
    if (finite) {
      const DarkSegments found = dark_segments(ends, b, st.transmittance);
      if ((found.lit < dark.lit || found.no_light) && (*finite)()) dark = found;
    }
    if (at_ends)
      light_at_ends(ends, b, dark, st);
    else
      light_at_midpoints(ends, b, dark, st);
  }

  // Which of media_block's segments need their sources read (`finite`).
  struct DarkSegments {
    size_t lit;     // segments before the transmittance from the viewer is 0
    bool no_light;  // none of those scatters: every source is multiplied by 0
  };
  // The sums' transmittance, the same products in the same order, from `t`.
  DarkSegments dark_segments(const std::vector<double>& ends, const BlockScratch& b,
                             glm::dvec3 t) const {
    const size_t n = ends.size() - 1;
    DarkSegments out{n, true};
    for (size_t i = 0; i < n; ++i) {
      if (t == glm::dvec3(0.0)) {
        out.lit = i;
        break;
      }
      const double dt = ends[i + 1] - ends[i];
      if (!(dt > 0.0) || b.sigma_t[i] == glm::dvec3(0.0)) continue;
      if (b.sigma_s_phase[i] != glm::dvec3(0.0) || (mslut_ && b.sigma_s[i] != glm::dvec3(0.0)))
        out.no_light = false;
      for (int c = 0; c < 3; ++c) t[c] *= 1.0 + b.em[3 * i + c];
    }
    return out;
  }

  // The segments' midpoints, media (sigma_s, sigma_t, sigma_s_phase) and the
  // expm1(-sigma_t dt) of each channel, in blocks: each component's
  // densities in a row of its own, then each segment's sums in registers, in
  // segment()'s order (no zeroed arrays added to once per component).
  void media_block(const std::vector<double>& ends, BlockScratch& b) const {
    const size_t n = ends.size() - 1;
    for (std::vector<double>* v : {&b.h, &b.r, &b.mu_s}) scratch_entries(*v, n);
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 p = origin_ + (0.5 * (ends[i] + ends[i + 1])) * dir_;
      b.r[i] = std::max(glm::length(p), atm_.bottom_radius_m);
      b.h[i] = b.r[i] - atm_.bottom_radius_m;
      b.mu_s[i] = clamp_cosine(glm::dot(p, sun_) / b.r[i]);
    }
    scratch_entries(b.density, components_.size() * n);
    for (size_t k = 0; k < components_.size(); ++k)
      density_block(*components_[k].density, b.h.data(), n, NodeExp::block, b.medium,
                    b.density.data() + n * k);
    for (std::vector<glm::dvec3>* v : {&b.sigma_s, &b.sigma_t, &b.sigma_s_phase})
      scratch_entries(*v, n);
    scratch_entries(b.em, 3 * n);
    for (size_t i = 0; i < n; ++i) {
      glm::dvec3 sigma_s(0.0), sigma_t(0.0), sigma_s_phase(0.0);
      for (size_t k = 0; k < components_.size(); ++k) {
        const double d = b.density[n * k + i];
        if (d == 0.0) continue;
        sigma_s += d * components_[k].scattering;
        sigma_t += d * components_[k].extinction;
        sigma_s_phase += d * components_[k].scattering_phase;
      }
      b.sigma_s[i] = sigma_s;
      b.sigma_t[i] = sigma_t;
      b.sigma_s_phase[i] = sigma_s_phase;
      for (int c = 0; c < 3; ++c)
        b.em[3 * i + c] = std::clamp(-sigma_t[c] * (ends[i + 1] - ends[i]), -708.0, 708.0);
    }
    expm1_block(b.em.data(), 3 * n);
  }

  // segment()'s sums over media_block's segments, the sources read at the
  // midpoints: every segment's two reads first, several in the lanes of a
  // group (kernels/sun_and_psi_ms_reads.hpp, the same bits), then the sums
  // in order. The sums, the sun and the arrays' starts are locals: stores to
  // `st` could alias them (doubles all), which would reload them at every
  // segment.
  void light_at_midpoints(const std::vector<double>& ends, BlockScratch& b,
                          const DarkSegments& dark, MarchState& st) const {
    const size_t n = dark.lit;
    const double* em = b.em.data();
    const glm::dvec3 *sigma_s = b.sigma_s.data(), *sigma_t = b.sigma_t.data(),
                     *sigma_s_phase = b.sigma_s_phase.data();
    glm::dvec3 *sun = scratch_entries(b.sun, n), *ms = scratch_entries(b.ms, n);
    if (dark.no_light) {  // 0 times any finite read is the 0 read here
      std::fill(sun, sun + n, glm::dvec3(0.0));
      std::fill(ms, ms + n, glm::dvec3(0.0));
    } else {
      read_sun_and_psi_ms(atm_, tlut_, mslut_, msmap_, b.r.data(), b.mu_s.data(), n, sun, ms);
      view_psi_ms(b.r.data(), b.mu_s.data(), n, ms,
                  [&](size_t i) { return 0.5 * (ends[i] + ends[i + 1]); });
    }
    const glm::dvec3 sun_illuminance = atm_.sun_illuminance;
    const bool multiscattering = mslut_ != nullptr;
    MarchState sums = st;
    for (size_t i = 0; i < n; ++i) {
      const double dt = ends[i + 1] - ends[i];
      if (!(dt > 0.0) || sigma_t[i] == glm::dvec3(0.0)) continue;
      glm::dvec3 source = sun[i] * sigma_s_phase[i];
      if (multiscattering) source += ms[i] * sigma_s[i];
      const SegmentWeights w = segment_weights_from_expm1(sigma_t[i], dt, &em[3 * i]);
      sums.luminance += sums.transmittance * sun_illuminance * source * w.weight;
      sums.transmittance *= w.transmittance;
    }
    st = sums;
  }

  // The sums over media_block's segments with the sun's transmittance and
  // Psi_ms read at the segments' ends and each channel's source integrated
  // linear between them (segment_sources.hpp); locals as light_at_midpoints'.
  void light_at_ends(const std::vector<double>& ends, BlockScratch& b, const DarkSegments& dark,
                     MarchState& st) const {
    const size_t n = dark.lit;
    for (std::vector<double>* v : {&b.end_r, &b.end_mu_s}) scratch_entries(*v, n + 1);
    glm::dvec3 *end_sun = scratch_entries(b.end_sun, n + 1),
               *end_ms = scratch_entries(b.end_ms, n + 1);
    // |origin + t dir|^2 and its dot with the sun, expanded (dir is unit).
    const double oo = glm::dot(origin_, origin_), od = glm::dot(origin_, dir_);
    const double os = glm::dot(origin_, sun_), ds = glm::dot(dir_, sun_);
    for (size_t k = 0; k <= n; ++k) {
      const double t = ends[k];
      const double r =
          std::max(std::sqrt(std::max(oo + t * (2.0 * od + t), 0.0)), atm_.bottom_radius_m);
      b.end_r[k] = r;
      b.end_mu_s[k] = clamp_cosine((os + t * ds) / r);
    }
    if (dark.no_light) {  // 0 times any finite read is the 0 read here
      std::fill(end_sun, end_sun + n + 1, glm::dvec3(0.0));
      std::fill(end_ms, end_ms + n + 1, glm::dvec3(0.0));
    } else {
      read_sun_and_psi_ms(atm_, tlut_, mslut_, msmap_, b.end_r.data(), b.end_mu_s.data(), n + 1,
                          end_sun, end_ms);
      view_psi_ms(b.end_r.data(), b.end_mu_s.data(), n + 1, end_ms,
                  [&](size_t k) { return ends[k]; });
    }
    const double* em = b.em.data();
    const glm::dvec3 *sigma_s = b.sigma_s.data(), *sigma_t = b.sigma_t.data(),
                     *sigma_s_phase = b.sigma_s_phase.data();
    const glm::dvec3 sun_illuminance = atm_.sun_illuminance;
    const bool multiscattering = mslut_ != nullptr;
    MarchState sums = st;
    for (size_t i = 0; i < n; ++i) {
      const double dt = ends[i + 1] - ends[i];
      if (!(dt > 0.0) || sigma_t[i] == glm::dvec3(0.0)) continue;
      glm::dvec3 scattered, transmittance;
      for (int c = 0; c < 3; ++c) {
        transmittance[c] = 1.0 + em[3 * i + c];
        const EndSourceWeights w = end_source_weights(sigma_t[i][c] * dt, em[3 * i + c], dt);
        scattered[c] =
            sigma_s_phase[i][c] * end_source_integral(end_sun[i][c], end_sun[i + 1][c], w);
        if (multiscattering)  // eq. 11
          scattered[c] += sigma_s[i][c] * end_source_integral(end_ms[i][c], end_ms[i + 1][c], w);
      }
      sums.luminance += sums.transmittance * sun_illuminance * scattered;
      sums.transmittance *= transmittance;
    }
    st = sums;
  }

  // Psi_ms at (r, mu_s) as this ray's view reads it, mu_v the ray's zenith
  // cosine there (eq. 11; a view-dependent table's layers, multiscattering_lut.hpp).
  glm::dvec3 psi_ms(double r, double mu_s, double mu_v) const {
    if (msmap_.nu_slices == 0) return lookup_multiscattering(*mslut_, msmap_, atm_, r, mu_s);
    return lookup_multiscattering(*mslut_, multiscattering_at_radius(*mslut_, msmap_, atm_, r),
                                  mu_s, msview_, mu_v);
  }

  // The block reads (read_sun_and_psi_ms) hold the isotropic layer; a
  // view-dependent table's reads are replaced by the view's, point i at
  // distance t_of(i) along the ray.
  template <typename Distance>
  void view_psi_ms(const double* r, const double* mu_s, size_t n, glm::dvec3* ms,
                   Distance t_of) const {
    if (!mslut_ || msmap_.nu_slices == 0) return;
    const double od = glm::dot(origin_, dir_);
    for (size_t i = 0; i < n; ++i)
      ms[i] = psi_ms(r[i], mu_s[i], clamp_cosine((od + t_of(i)) / r[i]));
  }

  // Where the ray enters and leaves the planet's shadow, ascending: the
  // roots of |p_perp(t)|^2 = Rb^2 (p_perp the part of the point across the
  // sun's direction) on the night side (p . sun < 0).
  std::vector<double> shadow_crossings() const {
    const glm::dvec3 o = origin_ - glm::dot(origin_, sun_) * sun_;
    const glm::dvec3 d = dir_ - glm::dot(dir_, sun_) * sun_;
    const double a = glm::dot(d, d), b = glm::dot(o, d);
    const double c = glm::dot(o, o) - atm_.bottom_radius_m * atm_.bottom_radius_m;
    const double disc = b * b - a * c;
    std::vector<double> out;
    if (!(a > 0.0) || !(disc > 0.0)) return out;
    const double root = std::sqrt(disc);
    for (double t : {(-b - root) / a, (-b + root) / a})
      if (t > 0.0 && glm::dot(origin_ + t * dir_, sun_) < 0.0) out.push_back(t);
    return out;
  }

  // The ground's diffuse response at distance t (eq. 1 L_o), seen through st.
  void lit_ground(double t, MarchState& st) const {
    const glm::dvec3 up = glm::normalize(origin_ + t * dir_);
    const double mu_s = clamp_cosine(glm::dot(up, sun_));
    if (mu_s <= 0.0) return;
    const glm::dvec3 t_sun = lookup_sun_transmittance(tlut_, atm_, atm_.bottom_radius_m, mu_s);
    st.luminance +=
        st.transmittance * atm_.sun_illuminance * t_sun * mu_s * atm_.ground_albedo / kPi;
  }

 private:
  const Atmosphere& atm_;
  const Texture& tlut_;
  const Texture* mslut_;
  const MultiscatteringMapping msmap_;  // parsed once: the march reads it per segment
  MultiscatteringView msview_;          // the nu slices this ray's view reads
  glm::dvec3 origin_, dir_, sun_;
  std::vector<RayComponent> components_;
};

}  // namespace

AtmosphereSpan clip_ray_to_atmosphere(const Atmosphere& atm, glm::dvec3 position_m,
                                      glm::dvec3 dir) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double len = glm::length(position_m);
  const double r = std::max(len, rb);
  const double mu = len > 0.0 ? clamp_cosine(glm::dot(position_m, dir) / len) : 1.0;
  AtmosphereSpan span;
  double r_in = r, mu_in = mu;
  if (r > rt) {
    // Above the top: enter where the ray first meets the top sphere, if it does.
    const double discriminant = r * r * (mu * mu - 1.0) + rt * rt;
    if (mu >= 0.0 || discriminant < 0.0) return span;
    span.t_enter = std::max(0.0, -r * mu - std::sqrt(discriminant));
    r_in = rt;
    mu_in = clamp_cosine((r * mu + span.t_enter) / rt);
  }
  span.hits_atmosphere = true;
  span.exits_on_ground = ray_intersects_ground(rb, r_in, mu_in);
  span.t_exit =
      span.t_enter + distance_to_nearest_boundary(rb, rt, r_in, mu_in, span.exits_on_ground);
  return span;
}

namespace {

// Vacuum without a lit ground: nothing scatters or attenuates, every ray is
// black (the march's result with no segment).
bool nothing_to_march(const Atmosphere& atm, const IntegrationOptions& options) {
  return atm.components.empty() && !options.lit_ground;
}

// integrate_scattered_luminance's march on a ray already clipped and set up:
// `cuts` the shadow's crossings where options.cut_at_shadow.
ScatteringResult march_span(const RayMarcher& marcher, const AtmosphereSpan& span,
                            double max_distance_m, int steps, const IntegrationOptions& options,
                            const std::vector<double>& cuts) {
  const double t_end = std::min(span.t_exit, std::max(max_distance_m, 0.0));
  MarchState st;
  marcher.march(span.t_enter, t_end, steps, options.distribution, st, cuts,
                options.block_exponentials, options.sources_at_ends, options.finite_tables);
  if (options.lit_ground && span.exits_on_ground && t_end >= span.t_exit)
    marcher.lit_ground(span.t_exit, st);
  return {st.luminance, st.transmittance};
}

}  // namespace

ScatteringResult integrate_scattered_luminance(const Atmosphere& atm,
                                               const Texture& transmittance_lut,
                                               const Texture* multiscattering_lut,
                                               glm::dvec3 position_m, glm::dvec3 view_dir,
                                               glm::dvec3 sun_dir, double max_distance_m, int steps,
                                               const IntegrationOptions& options) {
  if (nothing_to_march(atm, options)) return {};
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position_m, view_dir);
  if (!span.hits_atmosphere) return {};
  const RayMarcher marcher(atm, transmittance_lut, multiscattering_lut, position_m, view_dir,
                           sun_dir, options.multiscattering_mapping);
  return march_span(marcher, span, max_distance_m, steps, options,
                    options.cut_at_shadow ? marcher.shadow_crossings() : std::vector<double>{});
}

glm::dvec3 extrapolated_scattered_luminance(const Atmosphere& atm, const Texture& transmittance_lut,
                                            const Texture* multiscattering_lut,
                                            glm::dvec3 position_m, glm::dvec3 view_dir,
                                            glm::dvec3 sun_dir, double max_distance_m, int n,
                                            IntegrationOptions options) {
  options.cut_at_shadow = true;
  n = std::max(n, 1);
  // Both marches share the ray's clipping, set-up and shadow crossings; in
  // vacuum without a lit ground, and off the atmosphere, both are black.
  // (4 * 0 - 0) / 3 is +0 in every channel.
  if (nothing_to_march(atm, options)) return glm::dvec3(0.0);
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position_m, view_dir);
  if (!span.hits_atmosphere) return glm::dvec3(0.0);
  const RayMarcher marcher(atm, transmittance_lut, multiscattering_lut, position_m, view_dir,
                           sun_dir, options.multiscattering_mapping);
  const std::vector<double> cuts = marcher.shadow_crossings();
  const auto march = [&](int steps) {
    return march_span(marcher, span, max_distance_m, steps, options, cuts).luminance;
  };
  return (4.0 * march(2 * n) - march(n)) / 3.0;
}

std::vector<ScatteringResult> integrate_scattered_luminance_profile(
    const Atmosphere& atm, const Texture& transmittance_lut, const Texture* multiscattering_lut,
    glm::dvec3 position_m, glm::dvec3 view_dir, glm::dvec3 sun_dir,
    const std::vector<double>& distances_m, int steps_per_interval) {
  std::vector<ScatteringResult> out(distances_m.size());
  const AtmosphereSpan span = clip_ray_to_atmosphere(atm, position_m, view_dir);
  if (!span.hits_atmosphere) return out;
  const RayMarcher marcher(atm, transmittance_lut, multiscattering_lut, position_m, view_dir,
                           sun_dir);
  MarchState st;
  double cursor = span.t_enter;
  for (size_t k = 0; k < distances_m.size(); ++k) {
    const double target = std::min(distances_m[k], span.t_exit);
    if (target > cursor) {
      marcher.march(cursor, target, steps_per_interval, StepDistribution::uniform, st);
      cursor = target;
    }
    out[k] = {st.luminance, st.transmittance};
  }
  return out;
}

glm::dvec3 lookup_sun_transmittance(const Texture& transmittance_lut, const Atmosphere& atm,
                                    double r, double mu_s) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  if (ray_intersects_ground(atm.bottom_radius_m, r, mu_s)) return glm::dvec3(0.0);  // Vis = 0
  return lookup_transmittance_to_top(transmittance_lut, atm, r, mu_s);
}

}  // namespace skybake
