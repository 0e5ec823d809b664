// DeltaS_k of one order of the 4D table: the density J_k integrated along
// view rays (Bruneton 2017 ComputeMultipleScattering; the equation is in
// scattering_orders.hpp).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/kernels/row_blend.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sun_frame_density.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

// J / sigma_s (sigma_s summed over the groups, per channel; 0 where sigma_s
// is): the phase-averaged incident radiance. Along view rays the density is
// interpolated in this form and multiplied by sigma_s at the node, because
// sigma_s falls exponentially between r texels and a linear blend of J
// would overshoot it (by 9 % between 3.5 and 9.8 km on an 8-texel r axis),
// an energy gain per order that dense media amplify.
Texture density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                               const Texture& density);

// DeltaS_k of one ray by the straightforward quadrature (ray_transfer weights,
// sigma_s at the node times lookup_scattering_rgb of `density_per_sigma_s`,
// the table density_per_scattering returns, made once for many rays): the
// reference for bake_multiple_scattering.
glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                       const Texture& density_per_sigma_s, double r, double mu,
                                       double mu_s, double nu, bool ray_hits_ground, int nodes);

// DeltaS_k at every texel (RGB radiance), fast path.
Texture bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                 const Texture& density, int nodes, const BakeContext& ctx);

// What the fast path keeps from order to order: J / sigma_s as padded
// texels (row_blend.hpp), and per texel row the nodes that scatter, each
// with its weight and the four rows of the table it blends. The nodes are
// the same every order (ray_transfer, the medium and the (r, mu) mapping
// are), so the first pass makes them and the next ones read them: about
// 12 MB at default sizes, where making them was 3% of a tolerance bake.
struct MultipleScatteringWork {
  struct Node {
    double s = 0, inv_r_i = 0;  // distance along the ray, 1 / the node's radius
    Rgb4 wS;                    // ray_transfer weight x sigma_s, RGB
    int rows[4] = {0, 0, 0, 0};  // texel rows (z mu_size + y) of the bilinear blend
    float w[4] = {0, 0, 0, 0};   // and their weights
    int z0 = 0, z1 = 0;          // the r texels alone (the reads in the sun's frame)
    float rw = 0;                // and the weight of z1
    double mu_i = 0;             // the view's zenith cosine at the node
  };
  std::vector<Rgb4> radiance;
  std::vector<std::vector<Node>> nodes;  // per texel row
  int nodes_per_ray = 0;                 // what `nodes` was made for (0: not made)
  ScatteringShape shape;
};
// The same into `out` (reuse_rgb_table) with `work` kept from order to
// order, for one atmosphere and shape.
void bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                              const Texture& density, int nodes, const BakeContext& ctx,
                              Texture& out, MultipleScatteringWork& work);

// ---- Over the density in the sun's frame (sun_frame_density.hpp) ----------

// J / sigma_s in place, with density_per_scattering's rule where sigma_s
// is 0.
void divide_by_scattering(const Atmosphere& atm, SunFrameDensity& J);

// DeltaS_k of one ray by the straightforward quadrature over J / sigma_s in
// the sun's frame (lookup_sun_frame_density at each node, in double): the
// reference for the fast path below.
glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                                       double r, double mu, double mu_s, double nu,
                                       bool ray_hits_ground, int nodes);

// DeltaS_k at every texel of the 4D table from J / sigma_s in the sun's
// frame, into `out` with `work` kept from order to order.
void bake_multiple_scattering(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                              int nodes, const BakeContext& ctx, Texture& out,
                              MultipleScatteringWork& work);

}  // namespace skybake
