// The sky path tracer; see the header for the estimator and its conventions.
#include "reference/path_tracer.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "core/math.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "reference/counter_rng.hpp"
#include "reference/phase_sampling.hpp"
#include "reference/planet_shadow.hpp"

namespace skybake {

namespace {

constexpr int kChunkSamples = 64;  // samples per parallel work item
// Segments of the view ray's optical-depth table (forced collision, header).
constexpr int kViewRaySegments = 16;
constexpr double kViewRayDepthTolerance = 1e-12;

// An exponential free path of rate m: -ln(1 - u) / m, u in [0, 1).
double exponential_step(double m, double u) {
  return -std::log1p(-u) / m;
}

}  // namespace

// ---- RadianceAccumulator ----------------------------------------------------

void RadianceAccumulator::add(glm::dvec3 x) {
  ++n_;
  const glm::dvec3 delta = x - mean_;
  mean_ += delta / double(n_);
  m2_ += delta * (x - mean_);
}

void RadianceAccumulator::merge(const RadianceAccumulator& other) {
  if (other.n_ == 0) return;
  if (n_ == 0) {
    *this = other;
    return;
  }
  const double n = double(n_ + other.n_);
  const glm::dvec3 delta = other.mean_ - mean_;
  mean_ += delta * (double(other.n_) / n);
  m2_ += other.m2_ + delta * delta * (double(n_) * double(other.n_) / n);
  n_ += other.n_;
}

RadianceEstimate RadianceAccumulator::estimate() const {
  RadianceEstimate e;
  e.mean = mean_;
  e.samples = int(n_);
  if (n_ < 2) {
    e.ci95 = glm::dvec3(std::numeric_limits<double>::infinity());
    return e;
  }
  const glm::dvec3 variance = glm::max(m2_, 0.0) / double(n_ - 1);
  e.ci95 = 1.96 * glm::sqrt(variance / double(n_));
  return e;
}

// ---- SkyPathTracer ----------------------------------------------------------

SkyPathTracer::SkyPathTracer(const Atmosphere& atm)
    : atm_(atm), flight_bounds_(atm, 16), transmittance_bounds_(atm, AdaptiveBinning{}) {
  for (const MediumComponent& c : atm.components) {
    const glm::dvec3 extinction = c.scattering_per_m + c.absorption_per_m;
    if (extinction == glm::dvec3(0.0) || c.density.layers.empty()) continue;
    // A component without a phase cannot scatter: its sigma_s is lost, as in
    // reference_single_scattering.
    const glm::dvec3 scattering = c.phase == PhaseKind::none ? glm::dvec3(0.0) : c.scattering_per_m;
    components_.push_back({c.density, scattering, extinction, c.phase, c.g});
  }
}

double SkyPathTracer::extinction(double altitude_m, int channel) const {
  double sigma_t = 0.0;
  for (const Component& c : components_)
    sigma_t += density_at(c.density, altitude_m) * c.extinction[channel];
  return sigma_t;
}

bool SkyPathTracer::enter_atmosphere(glm::dvec3 position_m, glm::dvec3 view_dir,
                                     glm::dvec3& start) const {
  const double rb = atm_.bottom_radius_m, rt = atm_.top_radius_m;
  const double r = glm::length(position_m);
  assert(r > 0.0);
  if (r <= rt) {
    start = r < rb ? position_m * (rb / r) : position_m;
    return true;
  }
  const double mu = glm::dot(position_m, view_dir) / r;
  const double discriminant = r * r * (mu * mu - 1.0) + rt * rt;
  if (mu >= 0.0 || discriminant < 0.0) return false;
  const glm::dvec3 entry = position_m + (-r * mu - std::sqrt(discriminant)) * view_dir;
  start = entry * (rt / glm::length(entry));
  return true;
}

// Delta tracking from origin (inside the shell) along dir (unit) to the
// first real collision, the ground or space. The free path is drawn in
// optical units of the majorant and spent across the bins' segments.
template <typename Rng>
SkyPathTracer::Flight SkyPathTracer::fly(glm::dvec3 origin, glm::dvec3 dir, int channel,
                                         Rng& rng) const {
  const double rb = atm_.bottom_radius_m, rt = atm_.top_radius_m;
  const double r = glm::length(origin);
  const double mu = clamp_cosine(glm::dot(origin, dir) / r);
  const bool hits_ground = ray_intersects_ground(rb, r, mu);
  const double t_end = distance_to_nearest_boundary(rb, rt, r, mu, hits_ground);
  AltitudeBinWalker walker(flight_bounds_, r, mu, t_end);
  double t0, t1;
  int bin;
  double optical = exponential_step(1.0, rng());  // to the next tentative collision
  while (walker.next(t0, t1, bin)) {
    const double m = flight_bounds_.upper(bin)[channel];
    if (!(m > 0.0)) continue;
    double t = t0;
    while (t + optical / m < t1) {
      t += optical / m;
      const glm::dvec3 x = origin + t * dir;
      const double h = std::max(0.0, glm::length(x) - rb);
      if (rng() * m < extinction(h, channel)) return {Event::medium, x};
      optical = exponential_step(1.0, rng());
    }
    optical = std::max(0.0, optical - (t1 - t) * m);
  }
  if (!hits_ground) return {Event::escaped, glm::dvec3(0.0)};
  const glm::dvec3 g = origin + t_end * dir;
  return {Event::ground, g * (rb / glm::length(g))};
}

// Residual ratio tracking along the ray from origin (radius r, zenith
// cosine mu) to t_end: per bin segment of length L, the control exp(-lower
// L) is exact and its optical depth is added to control_depth; the return
// value is prod (1 - (sigma_t - lower) / (upper - lower)) over Poisson
// points of rate upper - lower (Novak et al. 2014, eq. 12 with a
// piecewise-constant control), the points drawn as one Poisson process in
// units of the local rate across the segments. No Russian roulette: it
// would turn a deep transmittance into a rare large value.
template <typename Rng>
double SkyPathTracer::residual_transmittance(glm::dvec3 origin, glm::dvec3 dir, double r, double mu,
                                             double t_end, int channel, Rng& rng,
                                             double& control_depth) const {
  const double rb = atm_.bottom_radius_m;
  AltitudeBinWalker walker(transmittance_bounds_, r, mu, t_end);
  double residual = 1.0, t0, t1;
  int bin;
  double optical = exponential_step(1.0, rng());  // to the next point, in units of m
  while (walker.next(t0, t1, bin)) {
    const double lower = transmittance_bounds_.lower(bin)[channel];
    const double m = transmittance_bounds_.upper(bin)[channel] - lower;
    control_depth += lower * (t1 - t0);
    if (!(m > 0.0)) continue;
    double t = t0;
    while (t + optical / m < t1) {
      t += optical / m;
      const double h = std::max(0.0, glm::length(origin + t * dir) - rb);
      residual *= std::clamp(1.0 - (extinction(h, channel) - lower) / m, 0.0, 1.0);
      if (residual == 0.0) return 0.0;
      optical = exponential_step(1.0, rng());
    }
    optical = std::max(0.0, optical - (t1 - t) * m);
  }
  return residual;
}

// The transmittance from origin toward the sun, 0 in the planet's shadow:
// the control times the residual (residual_transmittance).
template <typename Rng>
double SkyPathTracer::sun_transmittance(glm::dvec3 origin, glm::dvec3 sun_dir, int channel,
                                        Rng& rng) const {
  const double rb = atm_.bottom_radius_m, rt = atm_.top_radius_m;
  const double r = glm::length(origin);
  const double mu = clamp_cosine(glm::dot(origin, sun_dir) / r);
  if (ray_intersects_ground(rb, r, mu)) return 0.0;
  double control_depth = 0.0;
  const double residual = residual_transmittance(
      origin, sun_dir, r, mu, distance_to_top_boundary(rt, r, mu), channel, rng, control_depth);
  if (residual == 0.0) return 0.0;
  return std::exp(-control_depth) * residual;
}

// The pieces of the flight segment from origin along dir (to the ground or
// space) that the sun lights, cut at the transmittance bins, each with its
// share of the sampling density q(s) ~ upper(s) exp(-lower depth(0, s))
// (header, "segment"). Returns the total mass of q.
double SkyPathTracer::lit_segment_pieces(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 sun_dir,
                                         int channel, std::vector<LitPiece>& pieces) const {
  const double rb = atm_.bottom_radius_m, rt = atm_.top_radius_m;
  const double r = glm::length(origin);
  const double mu = clamp_cosine(glm::dot(origin, dir) / r);
  const double length =
      distance_to_nearest_boundary(rb, rt, r, mu, ray_intersects_ground(rb, r, mu));
  const ShadowInterval shadow = planet_shadow_interval(origin, dir, sun_dir, rb, length);
  const double inf = std::numeric_limits<double>::infinity();
  const double shadow_begin = shadow.empty() ? inf : shadow.begin;
  const double shadow_end = shadow.empty() ? inf : shadow.end;
  pieces.clear();
  AltitudeBinWalker walker(transmittance_bounds_, r, mu, length);
  double depth = 0.0, total = 0.0, t0, t1;  // depth: the control's optical depth to t0
  int bin;
  while (walker.next(t0, t1, bin)) {
    const double lower = transmittance_bounds_.lower(bin)[channel];
    const double upper = transmittance_bounds_.upper(bin)[channel];
    for (const auto& [a, b] :
         {std::pair{t0, std::min(t1, shadow_begin)}, std::pair{std::max(t0, shadow_end), t1}}) {
      if (!(a < b) || !(upper > 0.0)) continue;
      const double span = lower * (b - a);
      const double integral = span > 1e-12 ? -std::expm1(-span) / lower : b - a;
      const double mass = upper * std::exp(-(depth + lower * (a - t0))) * integral;
      pieces.push_back({a, b, lower, upper, mass, depth + lower * (a - t0)});
      total += mass;
    }
    depth += lower * (t1 - t0);
  }
  return total;
}

// The sun gathered along a flight segment (header, "segment"): one point s
// on the lit pieces, drawn from q1 ~ upper(s) exp(-lower depth(0, s)) or
// uniformly in length (q2), each with probability 1/2, weighted by the
// balance heuristic (one-sample MIS, Veach 1997 sec. 9.2.4): E sum_i
// sigma_s,i p_i(nu) T(0, s) T_sun(s) / (q1 + q2) / 2, with T(0, s) the
// control exp(-lower depth) times the residual.
template <typename Rng>
double SkyPathTracer::segment_sun(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 sun_dir,
                                  int channel, Rng& rng) const {
  thread_local std::vector<LitPiece> pieces;
  const double total = lit_segment_pieces(origin, dir, sun_dir, channel, pieces);
  if (!(total > 0.0)) return 0.0;
  double length = 0.0;
  for (const LitPiece& p : pieces) length += p.t1 - p.t0;
  const bool uniform = rng() < 0.5;
  double pick = rng() * (uniform ? length : total);
  size_t k = 0;
  const auto share = [uniform](const LitPiece& q) { return uniform ? q.t1 - q.t0 : q.mass; };
  while (k + 1 < pieces.size() && pick >= share(pieces[k])) pick -= share(pieces[k++]);
  const LitPiece& p = pieces[k];
  double s = p.t0 + pick;
  if (!uniform) {
    const double u = rng(), span = p.lower * (p.t1 - p.t0);
    s = span > 1e-12 ? p.t0 - std::log1p(u * std::expm1(-span)) / p.lower
                     : p.t0 + u * (p.t1 - p.t0);
  }
  s = std::clamp(s, p.t0, p.t1);
  const glm::dvec3 x = origin + s * dir;
  const double h = std::max(0.0, glm::length(x) - atm_.bottom_radius_m);
  const double nu = clamp_cosine(glm::dot(dir, sun_dir));
  double sigma_s_phase = 0.0;
  for (const Component& c : components_)
    sigma_s_phase +=
        density_at(c.density, h) * c.scattering[channel] * phase_function(c.phase, c.g, nu);
  if (!(sigma_s_phase > 0.0)) return 0.0;
  const double r = glm::length(origin);
  double control_depth = 0.0;
  const double view = residual_transmittance(
      origin, dir, r, clamp_cosine(glm::dot(origin, dir) / r), s, channel, rng, control_depth);
  if (view == 0.0) return 0.0;
  // (q1 + q2) / 2 over the control exp(-lower depth(0, s)), which cancels.
  const double depth = p.depth + p.lower * (s - p.t0);
  const double mixture = 0.5 * p.upper / total + 0.5 * std::exp(depth) / length;
  return atm_.sun_illuminance[channel] * sigma_s_phase * view *
         sun_transmittance(x, sun_dir, channel, rng) / mixture;
}

// The path from its first vertex on: at each vertex the sun by next-event
// estimation, then the next direction, Russian roulette and the next flight.
template <typename Rng>
double SkyPathTracer::continue_path(Flight flight, glm::dvec3 w, glm::dvec3 sun_dir,
                                    const PathTracerSpec& spec, int channel, Rng& rng) const {
  const double rb = atm_.bottom_radius_m;
  const double sun = atm_.sun_illuminance[channel];
  const bool by_segment = spec.sun_estimate == SunEstimate::segment;
  double radiance = 0.0, throughput = 1.0;
  for (int vertex = 1;; ++vertex) {
    const glm::dvec3 x = flight.position;
    if (flight.event == Event::medium) {
      const double h = std::max(0.0, glm::length(x) - rb);
      const double nu = clamp_cosine(glm::dot(w, sun_dir));
      double sigma_s = 0.0, sigma_t = 0.0, sigma_s_phase = 0.0;
      for (const Component& c : components_) {
        const double d = density_at(c.density, h);
        sigma_s += d * c.scattering[channel];
        sigma_t += d * c.extinction[channel];
        sigma_s_phase += d * c.scattering[channel] * phase_function(c.phase, c.g, nu);
      }
      throughput *= sigma_t > 0.0 ? sigma_s / sigma_t : 0.0;
      if (!(throughput > 0.0)) break;
      if (!by_segment)
        radiance += throughput * sun * (sigma_s_phase / sigma_s) *
                    sun_transmittance(x, sun_dir, channel, rng);
      // The next direction: a component by its share of sigma_s, then its phase.
      double pick = rng() * sigma_s;
      const Component* chosen = nullptr;
      for (const Component& c : components_) {
        const double s = density_at(c.density, h) * c.scattering[channel];
        if (s <= 0.0) continue;
        chosen = &c;
        if (pick < s) break;
        pick -= s;
      }
      assert(chosen);
      w = direction_from_cosine(w, sample_phase_cosine(chosen->phase, chosen->g, rng), rng());
    } else {
      if (!spec.ground_reflection) break;
      const glm::dvec3 n = x / rb;
      const double mu_s = glm::dot(n, sun_dir);
      const double albedo = atm_.ground_albedo[channel];
      if (mu_s > 0.0)
        radiance +=
            throughput * albedo / kPi * sun * mu_s * sun_transmittance(x, sun_dir, channel, rng);
      throughput *= albedo;
      if (!(throughput > 0.0)) break;
      w = sample_cosine_hemisphere(n, rng);
    }
    if (vertex >= spec.max_bounces) break;
    if (vertex >= spec.russian_roulette_after) {
      // Survival = throughput (pbrt's rule): a path of full throughput in a
      // medium that does not absorb is never cut short, since in a dense
      // sky its light arrives after hundreds of bounces.
      const double survive = std::min(throughput, 1.0);
      if (rng() >= survive) break;
      throughput /= survive;
    }
    if (by_segment) radiance += throughput * segment_sun(x, w, sun_dir, channel, rng);
    flight = fly(x, w, channel, rng);
    if (flight.event == Event::escaped) break;
  }
  return radiance;
}

// The distance t along the view ray where tau(0, t) = tau*, tau* =
// -ln(1 - u (1 - T)) (header): the segment from the node table, then
// Newton steps kept inside a shrinking bracket [a, b] of that segment,
// tau(t_k, t) by the same quadrature as the table.
double SkyPathTracer::forced_collision_distance(const ViewRay& view, int channel, double u) const {
  const double total = view.depth.back()[channel];
  const double target = std::min(-std::log1p(u * std::expm1(-total)), total);
  size_t k = 0;
  while (k + 2 < view.node_t.size() && view.depth[k + 1][channel] <= target) ++k;
  const double t_k = view.node_t[k], depth_k = view.depth[k][channel];
  const glm::dvec3 x_k = view.start + t_k * view.dir;
  const double r_k = glm::length(x_k), mu_k = clamp_cosine(glm::dot(x_k, view.dir) / r_k);
  const double rb = atm_.bottom_radius_m;
  double a = t_k, b = view.node_t[k + 1];
  const double span = view.depth[k + 1][channel] - depth_k;
  double t = span > 0.0 ? a + (b - a) * (target - depth_k) / span : a;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f =
        depth_k +
        reference_optical_depth(atm_, r_k, mu_k, t - t_k, kViewRayDepthTolerance).value[channel] -
        target;
    if (std::abs(f) <= 1e-13 * std::max(target, 1e-300)) break;
    (f < 0.0 ? a : b) = t;
    const double h = std::max(0.0, glm::length(view.start + t * view.dir) - rb);
    const double slope = extinction(h, channel);
    double next = slope > 0.0 ? t - f / slope : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);  // Newton left the bracket
    if (b - a <= 1e-12 * view.node_t.back()) break;
    t = next;
  }
  return t;
}

// The first flight along the view ray, split (see the header): a collision
// forced onto the ray weighted by 1 - T, plus the ground weighted by T.
template <typename Rng>
double SkyPathTracer::trace_channel(const ViewRay& view, glm::dvec3 sun_dir,
                                    const PathTracerSpec& spec, int channel, Rng& rng) const {
  if (spec.max_bounces < 1) return 0.0;
  const double transmittance = view.transmittance[channel];
  const double collision = -std::expm1(-view.depth.back()[channel]);
  const bool by_segment = spec.sun_estimate == SunEstimate::segment;
  // The segment estimate gathers the view ray's first vertex itself; the
  // forced collision is then needed only for the later ones.
  double radiance = by_segment ? segment_sun(view.start, view.dir, sun_dir, channel, rng) : 0.0;
  if (collision > 0.0 && !(by_segment && spec.max_bounces == 1)) {
    const double t = forced_collision_distance(view, channel, rng());
    const Flight first{Event::medium, view.start + t * view.dir};
    radiance += collision * continue_path(first, view.dir, sun_dir, spec, channel, rng);
  }
  if (view.hits_ground && transmittance > 0.0)
    radiance += transmittance *
                continue_path({Event::ground, view.ground}, view.dir, sun_dir, spec, channel, rng);
  return radiance;
}

bool SkyPathTracer::prepare_view(glm::dvec3 position_m, glm::dvec3 view_dir, ViewRay& view) const {
  view.dir = glm::normalize(view_dir);
  if (!enter_atmosphere(position_m, view.dir, view.start)) return false;
  const double rb = atm_.bottom_radius_m, rt = atm_.top_radius_m;
  const double r = glm::length(view.start);
  const double mu = clamp_cosine(glm::dot(view.start, view.dir) / r);
  view.hits_ground = ray_intersects_ground(rb, r, mu);
  const double t_end = distance_to_nearest_boundary(rb, rt, r, mu, view.hits_ground);
  const glm::dvec3 g = view.start + t_end * view.dir;
  view.ground = view.hits_ground ? g * (rb / glm::length(g)) : glm::dvec3(0.0);
  // The optical-depth table of the forced collision (header).
  view.node_t.assign(kViewRaySegments + 1, 0.0);
  view.depth.assign(kViewRaySegments + 1, glm::dvec3(0.0));
  for (int k = 1; k <= kViewRaySegments; ++k) {
    const double t0 = t_end * (k - 1) / kViewRaySegments;
    view.node_t[k] = t_end * k / kViewRaySegments;
    const glm::dvec3 x0 = view.start + t0 * view.dir;
    const double r0 = glm::length(x0);
    const glm::dvec3 segment =
        reference_optical_depth(atm_, r0, clamp_cosine(glm::dot(x0, view.dir) / r0),
                                view.node_t[k] - t0, kViewRayDepthTolerance)
            .value;
    view.depth[k] = view.depth[k - 1] + glm::max(segment, 0.0);
  }
  view.transmittance = glm::exp(-view.depth.back());
  return true;
}

glm::dvec3 SkyPathTracer::trace_sample(glm::dvec3 position_m, glm::dvec3 view_dir,
                                       glm::dvec3 sun_dir, const PathTracerSpec& spec,
                                       uint64_t sample_index) const {
  ViewRay view;
  if (!prepare_view(position_m, view_dir, view)) return glm::dvec3(0.0);
  return trace_view_sample(view, glm::normalize(sun_dir), spec, sample_index);
}

glm::dvec3 SkyPathTracer::trace_view_sample(const ViewRay& view, glm::dvec3 sun_dir,
                                            const PathTracerSpec& spec,
                                            uint64_t sample_index) const {
  glm::dvec3 value(0.0);
  for (int c = 0; c < 3; ++c) {
    CounterRng rng(spec.seed, sample_index, uint64_t(c));
    value[c] = trace_channel(view, sun_dir, spec, c, rng);
  }
  return value;
}

RadianceEstimate SkyPathTracer::trace(glm::dvec3 position_m, glm::dvec3 view_dir,
                                      glm::dvec3 sun_dir, const PathTracerSpec& spec) const {
  const int samples = std::max(spec.samples, 1);
  ViewRay view;
  if (!prepare_view(position_m, view_dir, view)) {
    RadianceEstimate black;
    black.samples = samples;
    return black;  // the ray misses the atmosphere: exactly 0
  }
  sun_dir = glm::normalize(sun_dir);
  const int chunks = (samples + kChunkSamples - 1) / kChunkSamples;
  std::vector<RadianceAccumulator> partial(static_cast<size_t>(chunks));
  tbb::parallel_for(
      tbb::blocked_range<int>(0, chunks, 1), [&](const tbb::blocked_range<int>& range) {
        for (int chunk = range.begin(); chunk != range.end(); ++chunk) {
          const int end = std::min(samples, (chunk + 1) * kChunkSamples);
          for (int k = chunk * kChunkSamples; k < end; ++k)
            partial[size_t(chunk)].add(trace_view_sample(view, sun_dir, spec, uint64_t(k)));
        }
      });
  RadianceAccumulator total;
  for (const RadianceAccumulator& p : partial) total.merge(p);
  return total.estimate();
}

RadianceEstimate trace_sky_radiance(const Atmosphere& atm, glm::dvec3 position_m,
                                    glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                    const PathTracerSpec& spec) {
  return SkyPathTracer(atm).trace(position_m, view_dir, sun_dir, spec);
}

}  // namespace skybake
