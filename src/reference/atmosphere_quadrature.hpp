// Ground truth for the atmosphere's line integrals by adaptive quadrature
// (reference/adaptive_quadrature.hpp): optical depth and transmittance along
// a ray, and single-scattered luminance along a view ray (Hillaire 2020
// eq. 1-4 without the ground term and without multiple scattering). Slow,
// simple and controlled by a requested tolerance; never in the fast path.
// The bakers' errors are measured against these.
//
// Why they can be trusted: every integral is cut where its integrand is not
// smooth (the altitudes where a density profile has a kink, crossed by the
// ray; the ray's perigee; the edge of the planet's shadow; where the sun
// ray becomes tangent to a kink altitude's sphere), and each smooth
// piece is integrated by G7-K15 until the error estimate meets the
// tolerance. Nothing is tabulated: the sun's transmittance at every point is
// integrated from scratch. Closed forms of optical depth (uniform slab,
// exponential, ozone tent) and of single scattering in a uniform slab are
// met to 1e-10 (tests/reference/atmosphere_quadrature_test.cpp).
//
// Geometry: a viewer at radius r (m) looks along a ray of zenith cosine mu;
// the sun has zenith cosine mu_s at the viewer, and nu is the cosine between
// the view direction and the direction to the sun (phase.hpp: nu = 1 looks
// into the sun, where the Mie peak is). At distance s along the ray the
// radius is r_s = sqrt(r^2 + 2 r mu s + s^2) and the sun's zenith cosine is
// (r mu_s + s nu) / r_s.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "reference/adaptive_quadrature.hpp"

namespace skybake {

// Optical depth (dimensionless, RGB) of the segment of length d (m) from
// radius r (m) along zenith cosine mu: integral_0^d sigma_t(h(s)) ds. The
// segment should stay in the shell (altitudes below 0 read the ground's
// density). tol: relative tolerance per channel, with an absolute floor of
// 1e-3 tol (an optical depth error that small is invisible in exp(-tau)).
QuadratureResult<glm::dvec3> reference_optical_depth(const Atmosphere& atm, double r, double mu,
                                                     double d, double tol);

// Transmittance exp(-tau) from (r, mu) to the top boundary, each channel in
// [0, 1]; 0 for a ray that enters the ground (the planet blocks it), while a
// ray tangent to it within rounding (perigee less than 1e-12 Rb below the
// ground) is the grazing horizon ray and is integrated. The error is that of
// tau times T (first order).
QuadratureResult<glm::dvec3> reference_transmittance_to_top(const Atmosphere& atm, double r,
                                                            double mu, double tol);

// Single-scattered luminance reaching the viewer (r, mu) from the medium
// along the view ray up to where it leaves the atmosphere or meets the
// ground, for a sun (mu_s, nu) of illuminance Atmosphere::sun_illuminance
// (so per unit sun illuminance when that is 1, the convention of the baked
// LUTs):
//   L = E integral_0^D T(0, s) Vis(s) T_sun(s) sum_i sigma_s,i(h(s)) p_i(nu) ds,
// T(0, s) = exp(-tau(0, s)) along the view ray, T_sun(s) = exp(-tau) from the
// point to the top toward the sun, Vis(s) = 0 where the sun ray meets the
// ground (the planet's shadow), else 1. Each component scatters with its own
// phase function. The ground's reflection is not included. A viewer above
// the atmosphere is moved to where the ray enters it (0 if it misses); a
// viewer below the ground stands on it.
//
// with_ground_shadow = false makes the planet transparent to the sun: Vis = 1
// and a sun ray through the planet is attenuated by the air it crosses on
// both sides of it (nothing inside).
//
// Error control (nested): the outer integral over s is driven to relative
// tolerance tol / 2 per channel; each optical depth inside it (view ray from
// the viewer to s, sun ray from s to the top) to an absolute error of
// 0.05 tol (or 1e-13 tau when larger, near the rounding floor). L depends on
// tau through exp(-tau), so an error e in tau is a relative error e in the
// integrand: the inner integrals add at most 0.1 tol to the relative error
// of L. The returned error is honest rather than tight: the outer estimate
// plus |L| times the largest inner error estimate met at any evaluation.
// `evaluations` counts the medium evaluations of both levels; `converged`
// is false if any integral hit its evaluation limit. Practical tol: 1e-4 to
// 1e-11 (a few ms for an Earth view at 1e-6).
QuadratureResult<glm::dvec3> reference_single_scattering(const Atmosphere& atm, double r, double mu,
                                                         double mu_s, double nu, double tol,
                                                         bool with_ground_shadow = true);

// The phase-free single scattering of one group of components, what
// Bruneton-style tables store (scattering_lut.hpp, scattering3d_lut.hpp):
//   S_group = E integral_0^D T(0, s) Vis(s) T_sun(s) sum_{i in group} sigma_s,i(h(s)) ds,
// the Rayleigh group being the components with the Rayleigh phase, the Mie
// group the other components that scatter. nu still places the sun (shadow,
// T_sun); only the phase factor is left out, so that
//   p_R(nu) S_rayleigh + p_M(nu) S_mie = reference_single_scattering
// when the Mie group shares one phase p_M (tested). Same geometry and error
// control as above.
enum class ScatteringGroup { rayleigh, mie };
QuadratureResult<glm::dvec3> reference_single_scattering_phase_free(
    const Atmosphere& atm, double r, double mu, double mu_s, double nu, ScatteringGroup group,
    double tol, bool with_ground_shadow = true);

// The same for a planet-centred position (m), a view direction (travelling
// away from the eye) and a direction toward the sun; directions need not be
// normalized.
QuadratureResult<glm::dvec3> reference_single_scattering(const Atmosphere& atm,
                                                         glm::dvec3 position_m, glm::dvec3 view_dir,
                                                         glm::dvec3 sun_dir, double tol,
                                                         bool with_ground_shadow = true);

}  // namespace skybake
