// Adaptive quadrature of optical depth, transmittance and single scattering;
// see the header for the integrals, the breakpoints and the error control.
#include "reference/atmosphere_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "core/math.hpp"
#include "reference/density_bounds.hpp"
#include "verify/direct_single_scattering.hpp"

namespace skybake {
namespace {

// Distances in (0, d) where the ray (r, mu) crosses the sphere of a kink
// altitude, and its perigee s = -r mu: between them the altitude is monotone
// and every density smooth.
std::vector<double> ray_breakpoints(const Atmosphere& atm, const std::vector<double>& kinks,
                                    double r, double mu, double d) {
  std::vector<double> s;
  const double perigee = -r * mu;
  if (perigee > 0.0 && perigee < d) s.push_back(perigee);
  for (double h : kinks) {
    const double radius = atm.bottom_radius_m + h;
    const double discriminant = r * r * mu * mu + (radius - r) * (radius + r);
    if (discriminant < 0.0) continue;
    const double q = std::sqrt(discriminant);
    for (double crossing : {perigee - q, perigee + q})
      if (crossing > 0.0 && crossing < d) s.push_back(crossing);
  }
  return s;
}

QuadratureResult<glm::dvec3> optical_depth(const Atmosphere& atm, const std::vector<double>& kinks,
                                           double r, double mu, double d,
                                           const QuadratureOptions& options) {
  const double rb = atm.bottom_radius_m;
  const auto sigma_t = [&](double s) {
    return extinction_at(atm, std::max(0.0, radius_after(r, mu, s) - rb));
  };
  return integrate_adaptive(sigma_t, 0.0, std::max(d, 0.0), options,
                            ray_breakpoints(atm, kinks, r, mu, d));
}

// Optical depth from (r, mu) to the top, through the planet when the ray
// meets it (the transparent planet of with_ground_shadow = false): the air
// before the ground plus the air after it, where the ray comes out.
QuadratureResult<glm::dvec3> optical_depth_to_top(const Atmosphere& atm,
                                                  const std::vector<double>& kinks, double r,
                                                  double mu, const QuadratureOptions& options) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  if (!ray_intersects_ground(rb, r, mu))
    return optical_depth(atm, kinks, r, mu, distance_to_top_boundary(rt, r, mu), options);
  const double to_ground = distance_to_bottom_boundary(rb, r, mu);
  const double out_of_ground = -r * mu + safe_sqrt(r * r * (mu * mu - 1.0) + rb * rb);
  const double mu_out = clamp_cosine((r * mu + out_of_ground) / rb);
  QuadratureResult<glm::dvec3> a = optical_depth(atm, kinks, r, mu, to_ground, options);
  const QuadratureResult<glm::dvec3> b =
      optical_depth(atm, kinks, rb, mu_out, distance_to_top_boundary(rt, rb, mu_out), options);
  a.value += b.value;
  a.error += b.error;
  a.evaluations += b.evaluations;
  a.converged = a.converged && b.converged;
  return a;
}

QuadratureOptions optical_depth_options(double tol) {
  QuadratureOptions o;
  o.relative_tolerance = tol;
  o.absolute_tolerance = 1e-3 * tol;
  return o;
}

// One component that scatters and its weight at density 1: sigma_s,i p_i(nu)
// (radiance) or sigma_s,i alone (phase-free).
struct ScatteringComponent {
  const DensityProfile* density;
  glm::dvec3 weight;
};

// The integral of reference_single_scattering (header) over the components,
// and with the weights, the caller picked.
QuadratureResult<glm::dvec3> single_scattering(const Atmosphere& atm, double r, double mu,
                                               double mu_s, double nu, double tol,
                                               bool with_ground_shadow,
                                               const std::vector<ScatteringComponent>& scatterers) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  mu = clamp_cosine(mu);
  mu_s = clamp_cosine(mu_s);
  nu = clamp_cosine(nu);
  r = std::max(r, rb);
  QuadratureResult<glm::dvec3> result;
  result.converged = true;
  if (r > rt) {  // move to where the ray enters the atmosphere
    const double discriminant = r * r * (mu * mu - 1.0) + rt * rt;
    if (mu >= 0.0 || discriminant < 0.0) return result;
    const double t = -r * mu - std::sqrt(discriminant);
    mu_s = clamp_cosine((r * mu_s + t * nu) / rt);
    mu = clamp_cosine((r * mu + t) / rt);
    r = rt;
  }
  const double d = distance_to_nearest_boundary(rb, rt, r, mu, ray_intersects_ground(rb, r, mu));
  if (!(d > 0.0) || scatterers.empty()) return result;

  const std::vector<double> kinks = density_kink_altitudes(atm);
  QuadratureOptions inner;
  inner.absolute_tolerance = 0.05 * tol;
  inner.relative_tolerance = 1e-13;
  inner.max_evaluations = 100000;
  int64_t inner_evaluations = 0;
  bool inner_converged = true;
  glm::dvec3 inner_error_max(0.0);  // largest error of tau_view + tau_sun met, per channel
  const auto integrand = [&](double s) -> glm::dvec3 {
    const double r_s = std::max(radius_after(r, mu, s), rb);
    const double h = r_s - rb;
    glm::dvec3 source(0.0);
    for (const ScatteringComponent& c : scatterers) source += density_at(*c.density, h) * c.weight;
    if (source == glm::dvec3(0.0)) return source;
    const double mu_s_here = clamp_cosine((r * mu_s + s * nu) / r_s);
    if (with_ground_shadow && ray_intersects_ground(rb, r_s, mu_s_here)) return glm::dvec3(0.0);
    const QuadratureResult<glm::dvec3> view = optical_depth(atm, kinks, r, mu, s, inner);
    const QuadratureResult<glm::dvec3> sun =
        optical_depth_to_top(atm, kinks, r_s, mu_s_here, inner);
    inner_evaluations += view.evaluations + sun.evaluations;
    inner_converged = inner_converged && view.converged && sun.converged;
    inner_error_max = glm::max(inner_error_max, view.error + sun.error);
    return source * glm::exp(-(view.value + sun.value));
  };

  // The edge of the planet's shadow, where Vis jumps, and where the sun ray
  // becomes tangent to a kink altitude's sphere, where the sun's optical
  // depth has a square-root kink (its ray starts or stops crossing it).
  std::vector<double> breakpoints = ray_breakpoints(atm, kinks, r, mu, d);
  for (double s : sun_ray_tangencies(rb, r, mu, mu_s, nu)) breakpoints.push_back(s);
  for (double h : kinks)
    for (double s : sun_ray_tangencies(rb + h, r, mu, mu_s, nu)) breakpoints.push_back(s);
  QuadratureOptions outer;
  outer.relative_tolerance = 0.5 * tol;
  outer.max_evaluations = 100000;
  result = integrate_adaptive(integrand, 0.0, d, outer, breakpoints);
  result.value *= atm.sun_illuminance;
  // An error e in tau is a relative error of at most e in the integrand
  // (|d exp(-tau)| = exp(-tau) |d tau|), first order.
  result.error = result.error * atm.sun_illuminance + inner_error_max * glm::abs(result.value);
  result.evaluations += inner_evaluations;
  result.converged = result.converged && inner_converged;
  return result;
}

}  // namespace

QuadratureResult<glm::dvec3> reference_optical_depth(const Atmosphere& atm, double r, double mu,
                                                     double d, double tol) {
  return optical_depth(atm, density_kink_altitudes(atm), r, clamp_cosine(mu), d,
                       optical_depth_options(tol));
}

QuadratureResult<glm::dvec3> reference_transmittance_to_top(const Atmosphere& atm, double r,
                                                            double mu, double tol) {
  mu = clamp_cosine(mu);
  QuadratureResult<glm::dvec3> result;
  // Blocked when the ray's perigee lies below the ground by more than a
  // rounding error (1e-12 Rb): the horizon ray a LUT maps to its last column,
  // computed back from texture coordinates, is grazing, not blocked.
  const double rb = atm.bottom_radius_m;
  if (mu < 0.0 && r * r * (mu * mu - 1.0) + rb * rb > 2e-12 * rb * rb) {
    result.converged = true;
    return result;
  }
  result =
      reference_optical_depth(atm, r, mu, distance_to_top_boundary(atm.top_radius_m, r, mu), tol);
  const glm::dvec3 t = glm::clamp(glm::exp(-glm::max(result.value, 0.0)), 0.0, 1.0);
  result.error *= t;
  result.value = t;
  return result;
}

QuadratureResult<glm::dvec3> reference_single_scattering(const Atmosphere& atm, double r, double mu,
                                                         double mu_s, double nu, double tol,
                                                         bool with_ground_shadow) {
  std::vector<ScatteringComponent> scatterers;
  for (const MediumComponent& c : atm.components)
    if (c.scattering_per_m != glm::dvec3(0.0) && c.phase != PhaseKind::none)
      scatterers.push_back(
          {&c.density, c.scattering_per_m * phase_function(c.phase, c.g, clamp_cosine(nu))});
  return single_scattering(atm, r, mu, mu_s, nu, tol, with_ground_shadow, scatterers);
}

QuadratureResult<glm::dvec3> reference_single_scattering_phase_free(
    const Atmosphere& atm, double r, double mu, double mu_s, double nu, ScatteringGroup group,
    double tol, bool with_ground_shadow) {
  std::vector<ScatteringComponent> scatterers;
  for (const MediumComponent& c : atm.components) {
    if (c.scattering_per_m == glm::dvec3(0.0) || c.phase == PhaseKind::none) continue;
    if ((c.phase == PhaseKind::rayleigh) == (group == ScatteringGroup::rayleigh))
      scatterers.push_back({&c.density, c.scattering_per_m});
  }
  return single_scattering(atm, r, mu, mu_s, nu, tol, with_ground_shadow, scatterers);
}

QuadratureResult<glm::dvec3> reference_single_scattering(const Atmosphere& atm,
                                                         glm::dvec3 position_m, glm::dvec3 view_dir,
                                                         glm::dvec3 sun_dir, double tol,
                                                         bool with_ground_shadow) {
  const double r = glm::length(position_m);
  const glm::dvec3 up = r > 0.0 ? position_m / r : glm::dvec3(0.0, 0.0, 1.0);
  view_dir = glm::normalize(view_dir);
  sun_dir = glm::normalize(sun_dir);
  return reference_single_scattering(atm, r, glm::dot(up, view_dir), glm::dot(up, sun_dir),
                                     glm::dot(view_dir, sun_dir), tol, with_ground_shadow);
}

}  // namespace skybake
