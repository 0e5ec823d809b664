// DeltaS_k of the 4D table: J_k integrated along view rays, the direct
// quadrature and the fast path that shares a row's nodes and (r, mu) taps.
// See scattering_orders.hpp for the equations.
#include "atmosphere/multiple_scattering.hpp"

#include <algorithm>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/kernels/node_slice_reads.hpp"
#include "atmosphere/kernels/sun_frame_reads.hpp"
#include "atmosphere/kernels/row_blend.hpp"
#include "atmosphere/ray_transfer.hpp"
#include "atmosphere/row_texels.hpp"
#include "core/math.hpp"

namespace skybake {

namespace {

// sigma_s at each r texel of the table.
std::vector<glm::dvec3> texel_scattering(const Atmosphere& atm, const ScatteringTexelGrid& texels) {
  std::vector<glm::dvec3> sigma_s(texels.r.size());
  for (size_t z = 0; z < texels.r.size(); ++z)
    sigma_s[z] = sample_medium(atm, texels.r[z] - atm.bottom_radius_m).scattering;
  return sigma_s;
}

// The r texel whose J / sigma_s channel c of r texel z takes: z itself,
// or where sigma_s = 0 (a layer that ends at the top texel, r = Rt
// exactly) and J / sigma_s is undefined, the nearest r texel's.
int scattering_source_texel(const std::vector<glm::dvec3>& sigma_s, int z, int c) {
  const int n = int(sigma_s.size());
  int from = z;
  for (int k = 1; sigma_s[from][c] == 0.0 && k < n; ++k)
    for (int candidate : {z - k, z + k})
      if (candidate >= 0 && candidate < n && sigma_s[candidate][c] > 0.0 &&
          sigma_s[from][c] == 0.0)
        from = candidate;
  return from;
}

// J / sigma_s of every texel (density_per_scattering), each value handed to
// store(texel index, channel, value): a Texture or the padded texels of the
// fast path, without a copy in between.
template <class Store>
void for_each_density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                     const Texture& density, Store&& store) {
  const std::vector<glm::dvec3> sigma_s =
      texel_scattering(atm, scattering_texel_grid(atm, shape));
  // Each r slice on its own (it reads others, writes only itself).
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int c = 0; c < 3; ++c) {
      const int from = scattering_source_texel(sigma_s, z, c);
      for (int y = 0; y < density.height; ++y)
        for (int x = 0; x < density.width; ++x)
          store(density.index(x, y, z) / density.channel_count(), c,
                sigma_s[from][c] > 0.0 ? float(density.texel(x, y, from)[c] / sigma_s[from][c])
                                       : 0.0f);
    }
  });
}

}  // namespace

Texture density_per_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                               const Texture& density) {
  Texture out = density;
  for_each_density_per_scattering(atm, shape, density,
                                  [&](size_t t, int c, float v) { out.data[t * out.channel_count() + c] = v; });
  return out;
}

glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                       const Texture& density_per_sigma_s, double r, double mu,
                                       double mu_s, double nu, bool ray_hits_ground, int nodes) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double d = distance_to_nearest_boundary(rb, rt, r, mu, ray_hits_ground);
  const Texture& radiance = density_per_sigma_s;
  RayTransfer transfer;
  ray_transfer(atm, r, mu, d, nodes, transfer);
  glm::dvec3 sum(0.0);
  for (const TransferNode& q : transfer.nodes) {
    const double mu_i = mu_after(r, mu, q.s, q.r);
    const double mu_s_i = clamp_cosine((r * mu_s + q.s * nu) / q.r);
    const glm::dvec3 sigma_s = sample_medium(atm, q.r - rb).scattering;
    sum += q.weight * sigma_s *
           lookup_scattering_rgb(radiance, shape, atm, q.r, mu_i, mu_s_i, nu, ray_hits_ground);
  }
  return sum;
}

// In single precision, three channels (and a pad) at a time: the table is
// float32 and a texel sums ~51 terms of one sign (relative rounding ~1e-6,
// far below the quadrature's error); the ray's geometry stays in double, the
// mu_s taps of each node are single precision (kernels/node_slice_reads.hpp: within 2.5e-5
// of a texel of the double ones).
Texture bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                                 const Texture& density, int nodes, const BakeContext& ctx) {
  Texture out;
  MultipleScatteringWork work;
  bake_multiple_scattering(atm, shape, density, nodes, ctx, out, work);
  return out;
}

namespace {

// The nodes of row (y, z) that scatter, as MultipleScatteringWork keeps them.
void make_row_nodes(const Atmosphere& atm, const ScatteringShape& shape, const ScatteringParams& p0,
                    int nodes, RayTransfer& transfer,
                    std::vector<MultipleScatteringWork::Node>& out) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const double r = p0.r, mu = p0.mu;
  const bool hits = p0.ray_hits_ground;
  ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, hits), nodes, transfer);
  out.clear();
  for (const TransferNode& q : transfer.nodes) {
    const glm::dvec3 wS = q.weight * sample_medium(atm, q.r - rb).scattering;
    if (wS == glm::dvec3(0.0)) continue;
    const double r_i = q.r, mu_i = mu_after(r, mu, q.s, r_i);
    const glm::dvec2 u_mu_r = scattering_u_mu_r(atm, shape, r_i, mu_i, hits);
    // J / sigma_s at (r_i, mu_i) for every (mu_s, nu) texel: the bilinear
    // blend of four rows of the table, shared by the row's texels.
    const AxisTap tr = axis_tap(u_mu_r.y, shape.r_size), tm = axis_tap(u_mu_r.x, shape.mu_size);
    MultipleScatteringWork::Node n;
    n.s = q.s;
    n.inv_r_i = 1.0 / r_i;
    n.wS = Rgb4{{float(wS.r), float(wS.g), float(wS.b), 0.0f}};
    const int row0 = tr.i0 * shape.mu_size, row1 = tr.i1 * shape.mu_size;
    const int rows[4] = {row0 + tm.i0, row0 + tm.i1, row1 + tm.i0, row1 + tm.i1};
    const float w[4] = {float((1.0 - tr.w) * (1.0 - tm.w)), float((1.0 - tr.w) * tm.w),
                        float(tr.w * (1.0 - tm.w)), float(tr.w * tm.w)};
    std::copy_n(rows, 4, n.rows);
    std::copy_n(w, 4, n.w);
    n.z0 = tr.i0;
    n.z1 = tr.i1;
    n.rw = float(tr.w);
    n.mu_i = mu_i;
    out.push_back(n);
  }
}

bool same_shape(const ScatteringShape& a, const ScatteringShape& b) {
  return a.r_size == b.r_size && a.mu_size == b.mu_size && a.mu_s_size == b.mu_s_size &&
         a.nu_size == b.nu_size && a.mu_s_min == b.mu_s_min;
}

// Every texel row (r, mu) of the table: its ray's nodes (made once, kept in
// `work`), its texels (RowTexels, then row_setup(row_texels)),
// node_reads(row_texels, p0, node, sum, scratch) adding each node's reads
// to the row's sums (scratch: the task's own W texels, for a node's blend),
// then the sums into `out`.
template <class RowSetup, class NodeReads>
void for_each_row(const Atmosphere& atm, const ScatteringShape& shape, int nodes,
                  const BakeContext& ctx, Texture& out, MultipleScatteringWork& work,
                  RowSetup&& row_setup, NodeReads&& node_reads) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  const int W = shape.texture_width();
  reuse_rgb_table(out, shape);
  const int rows = shape.r_size * shape.mu_size;
  const bool make_nodes = work.nodes_per_ray != nodes || !same_shape(work.shape, shape) ||
                          work.nodes.size() != size_t(rows);
  if (make_nodes) work.nodes.assign(size_t(rows), {});
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RayTransfer transfer;
    RowTexels row_texels(shape);
    std::vector<Rgb4> sum(row_texels.mu_s.size()), scratch(size_t(shape.texture_width()));
    for (int row = range.begin(); row != range.end(); ++row) {
      const int z = row / shape.mu_size, y = row % shape.mu_size;
      const ScatteringParams p0 = texels.params(0, y, z);
      row_texels.make(texels, shape, p0.mu);
      row_setup(row_texels);
      if (make_nodes) make_row_nodes(atm, shape, p0, nodes, transfer, work.nodes[size_t(row)]);
      std::fill(sum.begin(), sum.begin() + row_texels.end, Rgb4{});
      for (const MultipleScatteringWork::Node& a : work.nodes[size_t(row)])
        node_reads(row_texels, p0, a, sum.data(), scratch.data());
      float* texels_out = out.texel(0, y, z);
      for (int x = 0; x < W; ++x)
        for (int c = 0; c < 3; ++c) texels_out[3 * x + c] = sum[row_texels.slot[x]].v[c];
      progress.tick();
    }
  });
  if (make_nodes) {
    work.nodes_per_ray = nodes;
    work.shape = shape;
  }
}

}  // namespace

void bake_multiple_scattering(const Atmosphere& atm, const ScatteringShape& shape,
                              const Texture& density, int nodes, const BakeContext& ctx,
                              Texture& out, MultipleScatteringWork& work) {
  std::vector<Rgb4>& radiance = work.radiance;
  const SunCosineTapsFloat mu_s_taps(MuSAxis(atm, shape).constants());
  radiance.resize(density.texel_count());  // every texel's R, G, B written below, pads 0
  for_each_density_per_scattering(atm, shape, density,
                                  [&](size_t t, int c, float v) { radiance[t].v[c] = v; });
  const int W = shape.texture_width();
  // The scratch holds the node's blend of four rows of J / sigma_s.
  for_each_row(atm, shape, nodes, ctx, out, work, [](RowTexels&) {},
               [&](RowTexels& row_texels, const ScatteringParams& p0,
                   const MultipleScatteringWork::Node& a, Rgb4* sum, Rgb4* slice) {
                 const Rgb4* rows4[4];
                 for (int i = 0; i < 4; ++i) rows4[i] = &radiance[size_t(a.rows[i]) * W];
                 blend_rows(rows4, a.w, W, slice);
                 add_node_slice_reads(row_texels.node(p0.r, a.s, a.inv_r_i), mu_s_taps, slice,
                                      a.wS, row_texels.end, sum);
               });
}

// ---- Over the density in the sun's frame ----

void divide_by_scattering(const Atmosphere& atm, SunFrameDensity& J) {
  const ScatteringShape& shape = J.shape;
  const std::vector<glm::dvec3> sigma_s = texel_scattering(atm, scattering_texel_grid(atm, shape));
  const size_t stride = J.r_stride();
  // Where sigma_s > 0 first; then the texels that take another's.
  tbb::parallel_for(0, shape.r_size, [&](int z) {
    for (int c = 0; c < 3; ++c) {
      if (sigma_s[z][c] == 0.0) continue;
      const float inv = float(1.0 / sigma_s[z][c]);
      for (size_t t = z * stride; t < (z + 1) * stride; ++t) J.texels[t].v[c] *= inv;
    }
  });
  for (int z = 0; z < shape.r_size; ++z)
    for (int c = 0; c < 3; ++c) {
      if (sigma_s[z][c] != 0.0) continue;
      const int from = scattering_source_texel(sigma_s, z, c);
      for (size_t t = 0; t < stride; ++t)
        J.texels[z * stride + t].v[c] =
            sigma_s[from][c] > 0.0 ? J.texels[from * stride + t].v[c] : 0.0f;
    }
}

glm::dvec3 compute_multiple_scattering(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                                       double r, double mu, double mu_s, double nu,
                                       bool ray_hits_ground, int nodes) {
  const ScatteringShape& shape = J_per_sigma_s.shape;
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const MuSAxis mu_s_axis(atm, shape);
  RayTransfer transfer;
  ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, ray_hits_ground), nodes,
               transfer);
  glm::dvec3 sum(0.0);
  for (const TransferNode& q : transfer.nodes) {
    const double mu_i = mu_after(r, mu, q.s, q.r);
    const double mu_s_i = clamp_cosine((r * mu_s + q.s * nu) / q.r);
    const AxisTap tr =
        axis_tap(scattering_u_mu_r(atm, shape, q.r, mu_i, ray_hits_ground).y, shape.r_size);
    sum += q.weight * sample_medium(atm, q.r - rb).scattering *
           lookup_sun_frame_density(J_per_sigma_s, mu_s_axis, tr, mu_i, mu_s_i, nu);
  }
  return sum;
}

void bake_multiple_scattering(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                              int nodes, const BakeContext& ctx, Texture& out,
                              MultipleScatteringWork& work) {
  const SunFrameDensity& J = J_per_sigma_s;
  const SunCosineTapsFloat mu_s_taps(MuSAxis(atm, J.shape).constants());
  const size_t stride = J.r_stride();
  for_each_row(atm, J.shape, nodes, ctx, out, work,
               [&](RowTexels& row_texels) { row_texels.make_sun_frame_nu(J.nu, J.shape.mu_s_size); },
               [&](RowTexels& row_texels, const ScatteringParams& p0,
                   const MultipleScatteringWork::Node& a, Rgb4* sum, Rgb4*) {
                 add_sun_frame_reads(
                     row_texels.sun_frame_node(p0.r, a.s, a.inv_r_i, a.mu_i, J.phi_size),
                     mu_s_taps, &J.texels[a.z0 * stride], &J.texels[a.z1 * stride], a.rw, a.wS,
                     row_texels.end, sum);
               });
}

}  // namespace skybake
