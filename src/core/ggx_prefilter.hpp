// The GGX-prefiltered mip chain of a cube map for specular image-based
// lighting: the split-sum approximation's first factor with N = V = R
// (Karis 2013, "Real Shading in Unreal Engine 4"), the GGX distribution of
// Walter et al. 2007, by importance sampling with filtered importance
// sampling (Krivanek & Colbert 2008, GPU Gems 3 ch. 20). docs/runtime.md
// "Sky environment" has the roughness of each level.
//
// Level m of a chain of L levels (face n0 >> m texels) holds, for the
// direction N of each texel,
//   P_m(N) = int L(l) D(h) (N.l) dl / int D(h) (N.l) dl  over N.l > 0,
// h = normalize(N + l), D the GGX distribution of alpha = r_m^2, r_m =
// m / (L - 1) the level's perceptual roughness (level 0 is the mirror, r 0).
// The integral is estimated with `samples` half vectors h drawn from D on
// the Hammersley set (the same set for every texel, so the result is
// deterministic); a sample of pdf p(l) = D / 4 reads the box-filtered level
// of level 0 whose texels have about its solid angle 1 / (samples p):
// lod = max(0, log2(Omega_s / Omega_texel) / 2), trilinear between levels
// (without the +1 of Krivanek & Colbert's bias, which on a 32-texel sky cube
// blurred 3x further from the brute-force convolution: 2.4% RMS at
// roughness 1 against 0.7%; tests/core/ggx_prefilter_test.cpp).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/texture.hpp"

namespace skybake {

// r_m = m / (levels - 1) (0 for a one-level chain).
double ggx_level_roughness(int level, int levels);

// The GGX distribution D(cos theta_h) for roughness alpha (Walter et al. 2007 eq. 33).
double ggx_distribution(double cos_h, double alpha);

// Levels 1 .. levels - 1 of the prefiltered chain of the cube texture
// `level0` (core/cube_map.hpp: square faces, 6 layers per cube; channels kept,
// channels 0-2 filtered, any others copied from the box filter). Parallel,
// independent of the thread count.
// With z_mirror, level 0 symmetric about z = 0 (core/cube_map.hpp
// fill_z_mirrors): half of each level is filtered and the rest mirrored.
constexpr int kGgxDefaultSamples = 512;
std::vector<Texture> ggx_prefilter_levels(const Texture& level0, int levels,
                                          int samples = kGgxDefaultSamples,
                                          bool z_mirror = false);

// One sample of the estimate, the same for every texel of a level: the half
// vector in the texel's tangent frame, and the level of the box chain its
// solid angle reads (the lod above).
struct GgxSample {
  double cos_h = 1, sin_h = 0, cos_phi = 1, sin_phi = 0, lod = 0;
};
// The set for roughness alpha (= r^2), `samples` half vectors, level 0 of
// `face` texels a side.
std::vector<GgxSample> ggx_samples(double alpha, int samples, int face);

// One texel's value: P(N) for cube `cube` of a box chain (level 0 first, as
// build_mip_chain gives it), from a set of ggx_samples for level 0's face.
glm::dvec3 ggx_prefiltered_radiance(const std::vector<Texture>& box_chain, int cube, glm::dvec3 n,
                                    const std::vector<GgxSample>& samples);

}  // namespace skybake
