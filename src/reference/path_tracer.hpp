// A Monte Carlo volumetric path tracer of sky radiance with every scattering
// order: the ground truth the sky LUTs (single scattering, Hillaire's
// multiple-scattering approximation, Bruneton's orders) are measured
// against. Slow and simple; never in the fast path. The reference of
// Hillaire 2020 section 6 works the same way: delta tracking for free paths,
// ratio tracking for the transmittance toward the sun (Novak, Selle & Jarosz
// 2014), next-event estimation of the sun.
//
// What it estimates (the convention of the baked LUTs, sky_integrator.hpp):
// the radiance (luminance) L(x, -w) reaching the viewer at x from the view
// direction w (travelling away from the eye), for a sun that is a
// directional light of illuminance E = Atmosphere::sun_illuminance in
// direction l (toward the sun) at the top of the atmosphere. L is the
// solution of the radiative transfer equation in the shell Rb < |x| < Rt
// with a Lambertian ground of albedo Atmosphere::ground_albedo, black
// space, and sources: single scattering sigma_s,i p_i(dot(w, l)) T_sun Vis E
// in the medium and albedo / pi E T_sun max(dot(n, l), 0) on the ground.
// The sun itself (its delta, or a disk) is not part of L, as in the
// sky-view LUT. With E = 1, L is radiance per unit sun illuminance (1/sr).
//
// Method, per RGB channel separately (each channel is a scalar transport
// problem with its own majorant, so every weight stays in [0, 1]: no
// spectral MIS or hero wavelength to get wrong; three times the work):
// - free flight by delta tracking with a piecewise-constant majorant: the
//   upper bound of sigma_t in each altitude bin the ray crosses
//   (extinction_bounds.hpp);
// - at a real collision the throughput is multiplied by the single-scattering
//   albedo sigma_s / sigma_t; the sun is gathered by next-event estimation:
//   E sum_i sigma_s,i p_i(dot(w, l)) / sigma_s times the sun's transmittance,
//   estimated by residual ratio tracking (0 when the sun ray meets the
//   ground): exp(-optical depth of the bins' lower bounds), exact, times
//   ratio tracking of the residual between the bounds; the
//   path continues in a direction sampled from the phase of one component
//   picked with probability sigma_s,i / sigma_s (exact sampling, weight 1:
//   phase_sampling.hpp);
// - at the ground: the sun's diffuse reflection by next-event estimation,
//   throughput times the albedo, a cosine-weighted bounce;
// - Russian roulette after `russian_roulette_after` vertices (survival
//   probability min(throughput, 1)), a hard stop after `max_bounces`
//   vertices: the only bias, scattering orders above max_bounces are
//   dropped. Earth needs ~10 orders; a dense sky (optical depth tau, little
//   absorption) needs ~tau^2, so raise max_bounces there;
// - the first flight, along the view ray, is split: in thin air most free
//   paths would escape and gather nothing. With T the view ray's
//   transmittance, a path continues from a first collision forced onto the
//   ray with weight 1 - T, and, when the view ray ends on the ground,
//   another from the ground with weight T. The forced collision is drawn
//   exactly from the distribution conditioned on a collision, sigma_t(t)
//   T(0, t) / (1 - T), by inverting the optical depth: tau* = -ln(1 - u (1 -
//   T)), then t with tau(0, t) = tau*, found on a table of tau at
//   kViewRaySegments nodes along the ray (adaptive quadrature to 1e-12 per
//   segment, atmosphere_quadrature.hpp) and, inside the segment, by
//   safeguarded Newton steps on the same quadrature. Its cost does not
//   depend on 1 - T (rejection, tried first, needed 1 / (1 - T) flights: 1e5
//   in an atmosphere 1 m thick).
// The sun is a delta light, so a sampled direction never reaches it and
// next-event estimation alone counts it (no MIS needed).
//
// Two unbiased estimates of the sun scattered in the medium
// (PathTracerSpec::sun_estimate), the same expectation:
// - collision (the default): at each real collision, as above;
// - segment: before each flight, its expectation over the collision along
//   the whole segment, E sum_i p_i(nu) int T(0, s) sigma_s,i(s) T_sun(s)
//   Vis(s) ds (nu is constant along a straight segment), estimated with one
//   point drawn on the segment's lit part only (planet_shadow.hpp: the
//   shadow is one interval of a line), from upper(s) exp(-lower depth(0,
//   s)) with the transmittance bins' bounds (where the air is) or uniformly
//   in length (where the sun's transmittance, near 0 at the shadow's edge,
//   lets the light through), one of the two at random and weighted by the
//   balance heuristic; T(0, s) by residual ratio tracking. The collisions
//   then only carry the path on. With the sun below the
//   horizon, the light comes from the thin lit air high above the shadow,
//   which a collision reaches with a probability of 1e-3 to 1e-5: the
//   collision estimate's mean is right but its sum over thousands of paths
//   is mostly zero, while the segment estimate puts every point there.
//
// Altitude bins: 16 equal bins for the delta-tracking majorant (fewer
// segments to walk; a loose majorant only costs null collisions) and
// adaptive bins (AdaptiveBinning defaults) for the ratio-tracking control.
//
// Determinism: sample k of channel c draws from CounterRng(seed, k, c), the
// samples run in parallel in fixed chunks and are reduced in chunk order, so
// an estimate is bit-identical for any thread count. The 95% confidence
// interval is 1.96 standard errors per channel (sample variance over the
// paths; the estimator is a mean of independent paths, so the CLT applies).
// Where single paths are heavy-tailed (a sun transmittance of 1e-20 through
// a dense sky, g near 1, the sun below the horizon with the collision
// estimate) the sample variance converges slowly and the interval can be
// optimistic at small sample counts: use thousands of paths there (or the
// segment estimate in twilight: in single-scattering mode 256 collision
// paths read 0 to 27x the quadrature at 94-98 degrees, the segment
// estimate within its interval; with every order both agree at 94 degrees,
// tests/reference/path_tracer_twilight_accuracy_test.cpp). On Earth, z-scores of the estimates
// against the quadrature over many seeds have mean ~0 and variance ~1.
//
// Cost (one core, Earth, viewer on the ground): ~130k samples per second
// (three channels each, all orders) for a daytime view 30 degrees up, about
// 0.1 s to a 1% interval; ~200k-340k per second in single-scattering mode.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "reference/extinction_bounds.hpp"

namespace skybake {

// How the sun scattered in the medium is gathered (see the top).
enum class SunEstimate { collision, segment };

struct PathTracerSpec {
  uint64_t seed = 1;     // RNG key: same seed, same estimate, bit for bit
  int samples = 4096;    // paths per channel, >= 1
  int max_bounces = 64;  // vertices (medium or ground) that gather sunlight; 1 = single scattering
  bool ground_reflection = true;   // Lambertian ground of ground_albedo; false: a black ground
  int russian_roulette_after = 3;  // vertices before Russian roulette may end a path
  SunEstimate sun_estimate = SunEstimate::collision;
};

// The single-scattering mode: one vertex and a black ground, the quantity
// reference_single_scattering integrates (atmosphere_quadrature.hpp).
inline PathTracerSpec single_scattering_spec(PathTracerSpec spec = {}) {
  spec.max_bounces = 1;
  spec.ground_reflection = false;
  return spec;
}

struct RadianceEstimate {
  glm::dvec3 mean{0.0};  // radiance, units of Atmosphere::sun_illuminance (see the top)
  glm::dvec3 ci95{0.0};  // half-width of the 95% confidence interval: 1.96 standard errors
  int samples = 0;       // paths per channel
};

// Running mean and variance of RGB samples (Welford; merged with Chan et
// al.'s pairwise formula). Identical samples give a variance of exactly 0.
class RadianceAccumulator {
 public:
  void add(glm::dvec3 x);
  void merge(const RadianceAccumulator& other);
  // ci95 is infinite with fewer than two samples.
  RadianceEstimate estimate() const;

 private:
  int64_t n_ = 0;
  glm::dvec3 mean_{0.0};
  glm::dvec3 m2_{0.0};  // sum of squared deviations from the mean
};

class SkyPathTracer {
 public:
  // Copies what it needs of the atmosphere and builds the extinction bounds.
  explicit SkyPathTracer(const Atmosphere& atm);

  // One path per channel for sample `sample_index` of spec.seed. position_m
  // is planet-centred (m); a viewer above the atmosphere starts where the
  // view ray enters it (0 if it misses); a viewer below the ground stands on
  // it. Directions need not be normalized. Pure; thread-safe.
  glm::dvec3 trace_sample(glm::dvec3 position_m, glm::dvec3 view_dir, glm::dvec3 sun_dir,
                          const PathTracerSpec& spec, uint64_t sample_index) const;

  // spec.samples paths per channel, in parallel (tbb::parallel_for over
  // fixed chunks; deterministic reduction).
  RadianceEstimate trace(glm::dvec3 position_m, glm::dvec3 view_dir, glm::dvec3 sun_dir,
                         const PathTracerSpec& spec) const;

 private:
  struct Component {
    DensityProfile density;
    glm::dvec3 scattering;  // sigma_s at density 1; 0 for components without a phase
    glm::dvec3 extinction;  // sigma_t at density 1
    PhaseKind phase;
    double g;
  };
  enum class Event { escaped, medium, ground };
  struct Flight {
    Event event = Event::escaped;
    glm::dvec3 position{0.0};
  };
  // The view ray inside the atmosphere, shared by all samples of a view.
  struct ViewRay {
    glm::dvec3 start{0.0}, dir{0.0};
    bool hits_ground = false;
    glm::dvec3 ground{0.0};         // where it meets the ground, if it does
    glm::dvec3 transmittance{1.0};  // along the whole ray, exp(-depth.back())
    std::vector<double> node_t;     // kViewRaySegments + 1 distances from start, 0 .. length
    std::vector<glm::dvec3> depth;  // optical depth from start to each node
  };
  bool prepare_view(glm::dvec3 position_m, glm::dvec3 view_dir, ViewRay& view) const;
  glm::dvec3 trace_view_sample(const ViewRay& view, glm::dvec3 sun_dir, const PathTracerSpec& spec,
                               uint64_t sample_index) const;
  template <typename Rng>
  Flight fly(glm::dvec3 origin, glm::dvec3 dir, int channel, Rng& rng) const;
  // A lit piece [t0, t1) of a flight segment in one bin, its mass of q1 and
  // the control's optical depth from the segment's start to t0.
  struct LitPiece {
    double t0, t1, lower, upper, mass, depth;
  };
  template <typename Rng>
  double residual_transmittance(glm::dvec3 origin, glm::dvec3 dir, double r, double mu,
                                double t_end, int channel, Rng& rng, double& control_depth) const;
  double lit_segment_pieces(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 sun_dir, int channel,
                            std::vector<LitPiece>& pieces) const;
  template <typename Rng>
  double segment_sun(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 sun_dir, int channel,
                     Rng& rng) const;
  template <typename Rng>
  double sun_transmittance(glm::dvec3 origin, glm::dvec3 sun_dir, int channel, Rng& rng) const;
  double forced_collision_distance(const ViewRay& view, int channel, double u) const;
  template <typename Rng>
  double continue_path(Flight first, glm::dvec3 w, glm::dvec3 sun_dir, const PathTracerSpec& spec,
                       int channel, Rng& rng) const;
  template <typename Rng>
  double trace_channel(const ViewRay& view, glm::dvec3 sun_dir, const PathTracerSpec& spec,
                       int channel, Rng& rng) const;
  double extinction(double altitude_m, int channel) const;
  bool enter_atmosphere(glm::dvec3 position_m, glm::dvec3 view_dir, glm::dvec3& start) const;

  Atmosphere atm_;
  std::vector<Component> components_;
  ExtinctionBounds flight_bounds_;         // coarse: majorants for delta tracking
  ExtinctionBounds transmittance_bounds_;  // fine: control and residual for ratio tracking
};

// One-shot convenience: SkyPathTracer(atm).trace(...).
RadianceEstimate trace_sky_radiance(const Atmosphere& atm, glm::dvec3 position_m,
                                    glm::dvec3 view_dir, glm::dvec3 sun_dir,
                                    const PathTracerSpec& spec);

}  // namespace skybake
