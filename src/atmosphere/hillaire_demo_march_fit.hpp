// A Psi_ms table made for Hillaire's demo march (the multiscattering output's
// "fit_demo_march", docs/runtime.md "Using skybake's tables in a renderer
// derived from Hillaire's demo", docs/decisions/hillaire-demo-march.md).
//
// His IntegrateScatteredLuminance (hillaire_demo_march.hpp) samples each
// segment at 0.3 of its length, where the air is denser than on the
// segment's average for a rising ray: with exact tables his march at his
// sample counts renders the sky 2 to 7 % bright. No table can move his
// samples, but Psi_ms is a model quantity (Hillaire 2020 eq. 10): its rows
// are scaled per channel by k(h), piecewise linear on kDemoMarchFitNodes
// altitudes evenly over the shell, so that his march at his two settings
// (RayMarchMinMaxSPP 4-14 and 30-31) reading the scaled table comes closest,
// in relative least squares, to his march at 2000 samples reading the
// unscaled one, over fixed training views (cameras 1 m to 10 km, suns 1 to
// 80 degrees up, views 1 to 89 degrees). The transmittance stays the
// transmittance. The fit sees no path tracer; its target is the same
// tables' converged march.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "core/texture.hpp"

namespace skybake {

constexpr int kDemoMarchFitNodes = 8;

// k per node (node i at altitude i / (nodes - 1) of the shell) and channel.
struct DemoMarchFit {
  std::array<glm::dvec3, kDemoMarchFitNodes> factors;
};

// Fits k for a multiscattering table and a transmittance table, both in
// the hillaire_demo convention. Deterministic for any thread count.
DemoMarchFit fit_demo_march(const Atmosphere& atm, const Texture& transmittance_demo,
                            const Texture& multiscattering_demo);

// k at an altitude (clamped to the shell).
glm::dvec3 demo_march_factor(const Atmosphere& atm, const DemoMarchFit& fit, double altitude_m);

// The table's rows (his sub-uv altitude positions) scaled by k, and the
// factors recorded in its metadata: "demo_march_fit" (int, the node count)
// and "demo_march_fit.<i>" (double3, node i's R, G, B factor).
void apply_demo_march_fit(const Atmosphere& atm, const DemoMarchFit& fit,
                          Texture& multiscattering_demo);

}  // namespace skybake
