// The gathering LUT of Bodare & Sandberg 2014 (sec. 4.7.3): the
// light of one scattering order arriving at a point from all directions,
//   G_k(h, mu_s) = int_{4 pi} L_k(h, omega) d omega,
// parameterized by altitude and sun only, so that the next order of the
// azimuth-free table (scattering3d_lut.hpp) reads one value per ray node
// instead of integrating over the sphere there (Bodare & Sandberg Algorithms
// 3 and 7).
//
// Shape: width height_size x height sun_size of the 3D table (default
// 32 x 32), the same h and mu_s mappings, RGB float32, radiance x sr.
// L_k(h, omega) = p_R(nu) S_R,k(h, mu, mu_s) + p_M(nu) S_M,k(h, mu, mu_s) from the
// phase-free tables of order k, plus, along rays that meet the ground at g,
// T(x, g) albedo / pi E_{k-1}(mu_s at g) (E_0 direct sunlight).
// Quadrature: the sphere is cut into `bands` zenith bands; the tables are
// azimuth-free, so in the sky part only the phase depends on azimuth, and
//   G = sum_c sum_bands S_c(h, mu_band, mu_s) W_c(band, mu_s),
//   W_c = int over the band of p_c(nu) d omega,
// integrated finely once per sun (8 sub-bands x 256 azimuths: Mie's forward
// peak, 0.2 rad wide for g = 0.8, is resolved) and normalized so that
// sum_bands W_c = 1 = int p_c: a constant table gathers exactly S_R + S_M.
// The ground term depends on azimuth through the sun's cosine at g and is
// summed over 2 bands azimuths per band.
// Each pass also returns the ground irradiance of order k, E_k(mu_s) = int
// over the upper hemisphere of L_k cos(theta) d omega at h = 0 (weights
// int p_c cos(theta) d omega, same fine quadrature, not normalized), on the
// sun texels: it lights the ground for the next order.
// The product `gathering_sum` is sum_{k=1}^{N-1} G_k: what orders 2..N
// re-scatter, used to add multiple scattering to aerial perspective (Bodare
// & Sandberg sec. 6.4): p_c(nu) int sigma_s,c T G_sum ds.
// Reads: the transmittance LUT (ground term).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

// One order of the 3D table: phase-free S_R,k and S_M,k (RGB, 3D shape).
struct Scattering3dOrder {
  const Texture* rayleigh = nullptr;
  const Texture* mie = nullptr;
  const ScatteringPhases* phases = nullptr;
};

// Irradiance of order k - 1 on the ground: direct sunlight, or one value
// per sun texel (linear between them along u_s, clamped at the ends).
struct GroundLight3d {
  const std::vector<glm::dvec3>* per_sun_texel = nullptr;  // nullptr: direct sunlight
  glm::dvec3 irradiance(const Atmosphere& atm, const Texture& transmittance_lut, double mu_s) const;
};

struct Gathering {
  glm::dvec3 gathered{0.0};  // G_k
  glm::dvec3 ground{0.0};    // E_k, cosine weighted over the upper hemisphere
};

// The phase weights of the opening comment for one sun: per band, for the
// Rayleigh and the Mie group, over the sphere (normalized) and cosine
// weighted over the upper hemisphere.
struct GatheringWeights {
  std::vector<double> sphere_rayleigh, sphere_mie;
  std::vector<double> cosine_rayleigh, cosine_mie;
};
GatheringWeights gathering_weights(const ScatteringPhases& phases, double mu_s, int bands);

// G_k (and E_k) at altitude h for a sun at mu_s; bands even. Thread-safe.
Gathering compute_gathering(const Atmosphere& atm, const Texture& transmittance_lut,
                            const Scattering3dShape& shape, const Scattering3dOrder& order,
                            const GroundLight3d& ground, double h, double mu_s, int bands);

struct GatheringPass {
  Texture gathering;                          // height_size x sun_size, RGB: G_k
  std::vector<glm::dvec3> ground_irradiance;  // E_k at h = 0, per sun texel
};
// Every texel (h, mu_s) of the 3D shape; texels in parallel (tbb).
GatheringPass bake_gathering(const Atmosphere& atm, const Texture& transmittance_lut,
                             const Scattering3dShape& shape, const Scattering3dOrder& order,
                             const GroundLight3d& ground, int bands, const BakeContext& ctx);

// Bilinear read with clamp to edge.
glm::dvec3 lookup_gathering(const Texture& gathering, const Atmosphere& atm, double h, double mu_s);

}  // namespace skybake
