// Transmittance LUT: mapping, quadrature, bake and lookups. See the header for
// the parameterization (Hillaire 2020 sec. 5.2, Bruneton 2017).
//
// Why this quadrature: the midpoint rule with the paper's 40 uniform samples
// is off by up to ~2% in optical depth on Earth (Mie's 1.2 km scale height
// over a 100 km vertical ray; the ozone tent's kinks). Cutting the ray at the
// kinks and the perigee leaves smooth pieces, where composite Gauss-Legendre
// on a grid graded toward the dense end converges fast: with 3 points per
// segment (6th order) ~1e-4 at 20 steps, ~2e-6 at 40, ~4e-8 at 80 over the
// whole table; with 8 points (16th order), the table's rule, ~1e-8 at 6
// steps, 48 samples of sigma_t per ray where the 3-point rule needs 120 for
// ~2e-6. The table's rule also integrates the layers without an exponential
// term (the ozone tent) in closed form, so that neither their kinks cut the
// ray nor their densities are sampled (docs/reference.md "Transmittance").
#include "atmosphere/transmittance_lut.hpp"

#include "core/texture_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "atmosphere/density_kinks.hpp"
#include "atmosphere/extinction_profile.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/kernels/node_altitudes.hpp"
#include "atmosphere/linear_layer_depth.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// sqrt(Rt^2 - Rb^2), factored to keep the digits of a thin shell.
double horizon_distance(const Atmosphere& atm) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  return safe_sqrt((rt - rb) * (rt + rb));
}

// ---- Kinks of the density profiles ----

// Sorted kink altitudes of every component the quadrature integrates.
std::vector<double> kink_altitudes(const Atmosphere& atm, bool closed_form_linear) {
  std::vector<double> kinks;
  const double top_h = atm.top_radius_m - atm.bottom_radius_m;
  for (const MediumComponent& c : atm.components) {
    if (!integrated_by_quadrature(c, closed_form_linear)) continue;
    add_profile_kinks(c.density, top_h, kinks);
  }
  std::sort(kinks.begin(), kinks.end());
  kinks.erase(std::unique(kinks.begin(), kinks.end()), kinks.end());
  return kinks;
}

// What one ray's quadrature needs besides the ray: the kinks, the profile,
// and scratch arrays reused from ray to ray (a bake row allocates once).
// With `closed_form_linear` (the table's rule) the piecewise-linear
// components are integrated in closed form and neither their kinks cut the
// ray nor their densities are sampled; else every component is sampled.
struct RayQuadrature {
  // The table's rule takes its exponentials in blocks; the other, `exp_kind`'s.
  RayQuadrature(const Atmosphere& atm, bool closed_form_linear, NodeExp exp_kind = NodeExp::libm)
      : table_rule(closed_form_linear),
        kinks(kink_altitudes(atm, closed_form_linear)),
        extinction(atm, closed_form_linear, closed_form_linear ? NodeExp::block : exp_kind),
        linear(closed_form_linear ? LinearLayerDepth(atm) : LinearLayerDepth(Atmosphere{})) {}
  bool table_rule;  // the 8-point rule's cuts and grading (docs/reference.md)
  std::vector<double> kinks;
  ExtinctionProfile extinction;
  LinearLayerDepth linear;
  std::vector<double> scratch, breakpoints;
  std::vector<int> segments;
  // graded[g][n][k - 1]: the grading of segment end k of a piece cut in n,
  // t^2 (g = 0) or the table rule's t^1.25 (g = 1), t = k / n; filled on
  // first use (a ray computed the same two roots per segment end).
  std::vector<std::vector<double>> graded[2];
  std::vector<double> heights, weights;  // per node: altitude, Gauss weight times the half length
  std::vector<double> densities;         // per node, one component at a time
};

// The radius along the ray, r(x) = sqrt(x^2 + p^2) at distance x from the
// perigee (p its radius), has branch points at x = +-i p: a Gauss rule on a
// segment much longer than its distance to them converges slowly (a ray
// grazing a 1 km planet). From the ray's point nearest the perigee, x_0,
// cuts at x_{k+1} = x_k + r(x_k) on the ray's side(s) keep every piece no
// longer than its low end's distance to the branch points (Bernstein
// ellipse parameter >= ~3 for the 8-point rule). On Earth and Mars r > any
// ray's length, so nothing is cut.
void add_perigee_cuts(std::vector<double>& s, double r, double mu, double d) {
  const double perigee = -r * mu;  // s at x = 0
  const double p2 = r * r * std::max(0.0, (1.0 - mu) * (1.0 + mu));
  const double reach = std::max(std::abs(perigee), std::abs(d - perigee));  // largest |x|
  double x = perigee > 0.0 && perigee < d ? 0.0 : std::min(std::abs(perigee), std::abs(d - perigee));
  for (x += std::sqrt(x * x + p2); x < reach; x += std::sqrt(x * x + p2))
    for (double cut : {perigee - x, perigee + x})
      if (cut > 0.0 && cut < d) s.push_back(cut);
}

// Distances in [0, d] cutting the segment (r, mu, d) into smooth pieces of
// monotone altitude: its ends, the perigee s = -r mu and where it crosses the
// sphere of each kink altitude, s = -r mu +- sqrt(r^2 mu^2 + (R - r)(R + r)).
// Written to q.breakpoints.
void segment_breakpoints(const Atmosphere& atm, RayQuadrature& q, double r, double mu, double d) {
  std::vector<double>& s = q.scratch;
  s.assign({0.0, d});
  const double perigee = -r * mu;
  if (perigee > 0.0 && perigee < d) s.push_back(perigee);
  for (double h : q.kinks) {
    const double radius = atm.bottom_radius_m + h;
    const double disc = r * r * mu * mu + (radius - r) * (radius + r);
    if (disc <= 0.0) continue;
    const double root = std::sqrt(disc);
    for (double crossing : {perigee - root, perigee + root})
      if (crossing > 0.0 && crossing < d) s.push_back(crossing);
  }
  if (q.table_rule) add_perigee_cuts(s, r, mu, d);
  std::sort(s.begin(), s.end());
  // Drop pieces too short to matter (a kink grazed at the perigee, rounding).
  const double min_length = 1e-12 * d;
  std::vector<double>& out = q.breakpoints;
  out.assign(1, s.front());
  for (size_t i = 1; i + 1 < s.size(); ++i)
    if (s[i] - out.back() > min_length) out.push_back(s[i]);
  if (out.size() > 1 && d - out.back() <= min_length) out.pop_back();
  out.push_back(d);
}

// Segments per piece of q.breakpoints, written to q.segments: proportional to
// the piece's length, at least one each, the remainder to the pieces with the
// longest segments.
void segments_per_piece(RayQuadrature& q, int steps) {
  const std::vector<double>& s = q.breakpoints;
  const size_t pieces = s.size() - 1;
  const double d = s.back() - s.front();
  std::vector<int>& n = q.segments;
  n.assign(pieces, 0);
  int used = 0;
  for (size_t i = 0; i < pieces; ++i) {
    n[i] = std::max(1, int(steps * ((s[i + 1] - s[i]) / d)));
    used += n[i];
  }
  for (; used < steps; ++used) {
    size_t longest = 0;
    for (size_t i = 1; i < pieces; ++i)
      if ((s[i + 1] - s[i]) / n[i] > (s[longest + 1] - s[longest]) / n[longest]) longest = i;
    ++n[longest];
  }
}

// Gauss-Legendre nodes and weights on [-1, 1]: 3 points (exact for
// quintics) and 8 points (exact for degree 15), in ascending order.
constexpr double kGauss3Nodes[3] = {-0.77459666924148338, 0.0, 0.77459666924148338};  // -+sqrt(3/5)
constexpr double kGauss3Weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
constexpr double kGauss8Nodes[8] = {-0.96028985649753623, -0.79666647741362674,
                                    -0.52553240991632899, -0.18343464249564980,
                                    0.18343464249564980,  0.52553240991632899,
                                    0.79666647741362674,  0.96028985649753623};
constexpr double kGauss8Weights[8] = {0.10122853629037626, 0.22238103445337447,
                                      0.31370664587788729, 0.36268378337836198,
                                      0.36268378337836198, 0.31370664587788729,
                                      0.22238103445337447, 0.10122853629037626};

struct GaussRule {
  const double* nodes;
  const double* weights;
  int points;
};
GaussRule gauss_rule(SegmentRule rule) {
  if (rule == SegmentRule::gauss8) return {kGauss8Nodes, kGauss8Weights, 8};
  return {kGauss3Nodes, kGauss3Weights, 3};
}

// Writes the distances along the ray of the Gauss nodes of [a, b] to
// s[0, points) (node_altitudes turns them into altitudes) and their weights
// (the rule's times the half length) to w.
void gauss_nodes(const GaussRule& g, double a, double b, double* s, double* w) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  for (int k = 0; k < g.points; ++k) {
    s[k] = mid + half * g.nodes[k];
    w[k] = half * g.weights[k];
  }
}

// Distance s along (r, mu) -> altitude, radius_after's arithmetic, in one
// pass over the nodes (the compiler vectorizes it). Altitudes below 0 read
// the ground's density.
void node_altitudes(std::vector<double>& s, double r, double mu, double bottom_radius) {
  const double two_r_mu = 2.0 * r * mu, r2 = r * r;
  for (double& x : s)
    x = std::max(0.0, std::sqrt(std::max(x * x + two_r_mu * x + r2, 0.0)) - bottom_radius);
}

// node_altitudes for the table's rule, over lanes and without its clamps
// (kernels/node_altitudes.hpp).
void node_altitudes_from_perigee(std::vector<double>& s, double r, double mu,
                                 double bottom_radius) {
  const double from_perigee = r * mu, p2 = r * r * std::max(0.0, (1.0 - mu) * (1.0 + mu));
  altitudes_from_perigee(s.data(), s.size(), from_perigee, p2, bottom_radius);
}

// The grading of a piece cut in n segments, q.graded's row: segment end k
// at t^1.25 (`gentle`, the table's rule through a perigee) or t^2 of the
// piece's length, t = k / n.
const double* graded_fractions(RayQuadrature& q, bool gentle, int n) {
  std::vector<std::vector<double>>& rows = q.graded[gentle ? 1 : 0];
  if (rows.size() <= size_t(n)) rows.resize(size_t(n) + 1);
  std::vector<double>& row = rows[size_t(n)];
  if (row.empty()) {
    for (int k = 1; k <= n; ++k) {
      const double t = double(k) / n;
      row.push_back(gentle ? t * std::sqrt(std::sqrt(t)) : t * t);
    }
  }
  return row.data();
}

// The quadrature of compute_optical_depth with the kinks and profile already
// known, plus the closed form of the linear components q.linear holds.
glm::dvec3 integrate_optical_depth(const Atmosphere& atm, RayQuadrature& q, double r, double mu,
                                   double d, int steps, SegmentRule rule) {
  if (!(d > 0.0) || atm.components.empty()) return glm::dvec3(0.0);
  const glm::dvec3 linear = q.linear.integrate(r, mu, d);
  if (q.extinction.empty()) return linear;
  const GaussRule g = gauss_rule(rule);
  segment_breakpoints(atm, q, r, mu, d);
  segments_per_piece(q, steps);
  const std::vector<double>& s = q.breakpoints;
  const std::vector<int>& n = q.segments;
  const double perigee = -r * mu;
  int total = 0;
  for (int count : n) total += count;
  q.heights.resize(size_t(total) * g.points);
  q.weights.resize(size_t(total) * g.points);
  size_t node = 0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    // Grade s = low_end +- L t^2 toward the lowest altitude of the piece:
    // its end when the ray still descends to the perigee, else its start.
    // The table's rule grades t^1.25 on rays through their perigee: there
    // the altitude is quadratic in s and an exponential density a Gaussian,
    // which wants segments of more even length (docs/reference.md).
    const bool descending = s[i + 1] <= perigee;
    const double length = s[i + 1] - s[i];
    const double low_end = descending ? s[i + 1] : s[i];
    const double sign = descending ? -1.0 : 1.0;
    const double* graded = graded_fractions(q, q.table_rule && perigee > 0.0, n[i]);
    double prev = low_end;
    for (int k = 1; k <= n[i]; ++k) {
      const double next =
          k == n[i] ? (descending ? s[i] : s[i + 1]) : low_end + sign * length * graded[k - 1];
      gauss_nodes(g, std::min(prev, next), std::max(prev, next), &q.heights[node],
                  &q.weights[node]);
      node += g.points;
      prev = next;
    }
  }
  if (q.table_rule)
    node_altitudes_from_perigee(q.heights, r, mu, atm.bottom_radius_m);
  else
    node_altitudes(q.heights, r, mu, atm.bottom_radius_m);
  return q.extinction.integrate(q.heights, q.weights, q.densities) + linear;
}

glm::dvec3 transmittance_from_optical_depth(glm::dvec3 tau) {
  return glm::clamp(glm::exp(-glm::max(tau, glm::dvec3(0.0))), 0.0, 1.0);
}

void set_transmittance_metadata(Metadata& meta, const Atmosphere& atm,
                                const TransmittanceLutSpec& spec) {
  set_meta(meta, "parameterization", std::string("bruneton_transmittance"));
  set_meta(meta, "quantity",
           std::string("transmittance from (r, mu) to the top atmosphere boundary, "
                       "dimensionless, R/G/B at 680/550/440 nm"));
  set_meta(meta, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(meta, "top_radius_m", atm.top_radius_m);
  set_meta(meta, "horizon_distance_m", horizon_distance(atm));
  set_meta(meta, "width", spec.width);
  set_meta(meta, "height", spec.height);
  set_meta(meta, "integration_steps", spec.steps);
  set_meta(meta, "integration_rule",
           std::string("layers without an exponential term (ozone) in closed form; the "
                       "others over steps graded segments per smooth piece of the ray, "
                       "8-point Gauss-Legendre on each"));
  set_meta(meta, "texel_centers",
           std::string("texel (x, y) has its centre at u = (x + 0.5)/W, v = (y + 0.5)/Ht; "
                       "y = 0 is the ground (r = Rb), x = 0 the zenith (mu = 1)"));
  set_meta(meta, "mapping",
           std::string("Rb = bottom_radius_m, Rt = top_radius_m, W = width, Ht = height, "
                       "H = sqrt(Rt^2 - Rb^2), rho = sqrt(r^2 - Rb^2), "
                       "d = -r*mu + sqrt(r^2*(mu^2 - 1) + Rt^2), d_min = Rt - r, d_max = rho + H, "
                       "x_mu = (d - d_min)/(d_max - d_min), x_r = rho/H, "
                       "u = 0.5/W + x_mu*(1 - 1/W), v = 0.5/Ht + x_r*(1 - 1/Ht)"));
  set_meta(meta, "inverse_mapping",
           std::string("x_mu = (u - 0.5/W)/(1 - 1/W), x_r = (v - 0.5/Ht)/(1 - 1/Ht), "
                       "rho = H*x_r, r = sqrt(rho^2 + Rb^2), d = d_min + x_mu*(d_max - d_min), "
                       "mu = (d == 0) ? 1 : (H^2 - rho^2 - d^2)/(2*r*d)"));
  if (spec.convention == TableConvention::hillaire_demo) {
    // Hillaire's LutTransmittanceParamsToUv reads u = x_mu, v = x_r directly.
    set_meta(meta, "convention", std::string("hillaire_demo"));
    set_meta(meta, "mapping",
             std::string("Rb = bottom_radius_m, Rt = top_radius_m, H = sqrt(Rt^2 - Rb^2), "
                         "rho = sqrt(r^2 - Rb^2), d = -r*mu + sqrt(r^2*(mu^2 - 1) + Rt^2), "
                         "d_min = Rt - r, d_max = rho + H, x_mu = (d - d_min)/(d_max - d_min), "
                         "x_r = rho/H, u = x_mu, v = x_r (texel i holds x = (i + 0.5)/n)"));
    set_meta(meta, "inverse_mapping",
             std::string("x_mu = u, x_r = v, rho = H*x_r, r = sqrt(rho^2 + Rb^2), "
                         "d = d_min + x_mu*(d_max - d_min), "
                         "mu = (d == 0) ? 1 : (H^2 - rho^2 - d^2)/(2*r*d)"));
  }
  set_meta(meta, "domain",
           std::string("rays that do not hit the ground, mu >= -sqrt(1 - Rb^2/r^2); for a ray "
                       "toward the ground from p to q use T(q, -mu_q)/T(p, -mu) "
                       "(Bruneton 2017 GetTransmittance)"));
}

}  // namespace

// ---- Mapping ----

TexelPlacement transmittance_placement(TableConvention c) {
  return c == TableConvention::hillaire_demo ? TexelPlacement::centres : TexelPlacement::ends;
}

glm::dvec2 transmittance_uv_from_r_mu(const Atmosphere& atm, double r, double mu, int width,
                                      int height) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  r = std::clamp(r, rb, rt);
  const double H = horizon_distance(atm);
  const double rho = safe_sqrt((r - rb) * (r + rb));
  const double d = distance_to_top_boundary(rt, r, clamp_cosine(mu));
  const double d_min = rt - r, d_max = rho + H;
  const double x_mu = std::clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
  const double x_r = rho / H;
  return {texel_coord_from_unit(x_mu, width), texel_coord_from_unit(x_r, height)};
}

namespace {

// The v half of r_mu_from_transmittance_uv: what a row of the table shares.
struct TransmittanceRow {
  double r, rt, d_min, d_max;
};

TransmittanceRow transmittance_row(const Atmosphere& atm, double v, int height) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double x_r = std::clamp(unit_from_texel_coord(v, height), 0.0, 1.0);
  const double H = horizon_distance(atm);
  const double rho = H * x_r;
  const double r = std::clamp(std::sqrt(rho * rho + rb * rb), rb, rt);
  return {r, rt, rt - r, rho + H};
}

// The u half: mu of the ray whose distance to the top is u's fraction of the
// row's [d_min, d_max].
double transmittance_mu(const TransmittanceRow& row, double u, int width) {
  const double x_mu = std::clamp(unit_from_texel_coord(u, width), 0.0, 1.0);
  const double r = row.r, rt = row.rt;
  const double d = row.d_min + x_mu * (row.d_max - row.d_min);
  // Law of cosines in the triangle centre / point / exit point; H^2 - rho^2 is
  // written (Rt - r)(Rt + r) so that it keeps its digits near the top.
  return d == 0.0 ? 1.0 : clamp_cosine(((rt - r) * (rt + r) - d * d) / (2.0 * r * d));
}

}  // namespace

void r_mu_from_transmittance_uv(const Atmosphere& atm, glm::dvec2 uv, int width, int height,
                                double& r, double& mu) {
  const TransmittanceRow row = transmittance_row(atm, uv.y, height);
  r = row.r;
  mu = transmittance_mu(row, uv.x, width);
}

// ---- Integration ----

glm::dvec3 compute_optical_depth(const Atmosphere& atm, double r, double mu, double d, int steps,
                                 SegmentRule rule) {
  RayQuadrature q(atm, rule == SegmentRule::gauss8);
  return integrate_optical_depth(atm, q, r, mu, d, steps, rule);
}

glm::dvec3 compute_optical_depth_to_top(const Atmosphere& atm, double r, double mu, int steps,
                                        SegmentRule rule) {
  return compute_optical_depth(atm, r, mu, distance_to_top_boundary(atm.top_radius_m, r, mu),
                               steps, rule);
}

glm::dvec3 compute_transmittance_to_top(const Atmosphere& atm, double r, double mu, int steps,
                                        SegmentRule rule) {
  return transmittance_from_optical_depth(compute_optical_depth_to_top(atm, r, mu, steps, rule));
}

std::vector<glm::dvec3> compute_transmittances_to_top(const Atmosphere& atm,
                                                      const std::vector<glm::dvec2>& rays,
                                                      int steps, SegmentRule rule,
                                                      NodeExp exp_kind) {
  // In vacuum every optical depth is 0 (integrate_optical_depth): one
  // transmittance for all.
  if (atm.components.empty())
    return std::vector<glm::dvec3>(rays.size(), transmittance_from_optical_depth(glm::dvec3(0.0)));
  std::vector<glm::dvec3> out(rays.size());
  const RayQuadrature shared(atm, rule == SegmentRule::gauss8, exp_kind);
  // One copy per thread, not per task: a copy is the set-up and its grading
  // cache, which a task of 16 rays would otherwise rebuild.
  tbb::enumerable_thread_specific<RayQuadrature> scratch(shared);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 16),
                    [&](const tbb::blocked_range<size_t>& range) {
                      RayQuadrature& q = scratch.local();
                      for (size_t i = range.begin(); i != range.end(); ++i) {
                        const double r = rays[i].x, mu = rays[i].y;
                        const double d = distance_to_top_boundary(atm.top_radius_m, r, mu);
                        out[i] = transmittance_from_optical_depth(
                            integrate_optical_depth(atm, q, r, mu, d, steps, rule));
                      }
                    });
  return out;
}

// ---- Bake ----

Texture bake_transmittance_lut(const Atmosphere& atm, const TransmittanceLutSpec& spec,
                               const BakeContext& ctx) {
  // One texel along an axis has no texel-centre mapping (1 - 1/N = 0).
  if (spec.width < 2 || spec.height < 2 || spec.steps < 1)
    throw Error(fmt::format(
        "transmittance LUT: expected at least 2x2 texels and 1 step, got {}x{} and {} steps",
        spec.width, spec.height, spec.steps));
  Texture tex(spec.width, spec.height, 1, 1, {"R", "G", "B"});
  set_transmittance_metadata(tex.metadata, atm, spec);
  const TexelPlacement place = transmittance_placement(spec.convention);
  const RayQuadrature shared(atm, true);
  ProgressCounter progress(ctx, size_t(spec.height));
  tbb::parallel_for(
      tbb::blocked_range<int>(0, spec.height), [&](const tbb::blocked_range<int>& rows) {
        RayQuadrature q = shared;  // scratch arrays of this task
        for (int y = rows.begin(); y != rows.end(); ++y) {
          const TransmittanceRow row =
              transmittance_row(atm, skybake_coord_of_texel(place, y, spec.height), spec.height);
          for (int x = 0; x < spec.width; ++x) {
            const double r = row.r,
                         mu = transmittance_mu(row, skybake_coord_of_texel(place, x, spec.width),
                                               spec.width);
            const double d = distance_to_top_boundary(atm.top_radius_m, r, mu);
            const glm::dvec3 T = transmittance_from_optical_depth(
                integrate_optical_depth(atm, q, r, mu, d, spec.steps, SegmentRule::gauss8));
            float* texel = tex.texel(x, y);
            for (int c = 0; c < 3; ++c) texel[c] = float(T[c]);
          }
          progress.tick();
        }
      });
  return tex;
}

// ---- Lookups ----

glm::dvec3 lookup_transmittance_to_top(const Texture& lut, const Atmosphere& atm, double r,
                                       double mu) {
  const glm::dvec2 uv = transmittance_uv_from_r_mu(atm, r, mu, lut.width, lut.height);
  return glm::dvec3(sample_bilinear(lut, uv.x, uv.y, 0, 0, false));
}

TransmittanceAtRadius transmittance_at_radius(const Texture& lut, const Atmosphere& atm, double r) {
  // The r half of transmittance_uv_from_r_mu, the same operations.
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  r = std::clamp(r, rb, rt);
  const double H = horizon_distance(atm);
  const double rho = safe_sqrt((r - rb) * (r + rb));
  const double v = texel_coord_from_unit(rho / H, lut.height);
  return {r,        rt, rt - r, rho + H, bilinear_row(lut, v, 0, 0), 0.5 / lut.width,
          1.0 - 1.0 / lut.width};
}

glm::dvec3 lookup_transmittance(const Texture& lut, const Atmosphere& atm, double r, double mu,
                                double d, bool ray_hits_ground) {
  const double r_d = std::clamp(radius_after(r, mu, d), atm.bottom_radius_m, atm.top_radius_m);
  const double mu_d = mu_after(r, mu, d, r_d);
  // T(p, q) T(q, top) = T(p, top) along one straight line; a ray toward the
  // ground is reversed so that both lookups are rays that point up.
  const glm::dvec3 numerator = ray_hits_ground ? lookup_transmittance_to_top(lut, atm, r_d, -mu_d)
                                               : lookup_transmittance_to_top(lut, atm, r, mu);
  const glm::dvec3 denominator = ray_hits_ground ? lookup_transmittance_to_top(lut, atm, r, -mu)
                                                 : lookup_transmittance_to_top(lut, atm, r_d, mu_d);
  glm::dvec3 T(0.0);
  for (int c = 0; c < 3; ++c)
    T[c] = denominator[c] > 0.0 ? std::min(numerator[c] / denominator[c], 1.0) : 0.0;
  return T;
}

}  // namespace skybake
