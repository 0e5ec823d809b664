// Atmospheres for the atmosphere tests, built with the medium.hpp helpers:
// Earth with the constants of docs/reference.md (Hillaire 2020 and its demo), a
// small fake planet, and media simple enough to have closed forms (empty, a
// uniform slab, a single exponential or tent layer); and the small input
// LUTs of the sky-view and aerial-perspective tests. Header only; every test
// of tests/atmosphere may include it.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "atmosphere/geometry.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"

namespace skybake::fixtures {

inline MediumComponent make_component(std::string name, glm::dvec3 scattering_per_m,
                                      glm::dvec3 absorption_per_m, DensityProfile density,
                                      PhaseKind phase = PhaseKind::none, double g = 0.0) {
  MediumComponent c;
  c.name = std::move(name);
  c.scattering_per_m = scattering_per_m;
  c.absorption_per_m = absorption_per_m;
  c.density = std::move(density);
  c.phase = phase;
  c.g = g;
  return c;
}

inline MediumComponent earth_rayleigh() {
  return make_component("rayleigh", {5.802e-6, 13.558e-6, 33.1e-6}, glm::dvec3(0.0),
                        exponential_profile(8e3), PhaseKind::rayleigh);
}
inline MediumComponent earth_mie() {
  return make_component("mie", glm::dvec3(3.996e-6), glm::dvec3(0.444e-6),
                        exponential_profile(1.2e3), PhaseKind::cornette_shanks, 0.8);
}
inline MediumComponent earth_ozone() {
  return make_component("ozone", glm::dvec3(0.0), {0.650e-6, 1.881e-6, 0.085e-6},
                        tent_profile(10e3, 25e3, 40e3));
}

// Earth: Rb 6360 km, Rt 6460 km, Rayleigh + Mie + ozone (docs/reference.md).
inline Atmosphere earth_atmosphere() {
  Atmosphere atm;
  atm.bottom_radius_m = 6360e3;
  atm.top_radius_m = 6460e3;
  atm.ground_albedo = glm::dvec3(0.3);
  atm.components = {earth_rayleigh(), earth_mie(), earth_ozone()};
  return atm;
}

// A tiny planet (an extreme case of the domain, docs/reference.md "Atmosphere
// model"): 1 km radius under a 200 m thick dense sky, an exponential of
// 50 m scale height 1000x Earth's Rayleigh.
inline Atmosphere tiny_planet_atmosphere() {
  Atmosphere atm;
  atm.bottom_radius_m = 1e3;
  atm.top_radius_m = 1.2e3;
  atm.components = {make_component("rayleigh", {5.802e-3, 13.558e-3, 33.1e-3}, glm::dvec3(0.0),
                                   exponential_profile(50.0), PhaseKind::rayleigh)};
  return atm;
}

// Earth's radii with no media at all: transmittance is exactly 1.
inline Atmosphere empty_atmosphere() {
  Atmosphere atm;
  atm.bottom_radius_m = 6360e3;
  atm.top_radius_m = 6460e3;
  return atm;
}

// Earth's radii and one absorbing component of the given density profile.
inline Atmosphere single_component_atmosphere(glm::dvec3 absorption_per_m, DensityProfile density) {
  Atmosphere atm = empty_atmosphere();
  atm.components = {make_component("test", glm::dvec3(0.0), absorption_per_m, std::move(density))};
  return atm;
}

// Constant extinction sigma_t (split into scattering and absorption) filling
// the whole shell: a uniform slab from the ground to the top.
inline Atmosphere uniform_slab_atmosphere(glm::dvec3 scattering_per_m, glm::dvec3 absorption_per_m,
                                          double bottom_radius_m = 6360e3,
                                          double top_radius_m = 6460e3) {
  Atmosphere atm;
  atm.bottom_radius_m = bottom_radius_m;
  atm.top_radius_m = top_radius_m;
  atm.components = {make_component("slab", scattering_per_m, absorption_per_m,
                                   uniform_profile(0.0, top_radius_m - bottom_radius_m),
                                   PhaseKind::rayleigh)};
  return atm;
}

// `atm` with every component's scattering and absorption times `factor`:
// a denser (or thinner) medium of the same profiles.
inline Atmosphere scaled_atmosphere(Atmosphere atm, double factor) {
  for (MediumComponent& c : atm.components) {
    c.scattering_per_m *= factor;
    c.absorption_per_m *= factor;
  }
  return atm;
}

// The LUTs the sky-view and aerial-perspective bakers read, small: a 128 x 64
// transmittance LUT (40 steps) and a 16 x 16 multiple-scattering LUT.
struct SkyLutInputs {
  Texture transmittance, multiscattering;
};

inline SkyLutInputs bake_sky_lut_inputs(const Atmosphere& atm) {
  SkyLutInputs l;
  l.transmittance = bake_transmittance_lut(atm, {128, 64, 40}, {});
  l.multiscattering = bake_multiscattering_lut(atm, l.transmittance, {16, 16, 32, 20}, {});
  return l;
}

// Single scattering reads one thing from the transmittance LUT, the
// transmittance toward the sun at each node; the view ray's own is
// integrated along the ray (ray_transfer.hpp). With the sun straight along
// the view ray (mu_s = mu, nu = 1), the largest relative error of those
// reads against exp(-depth_to_top(s)), over 400 points of the ray of length
// d, bounds the error single scattering inherits from the LUT.
template <class DepthToTop>
double sun_lut_error_along_ray(const Texture& lut, const Atmosphere& atm, double r, double mu,
                               double d, DepthToTop depth_to_top) {
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double s = d * i / 400.0;
    const double r_s = std::clamp(radius_after(r, mu, s), atm.bottom_radius_m, atm.top_radius_m);
    const glm::dvec3 T = lookup_transmittance_to_top(lut, atm, r_s, mu_after(r, mu, s, r_s));
    const glm::dvec3 exact = glm::exp(-depth_to_top(s));
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(T[c] / exact[c] - 1.0));
  }
  return worst;
}

}  // namespace skybake::fixtures
