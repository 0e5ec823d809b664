#include "verify/psi_ms_reference.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium_block.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/kernels/exp_block.hpp"
#include "core/math.hpp"
#include "core/scratch.hpp"
#include "verify/kernels/ring_segments.hpp"
#include "verify/kernels/ring_sun_sums.hpp"

namespace skybake {
namespace {

// One zenith cosine's march from the point, everything but the sun.
struct RingMarch {
  // The samples that scatter light: the first `samples` entries of each
  // array (core/scratch.hpp).
  size_t samples = 0;
  std::vector<double> distances;                 // where each segment is lit (weight_centroid)
  std::vector<double> radii;                     // the radius there (at least Rb)
  std::vector<double> inverse_radii;             // 1 / radii
  std::vector<glm::dvec3> scattered;             // T sigma_s (1 - exp(-sigma_t dt)) / sigma_t
  glm::dvec3 l_f{0.0};                           // eq. 8: the sum of `scattered`
  bool ground = false;                           // the ray ends on the ground
  double length = 0.0;                           // to the ground or the top
  glm::dvec3 ground_transmittance{1.0};          // T from the point to the ground
  // Scratch: segment ends, midpoint altitudes, media, expm1s (ring_media),
  // the azimuths' sums of the sun (lit_ring).
  std::vector<double> ends, altitudes, expm1s;
  MediumBlock media;
  RingSegmentTerms terms;
  std::vector<glm::dvec3> sun_sums;
};

// Zenith cosines and the fraction of 4 pi each ring stands for: mu = mu_h -+
// c s^2 on each side of the horizon, dmu = 2 c s ds, a ring's solid angle
// 2 pi dmu; s the Gauss-Legendre nodes on [0, 1].
void zenith_rule(const PointRule& rule, double mu_h, std::vector<double>& mus,
                 std::vector<double>& weights) {
  mus.clear();
  weights.clear();
  const auto side = [&](const std::vector<double>& x, const std::vector<double>& w, double width,
                        double sign) {
    for (size_t i = 0; i < x.size(); ++i) {
      const double s = 0.5 + 0.5 * x[i], ws = 0.5 * w[i];
      mus.push_back(mu_h + sign * width * s * s);
      weights.push_back(ws * width * s);
    }
  };
  side(rule.below_nodes, rule.below_weights, mu_h + 1.0, -1.0);
  side(rule.above_nodes, rule.above_weights, 1.0 - mu_h, 1.0);
}

// Segment ends on [0, length] of the ray (r, mu): cut at the perigee, each
// piece's segments (in proportion to its length, at least one) graded s^2
// toward its lower end.
void segment_ends(double r, double mu, double length, int steps, std::vector<double>& ends) {
  ends.assign(1, 0.0);
  const double perigee = -r * mu;
  const bool split = perigee > 1e-9 * length && perigee < (1.0 - 1e-9) * length;
  const int first =
      split ? std::clamp(int(std::lround(steps * perigee / length)), 1, steps - 1) : steps;
  const auto piece = [&](double a, double b, int n) {
    // Descending to the perigee (or to the ground): the low end is b.
    const bool descending = b <= perigee;
    for (int k = 1; k <= n; ++k) {
      const double g = double(k) / n;
      ends.push_back(descending ? b - (b - a) * (1.0 - g) * (1.0 - g) : a + (b - a) * g * g);
    }
  };
  if (split && steps >= 2) {
    piece(0.0, perigee, first);
    piece(perigee, length, steps - first);
  } else {
    piece(0.0, length, steps);
  }
  ends.back() = length;
}

// The ring's segments' media and the four expm1 of each (segment_weights'
// three, weight_centroid's one) in blocks: one pass per component and one
// of expm1 over the ring, over lanes (medium_block.hpp,
// core/kernels/exp_block.hpp: within 1e-15 relative of libm, the same bits
// on every target).
// Not called in vacuum (no component: march_ring skips the segments).
void ring_media(const Atmosphere& atm, double r, double mu, RingMarch& out) {
  const std::vector<double>& ends = out.ends;
  const size_t n = ends.size() - 1;
  const double rb = atm.bottom_radius_m;
  out.altitudes.resize(n);
  for (size_t i = 0; i < n; ++i)  // the medium at the midpoint, as the table's march samples it
    out.altitudes[i] = std::max(radius_after(r, mu, 0.5 * (ends[i] + ends[i + 1])), rb) - rb;
  sample_medium_block(atm, out.altitudes.data(), n, NodeExp::block, out.media);
  out.expm1s.resize(4 * n);
  // expm1_block's range: beyond it the weights' -1 and the centroid's
  // 1 / expm1 change by less than 1e-307. Clamped as written.
  const double bound = 708.0;
  for (size_t i = 0; i < n; ++i) {
    const double dt = ends[i + 1] - ends[i];
    const glm::dvec3& e = out.media.extinction[i];
    for (int c = 0; c < 3; ++c) out.expm1s[4 * i + c] = std::clamp(-e[c] * dt, -bound, bound);
    out.expm1s[4 * i + 3] = std::clamp((e.x + e.y + e.z) / 3.0 * dt, -bound, bound);
  }
  expm1_block(out.expm1s.data(), out.expm1s.size());
}

// march_ring's sums over its segments, in order: L_f (eq. 8) and each
// sample that scatters light (out.samples of them); returns the
// transmittance to the ray's end. The sums are locals: the arrays' doubles
// could alias a sum kept in `out`, which would then be stored and reloaded
// at every segment.
glm::dvec3 ring_samples(const CachedFiniteCheck* finite_table, RingMarch& out) {
  const size_t n = out.ends.size() - 1;
  const double* ends = out.ends.data();
  const double* expm1s = out.expm1s.data();
  const glm::dvec3* extinction = out.media.extinction.data();
  const glm::dvec3* scattering = out.media.scattering.data();
  const RingSegmentTerms& terms = out.terms;
  double* distances = scratch_entries(out.distances, n);
  double* radii = scratch_entries(out.radii, n);
  double* inverse_radii = scratch_entries(out.inverse_radii, n);
  glm::dvec3* scattered_out = scratch_entries(out.scattered, n);
  glm::dvec3 transmittance(1.0), l_f(0.0);
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    const double dt = ends[i + 1] - ends[i];
    if (!(dt > 0.0)) continue;
    if (extinction[i] == glm::dvec3(0.0)) continue;
    // segment_weights with the block's expm1(-sigma_t dt).
    SegmentWeights w;
    for (int c = 0; c < 3; ++c) {
      w.weight[c] = terms.weight[c][i];
      w.transmittance[c] = 1.0 + expm1s[4 * i + c];
    }
    const glm::dvec3 scattered = transmittance * scattering[i] * w.weight;
    l_f += scattered;
    transmittance *= w.transmittance;
    if (scattered == glm::dvec3(0.0) && finite_table && (*finite_table)()) {
      // Every later segment scatters transmittance (0) times finite terms.
      if (transmittance == glm::dvec3(0.0)) break;
      continue;
    }
    distances[kept] = terms.lit_at[i];
    radii[kept] = terms.lit_radius[i];
    inverse_radii[kept] = terms.inverse_radius[i];
    scattered_out[kept++] = scattered;
  }
  out.samples = kept;
  out.l_f = l_f;
  return transmittance;
}

// `finite_table`: multiscattering_at_point's (psi_ms_reference.hpp).
void march_ring(const Atmosphere& atm, double r, double mu, int steps,
                const CachedFiniteCheck* finite_table, RingMarch& out) {
  out.samples = 0;
  out.l_f = glm::dvec3(0.0);
  const double rb = atm.bottom_radius_m;
  out.ground = ray_intersects_ground(rb, r, mu);
  out.length = distance_to_nearest_boundary(rb, atm.top_radius_m, r, mu, out.ground);
  if (atm.components.empty()) {  // vacuum: no segment scatters or attenuates
    out.ground_transmittance = glm::dvec3(1.0);
    return;
  }
  segment_ends(r, mu, out.length, std::max(steps, 1), out.ends);
  ring_media(atm, r, mu, out);
  ring_segment_terms(out.ends.data(), out.ends.size() - 1, out.media.extinction.data(),
                     out.expm1s.data(), r, mu, rb, out.terms);
  out.ground_transmittance = ring_samples(finite_table, out);
}

// The ring's L' of eq. 6 (E_I = 1) summed over its azimuths, each a
// direction whose cosine with the sun is cosines[j]: a sample at distance t
// sees the sun at zenith cosine (r mu_s + t c) / r_t, since the point is
// (0, 0, r). Per sample the azimuths' sun transmittances are summed first
// and scaled by the sun-independent `scattered` once, several samples at a
// time (kernels/ring_sun_sums.hpp).
glm::dvec3 lit_ring(const Atmosphere& atm, const Texture& transmittance_lut, RingMarch& m, double r,
                    double mu_s, const std::vector<double>& cosines) {
  const double rb = atm.bottom_radius_m;
  const double height = r * mu_s;
  glm::dvec3 l_prime(0.0);
  const size_t n = m.samples;
  glm::dvec3* sums = scratch_entries(m.sun_sums, n);
  ring_sun_sums(transmittance_lut, atm, m.radii.data(), m.distances.data(),
                m.inverse_radii.data(), n, height, cosines.data(), cosines.size(), sums);
  for (size_t i = 0; i < n; ++i) l_prime += m.scattered[i] * sums[i];
  l_prime *= isotropic_phase();
  if (!m.ground) return l_prime;
  for (double c : cosines) {
    const double mu_ground = clamp_cosine((height + m.length * c) / rb);
    if (mu_ground > 0.0)
      l_prime += m.ground_transmittance *
                 lookup_sun_transmittance(transmittance_lut, atm, rb, mu_ground) * mu_ground *
                 atm.ground_albedo / kPi;
  }
  return l_prime;
}

}  // namespace

PointRule point_rule(const PointQuadrature& quadrature) {
  PointRule rule;
  rule.quadrature = quadrature;
  rule.quadrature.azimuths = std::max(quadrature.azimuths, 1);
  rule.quadrature.steps = std::max(quadrature.steps, 1);
  if (quadrature.below > 0) gauss_legendre(quadrature.below, rule.below_nodes, rule.below_weights);
  if (quadrature.above > 0) gauss_legendre(quadrature.above, rule.above_nodes, rule.above_weights);
  return rule;
}

MultiscatteringSample multiscattering_at_point(const Atmosphere& atm,
                                               const Texture& transmittance_lut, double r,
                                               double mu_s, const PointRule& rule,
                                               const CachedFiniteCheck* finite_table) {
  r = std::clamp(r, atm.bottom_radius_m, atm.top_radius_m);
  mu_s = clamp_cosine(mu_s);
  const double ratio = atm.bottom_radius_m / r;
  std::vector<double> mus, ring_weights, cosines;
  zenith_rule(rule, -safe_sqrt(1.0 - ratio * ratio), mus, ring_weights);
  const int azimuths = rule.quadrature.azimuths;
  const double sun_x = safe_sqrt(1.0 - mu_s * mu_s);
  MultiscatteringSample out;
  // Kept by each thread from point to point: the record's 24 points would
  // otherwise grow a dozen arrays each (march_ring clears what it fills).
  thread_local RingMarch march;
  std::vector<double> azimuth_cosines;  // the same for every ring
  for (int j = 0; j < azimuths; ++j)
    azimuth_cosines.push_back(std::cos(kPi * (j + 0.5) / azimuths));
  for (size_t k = 0; k < mus.size(); ++k) {
    march_ring(atm, r, mus[k], rule.quadrature.steps, finite_table, march);
    // In vacuum a ring that does not meet the ground sees no light: it adds +0.
    if (atm.components.empty() && !march.ground) continue;
    const double sin_zenith = safe_sqrt(1.0 - mus[k] * mus[k]);
    cosines.clear();
    for (int j = 0; j < azimuths; ++j)
      cosines.push_back(sin_zenith * azimuth_cosines[j] * sun_x + mus[k] * mu_s);
    out.l2 +=
        ring_weights[k] / azimuths * lit_ring(atm, transmittance_lut, march, r, mu_s, cosines);
    out.f_ms += ring_weights[k] * march.l_f;
  }
  const glm::dvec3 f = glm::min(out.f_ms, glm::dvec3(kMaxMultiscatteringTransfer));
  out.psi_ms = out.l2 / (1.0 - f);  // eq. 9-10
  return out;
}

}  // namespace skybake
