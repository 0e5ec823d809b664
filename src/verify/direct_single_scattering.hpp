// Single scattering integrated from scratch, reading no table: the error
// reference of the bake's measurement of the precomputed-scattering tables
// (pipeline/error_measures.hpp, docs/decisions/error-records.md). The tables read the sun's transmittance from the
// transmittance LUT and smooth the shadow over the sun's disk; this
// integrates the sun's optical depth along every sun ray (compute_optical_
// depth_to_top) for a point sun whose light the planet's shadow cuts
// exactly, the convention of the report's adaptive quadrature
// (reference/atmosphere_quadrature.hpp), which it approaches as the steps
// grow (tests/report/bake_error_test.cpp).
//
// Integral (per group c, phase-free, Bruneton's storage):
//   S_c = E_sun int_0^d sigma_s,c(y) T(x, y) Vis(y) T_sun(y) ds
// over the view ray from (r, mu) to the ground or the top. The ray is cut
// at the edge of the planet's shadow, where Vis jumps, and each piece
// integrated with ray_segments (graded toward its densest end, cut at the
// perigee) and 3-point Gauss-Legendre; T(x, y) accumulates the optical
// depth between consecutive nodes.
#pragma once

#include <vector>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"

namespace skybake {

struct DirectScatteringSteps {
  int view_segments = 32;  // Gauss-Legendre segments along the view ray
  int sun_steps = 16;      // compute_optical_depth_to_top steps per sun ray
};

// S_R and S_M (units of sun_illuminance) for a viewer at radius r in the
// shell looking along zenith cosine mu, the sun at zenith cosine mu_s and
// cosine nu to the view. Thread-safe.
SingleScattering compute_single_scattering_direct(const Atmosphere& atm, double r, double mu,
                                                  double mu_s, double nu,
                                                  const DirectScatteringSteps& steps);

// The mean of the above over `azimuths` sun azimuths around the view
// (midpoint rule on [0, pi], the sky being symmetric about the sun's
// vertical plane): what an azimuth-free texel can hold at best
// (scattering3d_lut.hpp).
SingleScattering compute_single_scattering_azimuth_mean(const Atmosphere& atm, double r, double mu,
                                                        double mu_s, int azimuths,
                                                        const DirectScatteringSteps& steps);

// Distances s > 0 along the view ray (r, mu) where the ray toward the sun
// (mu_s, nu at the viewer) is tangent to the sphere of radius `radius` with
// the tangent point ahead of it: r_s^2 - (r mu_s + s nu)^2 = radius^2 and
// r mu_s + s nu < 0, a quadratic in s. For the ground's radius this is the
// edge of the planet's shadow.
std::vector<double> sun_ray_tangencies(double radius, double r, double mu, double mu_s, double nu);

}  // namespace skybake
