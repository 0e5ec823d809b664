// The atmosphere's participating media: a spherical planet of radius
// bottom_radius_m, an atmosphere shell up to top_radius_m, and a list of
// components (Rayleigh, Mie, ozone, ...) whose coefficients scale with a
// density profile of the altitude h only.
//
// Density profile (Bruneton 2017 DensityProfileLayer, generalised to any
// number of layers): layers are stacked from the ground up, layer i covering
// [sum of the widths below it, + width_m); the last layer extends to the top.
//   density(h) = clamp(exp_term * exp(exp_scale_per_m * h) + linear_term_per_m * h
//                      + constant_term, 0, 1)
// An exponential of scale height H is {exp_term 1, exp_scale -1/H}; the ozone
// tent of Hillaire 2020 is two linear layers; a uniform slab is a constant.
// h is the altitude above the ground in metres in every layer (not relative to
// the layer's bottom), as in Bruneton's model.
#pragma once

#include <algorithm>

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace skybake {

struct DensityLayer {
  double width_m = 0.0;            // thickness of this layer; ignored for the last layer
  double exp_term = 0.0;           // a of a exp(b h)
  double exp_scale_per_m = 0.0;    // b of a exp(b h), 1/m
  double linear_term_per_m = 0.0;  // c of c h, 1/m
  double constant_term = 0.0;      // d
};

struct DensityProfile {
  std::vector<DensityLayer> layers;  // empty = density 0 everywhere
};

// Profile density at altitude h (metres), in [0, 1].
double density_at(const DensityProfile& profile, double altitude_m);

// density_at's two halves, for callers that take the exponentials in blocks
// (medium_block.hpp): the layer holding altitude h (the first whose top lies
// above it, else the last; the profile must have a layer), and that layer's
// clamped density at h given exponential = exp(l.exp_scale_per_m h) (read
// only where l.exp_term != 0).
// Inline: the linear profiles' block loop (medium_block.cpp) calls it per altitude.
inline const DensityLayer& layer_at(const DensityProfile& profile, double altitude_m) {
  double layer_bottom = 0.0;
  size_t k = 0;
  for (; k + 1 < profile.layers.size(); ++k) {
    if (altitude_m < layer_bottom + profile.layers[k].width_m) break;
    layer_bottom += profile.layers[k].width_m;
  }
  return profile.layers[k];
}
inline double layer_density(const DensityLayer& l, double altitude_m, double exponential) {
  const double e = l.exp_term == 0.0 ? 0.0 : l.exp_term * exponential;
  return std::clamp(e + l.linear_term_per_m * altitude_m + l.constant_term, 0.0, 1.0);
}

// Helpers that build the usual profiles.
DensityProfile exponential_profile(double scale_height_m);
// 0 below bottom, rising linearly to 1 at center, back to 0 at top (ozone).
DensityProfile tent_profile(double bottom_m, double center_m, double top_m);
// 1 between bottom and top, 0 elsewhere.
DensityProfile uniform_profile(double bottom_m, double top_m);

enum class PhaseKind {
  none,               // absorbs only (ozone)
  rayleigh,           // 3 (1 + c^2) / (16 pi)
  cornette_shanks,    // Mie, Hillaire 2020 sec. 4 (docs/reference.md)
  henyey_greenstein,  // Mie option
};

struct MediumComponent {
  std::string name;                  // "rayleigh", "mie", "ozone", ...
  glm::dvec3 scattering_per_m{0.0};  // sigma_s at density 1, RGB = 680/550/440 nm
  glm::dvec3 absorption_per_m{0.0};  // sigma_a at density 1
  DensityProfile density;
  PhaseKind phase = PhaseKind::none;
  double g = 0.0;  // asymmetry for CS / HG phases
};

struct Atmosphere {
  double bottom_radius_m = 6360e3;  // ground radius Rb
  double top_radius_m = 6460e3;     // top of the atmosphere Rt
  glm::dvec3 ground_albedo{0.3};    // diffuse, RGB
  glm::dvec3 sun_illuminance{1.0};  // at the top of the atmosphere, RGB (relative units)
  double sun_angular_radius_rad = 0.004675;
  std::vector<MediumComponent> components;  // zero or absent components are dropped at load
};

// Media coefficients at one point, summed over components.
struct MediumSample {
  glm::dvec3 scattering{0.0};  // sigma_s, 1/m
  glm::dvec3 extinction{0.0};  // sigma_t = sigma_s + sigma_a, 1/m
};

MediumSample sample_medium(const Atmosphere& atm, double altitude_m);

// sigma_t only (transmittance does not need the split).
glm::dvec3 extinction_at(const Atmosphere& atm, double altitude_m);

}  // namespace skybake
