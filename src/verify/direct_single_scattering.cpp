#include "verify/direct_single_scattering.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/geometry.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "verify/query_points.hpp"

namespace skybake {

namespace {

// Gauss-Legendre nodes of the view ray (r, mu) over [0, d], each piece
// between shadow edges on its own segments, in increasing s.
std::vector<RayNode> view_nodes(const Atmosphere& atm, double r, double mu, double mu_s, double nu,
                                double d, int segments) {
  std::vector<double> cuts = {0.0};
  for (double s : sun_ray_tangencies(atm.bottom_radius_m, r, mu, mu_s, nu))
    if (s < d) cuts.push_back(s);
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(d);
  std::vector<RayNode> nodes;
  std::vector<RaySegment> pieces;
  for (size_t p = 0; p + 1 < cuts.size(); ++p) {
    const double a = cuts[p], length = cuts[p + 1] - a;
    if (!(length > 0.0)) continue;
    const double r_a = radius_after(r, mu, a);
    const double mu_a = mu_after(r, mu, a, r_a);
    const int share = std::max(1, int(std::lround(segments * length / d)));
    ray_segments(r_a, mu_a, length, 3 * share, pieces);
    for (const RaySegment& g : pieces) {
      const double centre = a + 0.5 * (g.a + g.b), half = 0.5 * (g.b - g.a);
      for (int k = 0; k < 3; ++k)
        nodes.push_back({centre + half * kGauss3Nodes[k], half * kGauss3Weights[k]});
    }
  }
  return nodes;
}

// Optical depth of the view ray (r, mu) between distances a < b, 3-point
// Gauss-Legendre: consecutive nodes are close, and the extinction smooth
// between them (a kink inside costs second order on a short interval).
glm::dvec3 optical_depth_between(const Atmosphere& atm, double r, double mu, double a, double b) {
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  glm::dvec3 tau(0.0);
  for (int k = 0; k < 3; ++k) {
    const double h = radius_after(r, mu, centre + half * kGauss3Nodes[k]) - atm.bottom_radius_m;
    tau += kGauss3Weights[k] * extinction_at(atm, std::max(h, 0.0));
  }
  return half * tau;
}

}  // namespace

std::vector<double> sun_ray_tangencies(double radius, double r, double mu, double mu_s, double nu) {
  const double a = 1.0 - nu * nu;
  const double b = 2.0 * r * (mu - mu_s * nu);
  const double c = (r - radius) * (r + radius) - r * r * mu_s * mu_s;
  std::vector<double> roots;
  if (std::abs(a) < 1e-12) {
    if (b != 0.0) roots.push_back(-c / b);
  } else {
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant >= 0.0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
      roots.push_back(q / a);
      if (q != 0.0) roots.push_back(c / q);
    }
  }
  std::vector<double> out;
  for (double s : roots)
    if (s > 0.0 && r * mu_s + s * nu < 0.0) out.push_back(s);
  return out;
}

SingleScattering compute_single_scattering_direct(const Atmosphere& atm, double r, double mu,
                                                  double mu_s, double nu,
                                                  const DirectScatteringSteps& steps) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  r = std::clamp(r, rb, rt);
  mu = clamp_cosine(mu);
  mu_s = clamp_cosine(mu_s);
  nu = clamp_cosine(nu);
  SingleScattering out;
  const double d = distance_to_nearest_boundary(rb, rt, r, mu, ray_intersects_ground(rb, r, mu));
  if (!(d > 0.0)) return out;
  glm::dvec3 tau_view(0.0);
  double s_previous = 0.0;
  for (const RayNode& n : view_nodes(atm, r, mu, mu_s, nu, d, steps.view_segments)) {
    const double r_s = radius_after(r, mu, n.s);
    tau_view += optical_depth_between(atm, r, mu, s_previous, n.s);
    s_previous = n.s;
    glm::dvec3 rayleigh, mie;
    scattering_by_group(atm, std::max(r_s - rb, 0.0), rayleigh, mie);
    if (rayleigh == glm::dvec3(0.0) && mie == glm::dvec3(0.0)) continue;
    const double mu_s_here = clamp_cosine((r * mu_s + n.s * nu) / r_s);
    if (ray_intersects_ground(rb, r_s, mu_s_here)) continue;  // the planet's shadow
    const glm::dvec3 tau_sun = compute_optical_depth_to_top(atm, r_s, mu_s_here, steps.sun_steps);
    const glm::dvec3 a = n.weight * glm::exp(-(tau_view + tau_sun));
    out.rayleigh += a * rayleigh;
    out.mie += a * mie;
  }
  out.rayleigh *= atm.sun_illuminance;
  out.mie *= atm.sun_illuminance;
  return out;
}

SingleScattering compute_single_scattering_azimuth_mean(const Atmosphere& atm, double r, double mu,
                                                        double mu_s, int azimuths,
                                                        const DirectScatteringSteps& steps) {
  SingleScattering mean;
  for (int k = 0; k < azimuths; ++k) {
    const double nu = nu_from_azimuth(mu, mu_s, (k + 0.5) * kPi / azimuths);
    const SingleScattering s = compute_single_scattering_direct(atm, r, mu, mu_s, nu, steps);
    mean.rayleigh += s.rayleigh / double(azimuths);
    mean.mie += s.mie / double(azimuths);
  }
  return mean;
}

}  // namespace skybake
