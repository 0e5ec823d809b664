// Single scattering and the shared machinery of the 4D scattering table. See
// the header for the parameterization (Bruneton 2017 functions.glsl).
#include "atmosphere/scattering_lut.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/kernels/sun_taps.hpp"
#include "atmosphere/phase.hpp"
#include "core/error.hpp"

namespace skybake {

namespace {

// sqrt(Rt^2 - Rb^2), factored to keep the digits of a thin shell.
double horizon_distance(const Atmosphere& atm) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  return safe_sqrt((rt - rb) * (rt + rb));
}

// Distance from the ground (r = Rb) to the top along mu_s, through the
// planet when mu_s < 0 (the mu_s axis measures the sun, not a visible ray).
double ground_distance_to_top(const Atmosphere& atm, double mu_s) {
  const double rb = atm.bottom_radius_m, H = horizon_distance(atm);
  return -rb * mu_s + safe_sqrt(rb * rb * mu_s * mu_s + H * H);
}

// a(mu_s) of the header: 0 at the zenith, 1 at the horizon, > 1 below it.
double mu_s_parameter(const Atmosphere& atm, double mu_s) {
  const double d_min = atm.top_radius_m - atm.bottom_radius_m, d_max = horizon_distance(atm);
  return (ground_distance_to_top(atm, mu_s) - d_min) / (d_max - d_min);
}

// Reads `count` channels from `first` at the 16 taps.
void read_channels(const Texture& table, const ScatteringShape& shape, const ScatteringTaps& t,
                   int first, int count, double* out) {
  for (int c = 0; c < count; ++c) out[c] = 0.0;
  const int r_i[2] = {t.r.i0, t.r.i1}, mu_i[2] = {t.mu.i0, t.mu.i1};
  const int mus_i[2] = {t.mu_s.i0, t.mu_s.i1}, nu_i[2] = {t.nu.i0, t.nu.i1};
  const double r_w[2] = {1.0 - t.r.w, t.r.w}, mu_w[2] = {1.0 - t.mu.w, t.mu.w};
  const double mus_w[2] = {1.0 - t.mu_s.w, t.mu_s.w}, nu_w[2] = {1.0 - t.nu.w, t.nu.w};
  for (int a = 0; a < 2; ++a) {
    if (r_w[a] == 0.0) continue;
    for (int b = 0; b < 2; ++b) {
      if (mu_w[b] == 0.0) continue;
      for (int n = 0; n < 2; ++n) {
        if (nu_w[n] == 0.0) continue;
        for (int m = 0; m < 2; ++m) {
          const double w = r_w[a] * mu_w[b] * nu_w[n] * mus_w[m];
          if (w == 0.0) continue;
          const float* texel = table.texel(nu_i[n] * shape.mu_s_size + mus_i[m], mu_i[b], r_i[a]);
          for (int c = 0; c < count; ++c) out[c] += w * texel[first + c];
        }
      }
    }
  }
}

}  // namespace

// ---- Shape ----

void check_scattering_shape(const ScatteringShape& s) {
  if (s.r_size < 2 || s.mu_size < 4 || s.mu_size % 2 != 0 || s.mu_s_size < 2 || s.nu_size < 2)
    throw Error(fmt::format(
        "scattering table: expected r >= 2, mu even >= 4, mu_s >= 2, nu >= 2 texels, got "
        "{} x {} x {} x {}",
        s.r_size, s.mu_size, s.mu_s_size, s.nu_size));
  if (!(s.mu_s_min > -1.0 && s.mu_s_min <= 0.0))
    throw Error(fmt::format("scattering table: expected mu_s_min in (-1, 0], got {}", s.mu_s_min));
}

void reuse_rgb_table(Texture& table, const ScatteringShape& shape) {
  if (table.width == shape.texture_width() && table.height == shape.mu_size &&
      table.depth == shape.r_size && table.layers == 1 &&
      table.channels == std::vector<std::string>{"R", "G", "B"})
    return;
  table = Texture(shape.texture_width(), shape.mu_size, shape.r_size, 1, {"R", "G", "B"});
}

void set_scattering_shape_metadata(Metadata& meta, const ScatteringShape& s) {
  set_meta(meta, "r_size", s.r_size);
  set_meta(meta, "mu_size", s.mu_size);
  set_meta(meta, "mu_s_size", s.mu_s_size);
  set_meta(meta, "nu_size", s.nu_size);
  set_meta(meta, "mu_s_min", s.mu_s_min);
}

ScatteringShape scattering_shape_from_metadata(const Metadata& meta) {
  ScatteringShape s;
  s.r_size = meta_int(meta, "r_size");
  s.mu_size = meta_int(meta, "mu_size");
  s.mu_s_size = meta_int(meta, "mu_s_size");
  s.nu_size = meta_int(meta, "nu_size");
  s.mu_s_min = meta_double(meta, "mu_s_min");
  return s;
}

// ---- Mapping ----

glm::dvec2 scattering_u_mu_r(const Atmosphere& atm, const ScatteringShape& shape, double r,
                             double mu, bool ray_hits_ground) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m, H = horizon_distance(atm);
  r = std::clamp(r, rb, rt);
  mu = clamp_cosine(mu);
  const double rho = safe_sqrt((r - rb) * (r + rb));
  const double u_r = texel_coord_from_unit(rho / H, shape.r_size);

  // Discriminant of the ray / ground intersection, r^2 mu^2 - r^2 + Rb^2.
  const double r_mu = r * mu, discriminant = r_mu * r_mu - rho * rho;
  const int half = shape.mu_size / 2;
  double u_mu;
  if (ray_hits_ground) {
    const double d = -r_mu - safe_sqrt(discriminant), d_min = r - rb, d_max = rho;
    const double x = d_max == d_min ? 0.0 : (d - d_min) / (d_max - d_min);
    u_mu = 0.5 - 0.5 * texel_coord_from_unit(std::clamp(x, 0.0, 1.0), half);
  } else {
    const double d = -r_mu + safe_sqrt(discriminant + H * H), d_min = rt - r, d_max = rho + H;
    const double x = (d - d_min) / (d_max - d_min);
    u_mu = 0.5 + 0.5 * texel_coord_from_unit(std::clamp(x, 0.0, 1.0), half);
  }
  return {u_mu, u_r};
}

glm::dvec4 scattering_uvwz_from_r_mu_mu_s_nu(const Atmosphere& atm, const ScatteringShape& shape,
                                             double r, double mu, double mu_s, double nu,
                                             bool ray_hits_ground) {
  const glm::dvec2 u_mu_r = scattering_u_mu_r(atm, shape, r, mu, ray_hits_ground);
  const double u_mu_s = MuSAxis(atm, shape).u(mu_s);
  const double u_nu = 0.5 * (clamp_cosine(nu) + 1.0);
  return {u_nu, u_mu_s, u_mu_r.x, u_mu_r.y};
}

ScatteringParams r_mu_mu_s_nu_from_scattering_uvwz(const Atmosphere& atm,
                                                   const ScatteringShape& shape, glm::dvec4 uvwz) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m, H = horizon_distance(atm);
  ScatteringParams p;
  const double rho = H * std::clamp(unit_from_texel_coord(uvwz.w, shape.r_size), 0.0, 1.0);
  p.r = std::clamp(std::sqrt(rho * rho + rb * rb), rb, rt);

  const int half = shape.mu_size / 2;
  if (uvwz.z < 0.5) {
    // Ground half: the distance d to the ground, from d_min (straight down)
    // to d_max (the horizon); law of cosines Rb^2 = r^2 + d^2 + 2 r d mu.
    const double d_min = p.r - rb, d_max = rho;
    const double x = std::clamp(unit_from_texel_coord(1.0 - 2.0 * uvwz.z, half), 0.0, 1.0);
    const double d = d_min + x * (d_max - d_min);
    p.mu = d == 0.0 ? -1.0 : clamp_cosine(-(rho * rho + d * d) / (2.0 * p.r * d));
    p.ray_hits_ground = true;
  } else {
    // Sky half: the distance to the top, Rt^2 = r^2 + d^2 + 2 r d mu.
    const double d_min = rt - p.r, d_max = rho + H;
    const double x = std::clamp(unit_from_texel_coord(2.0 * uvwz.z - 1.0, half), 0.0, 1.0);
    const double d = d_min + x * (d_max - d_min);
    p.mu = d == 0.0 ? 1.0 : clamp_cosine(((rt - p.r) * (rt + p.r) - d * d) / (2.0 * p.r * d));
    p.ray_hits_ground = false;
  }

  const double x_mu_s = std::clamp(unit_from_texel_coord(uvwz.y, shape.mu_s_size), 0.0, 1.0);
  const double d_min = rt - rb, d_max = H;
  const double A = mu_s_parameter(atm, shape.mu_s_min);
  const double a = (A - x_mu_s * A) / (1.0 + x_mu_s * A);
  const double d = d_min + std::min(a, A) * (d_max - d_min);
  p.mu_s = d == 0.0 ? 1.0 : clamp_cosine((H * H - d * d) / (2.0 * rb * d));

  p.nu = clamp_cosine(2.0 * uvwz.x - 1.0);
  return p;
}

ScatteringParams scattering_texel_params(const Atmosphere& atm, const ScatteringShape& shape, int x,
                                         int y, int z) {
  const int nu_index = x / shape.mu_s_size, mu_s_index = x % shape.mu_s_size;
  const glm::dvec4 uvwz(double(nu_index) / (shape.nu_size - 1),
                        texel_center(mu_s_index, shape.mu_s_size), texel_center(y, shape.mu_size),
                        texel_center(z, shape.r_size));
  ScatteringParams p = r_mu_mu_s_nu_from_scattering_uvwz(atm, shape, uvwz);
  // nu = cos of the angle between view and sun, both at fixed zenith angles.
  const double spread = std::sqrt((1.0 - p.mu * p.mu) * (1.0 - p.mu_s * p.mu_s));
  p.nu = std::clamp(p.nu, p.mu * p.mu_s - spread, p.mu * p.mu_s + spread);
  return p;
}

MuSAxis::MuSAxis(const Atmosphere& atm, const ScatteringShape& shape)
    : rb_(atm.bottom_radius_m),
      rb2_(rb_ * rb_),
      H2_(horizon_distance(atm) * horizon_distance(atm)),
      d_min_(atm.top_radius_m - atm.bottom_radius_m),
      inv_span_(1.0 / (horizon_distance(atm) - d_min_)),
      inv_A_(1.0 / mu_s_parameter(atm, shape.mu_s_min)),
      mu_s_min_(shape.mu_s_min),
      size_(shape.mu_s_size) {}

ScatteringParams ScatteringTexelGrid::params(int x, int y, int z) const {
  ScatteringParams p;
  const size_t row = size_t(z) * shape.mu_size + y;
  p.r = r[z];
  p.mu = mu[row];
  p.ray_hits_ground = ray_hits_ground[row] != 0;
  p.mu_s = mu_s[x % shape.mu_s_size];
  const double spread = ScatteringTexelGrid::spread(p.mu, p.mu_s);
  p.nu = std::clamp(nu[x / shape.mu_s_size], p.mu * p.mu_s - spread, p.mu * p.mu_s + spread);
  return p;
}

ScatteringTexelGrid scattering_texel_grid(const Atmosphere& atm, const ScatteringShape& shape) {
  check_scattering_shape(shape);
  ScatteringTexelGrid g;
  g.shape = shape;
  g.r.resize(shape.r_size);
  g.mu.resize(size_t(shape.r_size) * shape.mu_size);
  g.ray_hits_ground.resize(g.mu.size());
  for (int z = 0; z < shape.r_size; ++z)
    for (int y = 0; y < shape.mu_size; ++y) {
      const ScatteringParams p = scattering_texel_params(atm, shape, 0, y, z);
      g.r[z] = p.r;
      g.mu[size_t(z) * shape.mu_size + y] = p.mu;
      g.ray_hits_ground[size_t(z) * shape.mu_size + y] = p.ray_hits_ground;
    }
  for (int l = 0; l < shape.mu_s_size; ++l)
    g.mu_s.push_back(scattering_texel_params(atm, shape, l, 0, 0).mu_s);
  // The unclamped nu of each slice (the clamp depends on mu and mu_s).
  for (int m = 0; m < shape.nu_size; ++m)
    g.nu.push_back(r_mu_mu_s_nu_from_scattering_uvwz(
                       atm, shape, {double(m) / (shape.nu_size - 1), 0.5, 0.75, 0.5})
                       .nu);
  return g;
}

// ---- Media groups ----

ScatteringPhases scattering_phases(const Atmosphere& atm) {
  ScatteringPhases p;
  std::string mie_name;
  for (const MediumComponent& c : atm.components) {
    if (c.scattering_per_m == glm::dvec3(0.0)) continue;
    if (c.phase == PhaseKind::none)
      throw Error(
          fmt::format("scattering: component '{}' scatters but has no phase function", c.name));
    if (c.phase == PhaseKind::rayleigh) {
      p.rayleigh_per_m += c.scattering_per_m;
      p.has_rayleigh = true;
      continue;
    }
    if (p.has_mie && (c.phase != p.mie_phase || c.g != p.mie_g))
      throw Error(fmt::format(
          "scattering: expected one Mie phase for all non-Rayleigh components, got g = {} for "
          "'{}' and g = {} (or another phase kind) for '{}'",
          p.mie_g, mie_name, c.g, c.name));
    p.mie_phase = c.phase;
    p.mie_g = c.g;
    p.mie_per_m += c.scattering_per_m;
    p.has_mie = true;
    mie_name = c.name;
  }
  return p;
}

void scattering_by_group(const Atmosphere& atm, double altitude_m, glm::dvec3& rayleigh,
                         glm::dvec3& mie) {
  rayleigh = mie = glm::dvec3(0.0);
  for (const MediumComponent& c : atm.components) {
    if (c.phase == PhaseKind::none || c.scattering_per_m == glm::dvec3(0.0)) continue;
    const double density = density_at(c.density, altitude_m);
    if (density == 0.0) continue;
    (c.phase == PhaseKind::rayleigh ? rayleigh : mie) += density * c.scattering_per_m;
  }
}

// ---- Ray quadrature ----

void ray_segments(double r, double mu, double d, int nodes, std::vector<RaySegment>& out) {
  out.clear();
  if (!(d > 0.0)) return;
  struct Piece {
    double a, b;
    bool dense_at_b;  // the lowest altitude is at b
  };
  Piece pieces[2];
  int count = 0;
  const double perigee = -r * mu;
  if (perigee > 0.0 && perigee < d) {
    pieces[count++] = {0.0, perigee, true};
    pieces[count++] = {perigee, d, false};
  } else {
    pieces[count++] = {0.0, d, mu < 0.0};
  }
  const int segments = std::max(1, (nodes + 2) / 3);
  int n[2] = {segments, 0};
  if (count == 2) {
    n[0] = std::clamp(int(std::lround(segments * (perigee / d))), 1, std::max(1, segments - 1));
    n[1] = std::max(1, segments - n[0]);
  }
  for (int p = 0; p < count; ++p) {
    const Piece& piece = pieces[p];
    const double length = piece.b - piece.a;
    const size_t first = out.size();
    for (int k = 0; k < n[p]; ++k) {
      // Distances from the dense end: [L t0^2, L t1^2].
      const double t0 = double(k) / n[p], t1 = double(k + 1) / n[p];
      const double g0 = length * t0 * t0, g1 = length * t1 * t1;
      out.push_back(piece.dense_at_b ? RaySegment{piece.b - g1, piece.b - g0}
                                     : RaySegment{piece.a + g0, piece.a + g1});
    }
    if (piece.dense_at_b) std::reverse(out.begin() + first, out.end());
  }
}

void ray_quadrature(double r, double mu, double d, int nodes, std::vector<RayNode>& out) {
  out.clear();
  std::vector<RaySegment> segments;
  ray_segments(r, mu, d, nodes, segments);
  for (const RaySegment& seg : segments) {
    const double mid = 0.5 * (seg.a + seg.b), half = 0.5 * (seg.b - seg.a);
    for (int i = 0; i < 3; ++i)
      out.push_back({mid + half * kGauss3Nodes[i], half * kGauss3Weights[i]});
  }
}

// ---- Transmittance reader ----

void MuSAxis::taps(const double* mu_s, int n, int* i0, double* w) const {
  mu_s_taps(constants(), mu_s, n, i0, w);
}

TransmittanceReader::TransmittanceReader(const Texture& lut, const Atmosphere& atm)
    : lut_(lut),
      rb_(atm.bottom_radius_m),
      rt_(atm.top_radius_m),
      H_(horizon_distance(atm)),
      sun_radius_(atm.sun_angular_radius_rad),
      stride_(lut.channel_count()) {}

TransmittanceReader::Row TransmittanceReader::row(double r) const {
  Row row;
  row.r = std::clamp(r, rb_, rt_);
  const double rho = safe_sqrt((row.r - rb_) * (row.r + rb_));
  row.d_min = rt_ - row.r;
  row.inv_span = 1.0 / (rho + H_ - row.d_min);
  const double v = texel_coord_from_unit(rho / H_, lut_.height);
  const AxisTap tap = axis_tap(v, lut_.height);
  row.row0 = lut_.texel(0, tap.i0);
  row.row1 = lut_.texel(0, tap.i1);
  row.wy = tap.w;
  const double sin_h = rb_ / row.r, cos_h = -safe_sqrt(1.0 - sin_h * sin_h);
  const double half_width = sin_h * sun_radius_;
  row.sun_edge = cos_h - half_width;
  row.inv_sun_width = half_width > 0.0 ? 1.0 / (2.0 * half_width) : 1e300;
  return row;
}

glm::dvec3 TransmittanceReader::between(double r, double mu, double d, bool ray_hits_ground) const {
  const double r_d = std::clamp(radius_after(r, mu, d), rb_, rt_);
  const double mu_d = mu_after(r, mu, d, r_d);
  const glm::dvec3 numerator = ray_hits_ground ? to_top(r_d, -mu_d) : to_top(r, mu);
  const glm::dvec3 denominator = ray_hits_ground ? to_top(r, -mu) : to_top(r_d, mu_d);
  glm::dvec3 T(0.0);
  for (int c = 0; c < 3; ++c)
    T[c] = denominator[c] > 0.0 ? std::min(numerator[c] / denominator[c], 1.0) : 0.0;
  return T;
}

// ---- Single scattering ----

void SingleScatteringRay::prepare(const Atmosphere& atm, const TransmittanceReader& reader,
                                  double r_, double mu, bool ray_hits_ground, int count) {
  r = r_;
  nodes.clear();
  const double d =
      distance_to_nearest_boundary(atm.bottom_radius_m, atm.top_radius_m, r, mu, ray_hits_ground);
  ray_transfer(atm, r, mu, d, count, transfer);
  for (const TransferNode& q : transfer.nodes) {
    if (q.weight == glm::dvec3(0.0)) continue;
    glm::dvec3 sigma_r, sigma_m;
    scattering_by_group(atm, q.r - atm.bottom_radius_m, sigma_r, sigma_m);
    if (sigma_r == glm::dvec3(0.0) && sigma_m == glm::dvec3(0.0)) continue;
    Node n;
    n.s = q.s;
    n.inv_r = 1.0 / q.r;
    n.sun_row = reader.row(q.r);
    n.a_rayleigh = q.weight * sigma_r;
    n.a_mie = q.weight * sigma_m;
    nodes.push_back(n);
  }
}

SingleScattering SingleScatteringRay::at_sun(const TransmittanceReader& reader, double mu_s,
                                             double nu, glm::dvec3 sun) const {
  const double mu_s2[2] = {mu_s, mu_s}, nu2[2] = {nu, nu};
  SingleScattering out[2];
  at_sun2(reader, mu_s2, nu2, sun, out);
  return out[0];
}

void SingleScatteringRay::at_sun2(const TransmittanceReader& reader, const double mu_s[2],
                                  const double nu[2], glm::dvec3 sun,
                                  SingleScattering out[2]) const {
  out[0] = out[1] = SingleScattering{};
  for (const Node& n : nodes) {
    const double mu_s_i[2] = {clamp_cosine((r * mu_s[0] + n.s * nu[0]) * n.inv_r),
                              clamp_cosine((r * mu_s[1] + n.s * nu[1]) * n.inv_r)};
    const glm::dvec3 T_sun[2] = {reader.to_sun(n.sun_row, mu_s_i[0]),
                                 reader.to_sun(n.sun_row, mu_s_i[1])};
    for (int k = 0; k < 2; ++k) {
      out[k].rayleigh += n.a_rayleigh * T_sun[k];
      out[k].mie += n.a_mie * T_sun[k];
    }
  }
  for (int k = 0; k < 2; ++k) {
    out[k].rayleigh *= sun;
    out[k].mie *= sun;
  }
}

void SingleScatteringRay::at_suns(const TransmittanceReader& reader, const double* mu_s,
                                  const double* nu, int n, glm::dvec3 sun, SingleScattering* out,
                                  Scratch& scratch) const {
  scratch.sums.assign(6 * size_t(n), 0.0);
  double* const sums[6] = {&scratch.sums[0],     &scratch.sums[n],     &scratch.sums[2 * n],
                           &scratch.sums[3 * n], &scratch.sums[4 * n], &scratch.sums[5 * n]};
  for (const Node& node : nodes)
    reader.add_sun_products(node.sun_row, NodeSuns{mu_s, nu, r, node.s, node.inv_r}, n,
                            node.a_rayleigh, node.a_mie, sums, scratch.taps);
  for (int k = 0; k < n; ++k) {
    out[k].rayleigh = {sums[0][k], sums[1][k], sums[2][k]};
    out[k].mie = {sums[3][k], sums[4][k], sums[5][k]};
  }
  for (int k = 0; k < n; ++k) {
    out[k].rayleigh *= sun;
    out[k].mie *= sun;
  }
}

SingleScattering compute_single_scattering(const Atmosphere& atm, const Texture& transmittance_lut,
                                           double r, double mu, double mu_s, double nu,
                                           bool ray_hits_ground, int nodes) {
  const TransmittanceReader reader(transmittance_lut, atm);
  SingleScatteringRay ray;
  ray.prepare(atm, reader, r, mu, ray_hits_ground, nodes);
  return ray.at_sun(reader, mu_s, nu, atm.sun_illuminance);
}

SingleScatteringTables bake_single_scattering(const Atmosphere& atm,
                                              const Texture& transmittance_lut,
                                              const ScatteringShape& shape, int nodes,
                                              const BakeContext& ctx) {
  check_scattering_shape(shape);
  if (nodes < 2)
    throw Error(fmt::format("single scattering: expected >= 2 ray nodes, got {}", nodes));
  const int W = shape.texture_width();
  SingleScatteringTables out{Texture(W, shape.mu_size, shape.r_size, 1, {"R", "G", "B"}),
                             Texture(W, shape.mu_size, shape.r_size, 1, {"R", "G", "B"})};
  const TransmittanceReader reader(transmittance_lut, atm);
  const ScatteringTexelGrid grid = scattering_texel_grid(atm, shape);
  const int rows = shape.r_size * shape.mu_size;
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    SingleScatteringRay ray;
    SingleScatteringRay::Scratch scratch;
    std::vector<double> mu_s(W), nu(W);
    std::vector<SingleScattering> s(W);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int z = row / shape.mu_size, y = row % shape.mu_size;
      const ScatteringParams p0 = grid.params(0, y, z);
      ray.prepare(atm, reader, p0.r, p0.mu, p0.ray_hits_ground, nodes);
      for (int x = 0; x < W; ++x) {  // every texel (sun) of the row at once
        const ScatteringParams p = grid.params(x, y, z);
        mu_s[x] = p.mu_s;
        nu[x] = p.nu;
      }
      ray.at_suns(reader, mu_s.data(), nu.data(), W, atm.sun_illuminance, s.data(), scratch);
      for (int x = 0; x < W; ++x) {
        float* rayleigh = out.rayleigh.texel(x, y, z);
        float* mie = out.mie.texel(x, y, z);
        for (int c = 0; c < 3; ++c) {
          rayleigh[c] = float(s[x].rayleigh[c]);
          mie[c] = float(s[x].mie[c]);
        }
      }
      progress.tick();
    }
  });
  return out;
}

// ---- Lookups ----

ScatteringTaps scattering_taps(const ScatteringShape& shape, glm::dvec4 uvwz) {
  ScatteringTaps t;
  t.r = axis_tap(uvwz.w, shape.r_size);
  t.mu = axis_tap(uvwz.z, shape.mu_size);
  t.mu_s = axis_tap(uvwz.y, shape.mu_s_size);
  t.nu = nu_slice_tap(uvwz.x, shape.nu_size);
  return t;
}

glm::dvec3 read_scattering(const Texture& table, const ScatteringShape& shape,
                           const ScatteringTaps& taps, int first_channel) {
  double v[3];
  read_channels(table, shape, taps, first_channel, 3, v);
  return {v[0], v[1], v[2]};
}

glm::dvec3 lookup_scattering_rgb(const Texture& table, const ScatteringShape& shape,
                                 const Atmosphere& atm, double r, double mu, double mu_s, double nu,
                                 bool ray_hits_ground) {
  return read_scattering(table, shape,
                         scattering_taps(shape, scattering_uvwz_from_r_mu_mu_s_nu(
                                                    atm, shape, r, mu, mu_s, nu, ray_hits_ground)));
}

glm::dvec3 lookup_scattering(const Texture& scattering, const Texture& single_mie,
                             const ScatteringShape& shape, const Atmosphere& atm, double r,
                             double mu, double mu_s, double nu, bool ray_hits_ground) {
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringTaps taps = scattering_taps(
      shape, scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground));
  const glm::dvec3 rgb = read_scattering(scattering, shape, taps);
  glm::dvec3 mie(0.0);
  if (!single_mie.data.empty()) {
    mie = read_scattering(single_mie, shape, taps);
  } else if (scattering.channel_count() >= 4) {
    double alpha = 0.0;
    read_channels(scattering, shape, taps, 3, 1, &alpha);
    const glm::dvec3 beta_r = phases.rayleigh_per_m, beta_m = phases.mie_per_m;
    if (rgb.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)
      for (int c = 0; c < 3; ++c)
        mie[c] = beta_r[c] > 0.0
                     ? rgb[c] * (alpha / rgb.r) * (beta_r.r / beta_m.r) * (beta_m[c] / beta_r[c])
                     : 0.0;
  }
  return rgb * phases.rayleigh(nu) + mie * phases.mie(nu);
}

glm::dvec3 ScatteringOrder::radiance_at(const Atmosphere& atm, const ScatteringShape& shape,
                                        double r, double mu, double mu_s, double nu,
                                        bool ray_hits_ground) const {
  const ScatteringTaps taps = scattering_taps(
      shape, scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, mu, mu_s, nu, ray_hits_ground));
  if (radiance) return read_scattering(*radiance, shape, taps);
  glm::dvec3 L(0.0);
  if (phases->has_rayleigh) L += phases->rayleigh(nu) * read_scattering(*rayleigh, shape, taps);
  if (phases->has_mie) L += phases->mie(nu) * read_scattering(*mie, shape, taps);
  return L;
}

void TransmittanceReader::add_sun_products(const Row& row, const NodeSuns& suns, int n,
                                           const glm::dvec3& a_rayleigh, const glm::dvec3& a_mie,
                                           double* const sums[6], SunTapScratch& scratch) const {
  skybake::add_sun_products({rt_, lut_.width, stride_}, row, suns, n, a_rayleigh, a_mie, sums,
                            scratch);
}

}  // namespace skybake
