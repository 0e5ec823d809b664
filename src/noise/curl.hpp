// Curl noise (Bridson, Hourihan & Nordenstam 2007, "Curl-Noise for Procedural
// Fluid Flow"): the curl of a smooth potential is divergence free, which is
// what lets Schneider use it to fake turbulent flow when distorting the detail
// noise lookups (GPU Pro 7 sec. 4.3.4; SIGGRAPH 2015 slides: 128^2, 3 channels).
//
// The potentials are periodic Perlin fBms (fbm.hpp), so the curl tiles with
// the same period. Derivatives are analytic (perlin3_sample), not finite
// differences: the result is the exact curl of a C2 potential, so its
// divergence vanishes up to float rounding.
//   2D: v = (d psi / dy, -d psi / dx) of one scalar potential psi.
//   3D: v = curl (psi1, psi2, psi3) of three decorrelated potentials, seeded
//       stream_seed(seed, 0..2) (lattice_hash.hpp).
// Units: p in cells of the base period; v per cell of the base period. Each
// octave's derivative is scaled by its frequency, so with gain 0.5 every
// octave contributes equally to v.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "noise/perlin.hpp"

namespace skybake {

glm::vec2 curl2(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed, float gain = 0.5f);
glm::vec3 curl3(glm::vec3 p, glm::ivec3 period, int octaves, uint32_t seed, float gain = 0.5f);

// The potentials themselves (value and gradient), for tests and previews.
NoiseSample2 curl2_potential(glm::vec2 p, glm::ivec2 period, int octaves, uint32_t seed,
                             float gain = 0.5f);
NoiseSample3 curl3_potential(int component, glm::vec3 p, glm::ivec3 period, int octaves,
                             uint32_t seed, float gain = 0.5f);

}  // namespace skybake
