// The azimuth-free 3D table: mappings, single scattering, orders through the
// gathering LUT. See the header (Hillaire 2016 Appendix A, Bodare & Sandberg
// 2014 ch. 4).
#include "atmosphere/scattering3d_lut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/energy_balance.hpp"
#include "atmosphere/gathering_lut.hpp"
#include "atmosphere/geometric_tail.hpp"
#include "atmosphere/geometry.hpp"
#include "atmosphere/order_progress.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/error.hpp"
#include "core/math.hpp"

namespace skybake {

const double kScattering3dMuSMin = std::tan(-0.74 * 0.75) / std::tan(1.26 * 0.75);

namespace {

const double kSunScale = std::tan(1.26 * 0.75);

// Zenith cosine of the horizon at altitude h, -sqrt(h (2 Rb + h)) / (Rb + h).
double horizon_cosine(const Atmosphere& atm, double h) {
  h = std::max(h, 0.0);
  return -std::sqrt(h * (2.0 * atm.bottom_radius_m + h)) / (atm.bottom_radius_m + h);
}

// Trilinear read of 3 channels from `first`.
glm::dvec3 read3(const Texture& t, const AxisTap& x, const AxisTap& y, const AxisTap& z,
                 int first) {
  glm::dvec3 out(0.0);
  const int xi[2] = {x.i0, x.i1}, yi[2] = {y.i0, y.i1}, zi[2] = {z.i0, z.i1};
  const double xw[2] = {1.0 - x.w, x.w}, yw[2] = {1.0 - y.w, y.w}, zw[2] = {1.0 - z.w, z.w};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c) {
        const double w = xw[c] * yw[b] * zw[a];
        if (w == 0.0) continue;
        const float* texel = t.texel(xi[c], yi[b], zi[a]);
        out += w * glm::dvec3(texel[first], texel[first + 1], texel[first + 2]);
      }
  return out;
}

// u_s(mu_s) tabulated on 4097 cosines in [-1, 1], read linearly: the atan
// of the exact mapping cost more than the rest of the multiple-scattering
// loop. |u''| < 1 on [mu_s_min, 1] (tan/atan of slope <= 1.4), so the table
// is within (2/4096)^2 / 8 = 3e-8 of the mapping: 1e-6 texel.
class SunAxisTable {
 public:
  explicit SunAxisTable(int n) : n_(n), u_(kSize + 1) {
    for (int i = 0; i <= kSize; ++i) u_[i] = scattering3d_u_from_mu_s(-1.0 + 2.0 * i / kSize, n);
  }
  AxisTap tap(double mu_s) const {
    const double t = (std::clamp(mu_s, -1.0, 1.0) + 1.0) * (0.5 * kSize);
    const int i = std::min(int(t), kSize - 1);
    const double w = t - i;
    return axis_tap(u_[i] + (u_[i + 1] - u_[i]) * w, n_);
  }

 private:
  static constexpr int kSize = 4096;
  int n_;
  std::vector<double> u_;
};

// S_c of order k + 1 for every texel from the gathering G_k (header).
void bake_order_from_gathering(const Atmosphere& atm, const Scattering3dShape& shape,
                               const Texture& gathering, int nodes, Texture& rayleigh, Texture& mie,
                               const BakeContext& ctx) {
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m;
  const int rows = shape.height_size * shape.view_size;
  const SunAxisTable sun_axis(gathering.height);
  ProgressCounter progress(ctx, size_t(rows));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    RayTransfer transfer;
    std::vector<glm::dvec3> sum_r(shape.sun_size), sum_m(shape.sun_size);
    std::vector<glm::dvec3> column(gathering.height);  // G at the node's h, per sun texel
    std::vector<double> mu_s(shape.sun_size);
    for (int z = 0; z < shape.sun_size; ++z)
      mu_s[z] = mu_s_from_scattering3d_u(texel_center(z, shape.sun_size), shape.sun_size);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int x = row % shape.height_size, y = row / shape.height_size;
      const Scattering3dParams p = scattering3d_texel_params(atm, shape, x, y, 0);
      const double r = rb + p.h, mu = p.mu;
      ray_transfer(atm, r, mu, distance_to_nearest_boundary(rb, rt, r, mu, p.ray_hits_ground),
                   nodes, transfer);
      std::fill(sum_r.begin(), sum_r.end(), glm::dvec3(0.0));
      std::fill(sum_m.begin(), sum_m.end(), glm::dvec3(0.0));
      for (const TransferNode& q : transfer.nodes) {
        const double r_y = q.r, h_y = r_y - rb;
        glm::dvec3 sigma_r, sigma_m;
        scattering_by_group(atm, h_y, sigma_r, sigma_m);
        if (sigma_r == glm::dvec3(0.0) && sigma_m == glm::dvec3(0.0)) continue;
        const glm::dvec3 wT = q.weight;  // energy conserving (ray_transfer.hpp)
        if (wT == glm::dvec3(0.0)) continue;
        const AxisTap th =
            axis_tap(scattering3d_u_from_h(atm, h_y, gathering.width), gathering.width);
        for (int v = 0; v < gathering.height; ++v) {
          const float* g0 = gathering.texel(th.i0, v);
          const float* g1 = gathering.texel(th.i1, v);
          for (int c = 0; c < 3; ++c) column[v][c] = g0[c] * (1.0 - th.w) + g1[c] * th.w;
        }
        const glm::dvec3 a_r = wT * sigma_r, a_m = wT * sigma_m;
        // Cosine between the zeniths at x and y: the sun's cosine at y,
        // averaged over azimuth, is mu_s times it.
        const double zenith_cos = clamp_cosine((r + q.s * mu) / r_y);
        for (int z = 0; z < shape.sun_size; ++z) {
          const AxisTap ts = sun_axis.tap(mu_s[z] * zenith_cos);
          const glm::dvec3 G = column[ts.i0] * (1.0 - ts.w) + column[ts.i1] * ts.w;
          sum_r[z] += a_r * G;
          sum_m[z] += a_m * G;
        }
      }
      for (int z = 0; z < shape.sun_size; ++z)
        for (int c = 0; c < 3; ++c) {
          rayleigh.at(x, y, z, 0, c) = float(sum_r[z][c]);
          mie.at(x, y, z, 0, c) = float(sum_m[z][c]);
        }
      progress.tick();
    }
  });
}

void set_scattering3d_metadata(Metadata& meta, const Atmosphere& atm, const Scattering3dSpec& spec,
                               const Scattering3dTextures& out, const ScatteringPhases& phases,
                               const std::string& quantity) {
  set_meta(meta, "parameterization", std::string("azimuth_free_3d_scattering"));
  set_meta(meta, "quantity", quantity);
  set_meta(meta, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(meta, "top_radius_m", atm.top_radius_m);
  set_meta(meta, "height_size", spec.height_size);
  set_meta(meta, "view_size", spec.view_size);
  set_meta(meta, "sun_size", spec.sun_size);
  set_meta(meta, "mu_s_min", kScattering3dMuSMin);
  set_meta(meta, "orders", out.orders_used);
  set_meta(meta, "last_residual", out.last_residual);
  set_meta(meta, "tolerance", spec.tolerance);
  set_meta(meta, "geometric_tail",
           geometric_tail_metadata(spec.tolerance > 0.0 && spec.geometric_tail, out.tail_factor));
  set_meta(meta, "azimuth_samples", spec.azimuth_samples);
  set_meta(meta, "gathering_directions", spec.gathering_directions);
  set_meta(meta, "ray_nodes", spec.ray_nodes);
  set_meta(meta, "rayleigh_scattering_per_m", phases.rayleigh_per_m);
  set_meta(meta, "mie_scattering_per_m", phases.mie_per_m);
  set_meta(meta, "mie_g", phases.mie_g);
  set_meta(meta, "units", std::string("relative to the sun_illuminance of the preset"));
  set_meta(meta, "mapping",
           std::string(
               "coord(x, n) = 0.5/n + x*(1 - 1/n), H_atm = Rt - Rb; u_h = coord(sqrt(h/H_atm), "
               "width); mu_h = -sqrt(h*(2*Rb + h))/(Rb + h); mu > mu_h (sky): u_mu = 0.5 + "
               "0.5*coord(((mu - mu_h)/(1 - mu_h))^0.2, height/2); ground rays: u_mu = "
               "0.5*coord(((mu_h - mu)/(mu_h + 1))^0.2, height/2); u_s = coord(0.5*(atan(max(mu_s, "
               "mu_s_min)*tan(0.945))/0.75 + 0.74), depth) (Hillaire 2016 Appendix A without the "
               "1e-4 horizon offsets)"));
}

// Order 1 of one texel: the mean over sun azimuths (a + 1/2) pi / N, the
// midpoints of [0, pi] (the other half of the circle mirrors them), two at a
// time (SingleScatteringRay::at_sun2).
SingleScattering azimuth_mean(const TransmittanceReader& reader, const SingleScatteringRay& ray,
                              double mu, double mu_s, int azimuths, glm::dvec3 sun) {
  const double spread = std::sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
  SingleScattering sum;
  for (int a = 0; a < azimuths; a += 2) {
    const int b = std::min(a + 1, azimuths - 1);
    const double mu_s2[2] = {mu_s, mu_s};
    const double nu[2] = {mu * mu_s + spread * std::cos((a + 0.5) * kPi / azimuths),
                          mu * mu_s + spread * std::cos((b + 0.5) * kPi / azimuths)};
    SingleScattering s[2];
    ray.at_sun2(reader, mu_s2, nu, sun, s);
    for (int k = 0; k < (b == a ? 1 : 2); ++k) {
      sum.rayleigh += s[k].rayleigh;
      sum.mie += s[k].mie;
    }
  }
  sum.rayleigh /= double(azimuths);
  sum.mie /= double(azimuths);
  return sum;
}

// azimuth_mean of many suns (mu_s[0..count)) of one ray at once: every
// sun and azimuth in one pass over the nodes (SingleScatteringRay::at_suns),
// summed in azimuth_mean's order, so the same values.
void azimuth_means(const TransmittanceReader& reader, const SingleScatteringRay& ray, double mu,
                   const double* mu_s, int count, int azimuths, glm::dvec3 sun,
                   SingleScattering* out, SingleScatteringRay::Scratch& scratch,
                   std::vector<double>& suns, std::vector<SingleScattering>& each) {
  const int n = count * azimuths;
  suns.resize(2 * size_t(n) + azimuths);
  each.resize(n);
  double* cos_azimuth = suns.data() + 2 * size_t(n);  // the same for every sun
  for (int a = 0; a < azimuths; ++a) cos_azimuth[a] = std::cos((a + 0.5) * kPi / azimuths);
  for (int z = 0; z < count; ++z) {
    const double spread = std::sqrt((1.0 - mu * mu) * (1.0 - mu_s[z] * mu_s[z]));
    for (int a = 0; a < azimuths; ++a) {
      suns[size_t(z) * azimuths + a] = mu_s[z];
      suns[n + size_t(z) * azimuths + a] = mu * mu_s[z] + spread * cos_azimuth[a];
    }
  }
  ray.at_suns(reader, suns.data(), suns.data() + n, n, sun, each.data(), scratch);
  for (int z = 0; z < count; ++z) {
    SingleScattering sum;
    for (int a = 0; a < azimuths; ++a) {
      sum.rayleigh += each[size_t(z) * azimuths + a].rayleigh;
      sum.mie += each[size_t(z) * azimuths + a].mie;
    }
    sum.rayleigh /= double(azimuths);
    sum.mie /= double(azimuths);
    out[z] = sum;
  }
}

}  // namespace

// ---- Shape and mappings ----

void check_scattering3d_shape(const Scattering3dShape& s) {
  if (s.height_size < 2 || s.view_size < 4 || s.view_size % 2 != 0 || s.sun_size < 2)
    throw Error(fmt::format(
        "scattering3d: expected height >= 2, view even >= 4, sun >= 2 texels, got {} x {} x {}",
        s.height_size, s.view_size, s.sun_size));
}

double scattering3d_u_from_h(const Atmosphere& atm, double h, int n) {
  const double thickness = atm.top_radius_m - atm.bottom_radius_m;
  return texel_coord_from_unit(std::sqrt(std::clamp(h / thickness, 0.0, 1.0)), n);
}

double h_from_scattering3d_u(const Atmosphere& atm, double u, int n) {
  const double x = std::clamp(unit_from_texel_coord(u, n), 0.0, 1.0);
  return x * x * (atm.top_radius_m - atm.bottom_radius_m);
}

double scattering3d_u_from_mu_s(double mu_s, int n) {
  const double m = std::clamp(mu_s, kScattering3dMuSMin, 1.0);
  const double x = 0.5 * (std::atan(m * kSunScale) / 0.75 + (1.0 - 0.26));
  return texel_coord_from_unit(std::clamp(x, 0.0, 1.0), n);
}

double mu_s_from_scattering3d_u(double u, int n) {
  const double x = std::clamp(unit_from_texel_coord(u, n), 0.0, 1.0);
  return clamp_cosine(std::tan((2.0 * x - 1.0 + 0.26) * 0.75) / kSunScale);
}

double scattering3d_u_from_mu(const Atmosphere& atm, double h, double mu, bool ray_hits_ground,
                              int n) {
  const double mu_h = horizon_cosine(atm, h);
  const int half = n / 2;
  if (!ray_hits_ground) {
    const double x = std::pow(std::clamp((mu - mu_h) / (1.0 - mu_h), 0.0, 1.0), 0.2);
    return 0.5 + 0.5 * texel_coord_from_unit(x, half);
  }
  const double x = std::pow(std::clamp((mu_h - mu) / (mu_h + 1.0), 0.0, 1.0), 0.2);
  return 0.5 * texel_coord_from_unit(x, half);
}

double mu_from_scattering3d_u(const Atmosphere& atm, double h, double u, int n,
                              bool& ray_hits_ground) {
  const double mu_h = horizon_cosine(atm, h);
  const int half = n / 2;
  ray_hits_ground = u < 0.5;
  if (!ray_hits_ground) {
    const double x = std::clamp(unit_from_texel_coord(2.0 * u - 1.0, half), 0.0, 1.0);
    return clamp_cosine(mu_h + std::pow(x, 5.0) * (1.0 - mu_h));
  }
  const double x = std::clamp(unit_from_texel_coord(2.0 * u, half), 0.0, 1.0);
  return clamp_cosine(mu_h - std::pow(x, 5.0) * (mu_h + 1.0));
}

glm::dvec3 scattering3d_uvw_from_h_mu_mu_s(const Atmosphere& atm, const Scattering3dShape& shape,
                                           double h, double mu, double mu_s, bool ray_hits_ground) {
  return {scattering3d_u_from_h(atm, h, shape.height_size),
          scattering3d_u_from_mu(atm, h, mu, ray_hits_ground, shape.view_size),
          scattering3d_u_from_mu_s(mu_s, shape.sun_size)};
}

Scattering3dParams h_mu_mu_s_from_scattering3d_uvw(const Atmosphere& atm,
                                                   const Scattering3dShape& shape, glm::dvec3 uvw) {
  Scattering3dParams p;
  p.h = h_from_scattering3d_u(atm, uvw.x, shape.height_size);
  p.mu = mu_from_scattering3d_u(atm, p.h, uvw.y, shape.view_size, p.ray_hits_ground);
  p.mu_s = mu_s_from_scattering3d_u(uvw.z, shape.sun_size);
  return p;
}

Scattering3dParams scattering3d_texel_params(const Atmosphere& atm, const Scattering3dShape& shape,
                                             int x, int y, int z) {
  return h_mu_mu_s_from_scattering3d_uvw(
      atm, shape,
      {texel_center(x, shape.height_size), texel_center(y, shape.view_size),
       texel_center(z, shape.sun_size)});
}

// ---- Single scattering ----

SingleScattering compute_single_scattering3d(const Atmosphere& atm,
                                             const Texture& transmittance_lut, double h, double mu,
                                             double mu_s, bool ray_hits_ground, int nodes,
                                             int azimuth_samples) {
  const TransmittanceReader reader(transmittance_lut, atm);
  SingleScatteringRay ray;
  ray.prepare(atm, reader, atm.bottom_radius_m + h, mu, ray_hits_ground, nodes);
  return azimuth_mean(reader, ray, mu, mu_s, azimuth_samples, atm.sun_illuminance);
}

// ---- Bake ----

void check_scattering3d_spec(const Scattering3dSpec& spec) {
  check_scattering3d_shape(spec.shape());
  if (spec.orders < 1 || spec.orders > kMaxScatteringOrders)
    throw Error(fmt::format("scattering3d: expected orders in [1, {}], got {}",
                            kMaxScatteringOrders, spec.orders));
  if (!(spec.tolerance >= 0.0) || !std::isfinite(spec.tolerance))
    throw Error(fmt::format("scattering3d: expected tolerance >= 0, got {}", spec.tolerance));
  if (spec.tolerance > 0.0 && (spec.max_orders < 2 || spec.max_orders > kMaxScatteringOrders))
    throw Error(fmt::format("scattering3d: expected max_orders in [2, {}], got {}",
                            kMaxScatteringOrders, spec.max_orders));
  if (spec.ray_nodes < 2 || spec.azimuth_samples < 1)
    throw Error(
        fmt::format("scattering3d: expected ray_nodes >= 2 and azimuth_samples >= 1, got "
                    "{} and {}",
                    spec.ray_nodes, spec.azimuth_samples));
  if (spec.gathering_directions < 2 || spec.gathering_directions % 2 != 0)
    throw Error(fmt::format("scattering3d: expected an even gathering_directions >= 2, got {}",
                            spec.gathering_directions));
}

namespace {

// Order 1, rows (h, mu) in parallel; the ray's nodes are shared by its suns.
void bake_single_scattering3d(const Atmosphere& atm, const TransmittanceReader& reader,
                              const Scattering3dSpec& spec, Texture& rayleigh, Texture& mie,
                              const BakeContext& ctx) {
  const Scattering3dShape shape = spec.shape();
  const int W = shape.height_size, Hv = shape.view_size, D = shape.sun_size;
  ProgressCounter progress(ctx, size_t(W * Hv));
  tbb::parallel_for(tbb::blocked_range<int>(0, W * Hv), [&](const tbb::blocked_range<int>& range) {
    SingleScatteringRay ray;
    SingleScatteringRay::Scratch scratch;
    std::vector<double> mu_s(D), suns;
    std::vector<SingleScattering> means(D), each;
    for (int z = 0; z < D; ++z) mu_s[z] = mu_s_from_scattering3d_u(texel_center(z, D), D);
    for (int row = range.begin(); row != range.end(); ++row) {
      const int x = row % W, y = row / W;
      const Scattering3dParams p = scattering3d_texel_params(atm, shape, x, y, 0);
      ray.prepare(atm, reader, atm.bottom_radius_m + p.h, p.mu, p.ray_hits_ground, spec.ray_nodes);
      azimuth_means(reader, ray, p.mu, mu_s.data(), D, spec.azimuth_samples, atm.sun_illuminance,
                    means.data(), scratch, suns, each);
      for (int z = 0; z < D; ++z)
        for (int c = 0; c < 3; ++c) {
          rayleigh.at(x, y, z, 0, c) = float(means[z].rayleigh[c]);
          mie.at(x, y, z, 0, c) = float(means[z].mie[c]);
        }
      progress.tick();
    }
  });
}

// The orders k >= 2 of one bake (header): the sums so far, the last order
// (which the next one gathers) and the lit ground.
class Scattering3dIteration {
 public:
  Scattering3dIteration(const Atmosphere& atm, const Texture& transmittance_lut,
                        const Scattering3dSpec& spec, const ScatteringPhases& phases,
                        Texture order1_rayleigh, Texture order1_mie)
      : atm_(atm),
        lut_(transmittance_lut),
        spec_(spec),
        shape_(spec.shape()),
        phases_(phases),
        total_r_(order1_rayleigh),
        total_m_(order1_mie),
        gathering_sum_(shape_.height_size, shape_.sun_size, 1, 1, {"R", "G", "B"}),
        delta_r_(std::move(order1_rayleigh)),
        delta_m_(std::move(order1_mie)) {}

  // Order k: gathers order k - 1 (lit ground of order k - 2) and integrates
  // it along the rays; returns the residual.
  double add_next_order(int k, const BakeContext& ctx) {
    const GatheringPass pass =
        bake_gathering(atm_, lut_, shape_, {&delta_r_, &delta_m_, &phases_}, ground_,
                       spec_.gathering_directions, stage_context(ctx, 0.0, 0.1));
    for (size_t i = 0; i < gathering_sum_.data.size(); ++i)
      gathering_sum_.data[i] += pass.gathering.data[i];
    ground_E_ = pass.ground_irradiance;
    ground_.per_sun_texel = &ground_E_;

    bake_order_from_gathering(atm_, shape_, pass.gathering, spec_.ray_nodes, delta_r_, delta_m_,
                              stage_context(ctx, 0.1, 1.0));
    // The tail's ratio of this order's total to the last's (header).
    glm::dvec3 order_sum(0.0);
    for (size_t i = 0; i < delta_r_.data.size(); ++i)
      order_sum[i % 3] += double(delta_r_.data[i]) + delta_m_.data[i];
    tail_factor_ = k >= 3 ? geometric_tail_factor(order_sum, previous_order_sum_) : glm::dvec3(0.0);
    previous_order_sum_ = order_sum;
    if (spec_.tolerance > 0.0 && spec_.geometric_tail) last_gathering_ = pass.gathering;
    return accumulate_order();
  }

  // Orders k > N stand as DeltaS_N lambda^(k - N): their sum is f DeltaS_N.
  glm::dvec3 add_geometric_tail() {
    for (size_t i = 0; i < total_r_.data.size(); ++i) {
      const double f = tail_factor_[i % 3];
      total_r_.data[i] = float(total_r_.data[i] + f * delta_r_.data[i]);
      total_m_.data[i] = float(total_m_.data[i] + f * delta_m_.data[i]);
    }
    for (size_t i = 0; i < last_gathering_.data.size(); ++i)
      gathering_sum_.data[i] =
          float(gathering_sum_.data[i] + tail_factor_[i % 3] * last_gathering_.data[i]);
    return tail_factor_;
  }

  Texture& total_rayleigh() { return total_r_; }
  Texture& total_mie() { return total_m_; }
  Texture& gathering_sum() { return gathering_sum_; }

 private:
  // Residual (header) and accumulation.
  double accumulate_order() {
    double peak = 0.0;
    for (size_t i = 0; i < total_r_.data.size(); ++i)
      peak = std::max(
          peak, double(total_r_.data[i]) + total_m_.data[i] + delta_r_.data[i] + delta_m_.data[i]);
    const double floor = std::max(1e-6 * peak, std::numeric_limits<double>::min());
    double residual = 0.0;
    for (size_t i = 0; i < total_r_.data.size(); ++i) {
      const double delta = double(delta_r_.data[i]) + delta_m_.data[i];
      const double sum = double(total_r_.data[i]) + total_m_.data[i] + delta;
      residual = std::max(residual, delta / std::max(sum, floor));
      total_r_.data[i] += delta_r_.data[i];
      total_m_.data[i] += delta_m_.data[i];
    }
    return residual;
  }

  const Atmosphere& atm_;
  const Texture& lut_;
  const Scattering3dSpec& spec_;
  const Scattering3dShape shape_;
  const ScatteringPhases& phases_;
  Texture total_r_, total_m_;
  Texture gathering_sum_;
  Texture delta_r_, delta_m_;         // DeltaS of the last order
  std::vector<glm::dvec3> ground_E_;  // E_{k-1} per sun texel
  GroundLight3d ground_;              // direct sunlight for order 1's gathering
  Texture last_gathering_;            // G_{k-1}, for the tail of the gathering sum
  glm::dvec3 previous_order_sum_{0.0}, tail_factor_{0.0};
};

// out.scattering (+ Mie red in A with combined_mie_alpha) and out.mie from
// the sums, with their metadata.
void assemble_scattering3d(const Atmosphere& atm, const Scattering3dSpec& spec,
                           const ScatteringPhases& phases, const Texture& total_r, Texture total_m,
                           Scattering3dTextures& out) {
  out.scattering = Texture(total_r.width, total_r.height, total_r.depth, 1,
                           spec.combined_mie_alpha ? std::vector<std::string>{"R", "G", "B", "A"}
                                                   : std::vector<std::string>{"R", "G", "B"});
  const int channels = out.scattering.channel_count();
  for (size_t t = 0; t < total_r.texel_count(); ++t) {
    for (int c = 0; c < 3; ++c) out.scattering.data[channels * t + c] = total_r.data[3 * t + c];
    if (spec.combined_mie_alpha) out.scattering.data[channels * t + 3] = total_m.data[3 * t];
  }
  out.mie = std::move(total_m);
  set_scattering3d_metadata(
      out.scattering.metadata, atm, spec, out, phases,
      spec.combined_mie_alpha
          ? "RGB: Rayleigh-phase scattering of all orders without phase; A: Mie-phase scattering "
            "red without phase; radiance = p_R(nu)*RGB + p_M(nu)*mie, mie = "
            "RGB*(A/R)*(beta_R.r/beta_M.r)*(beta_M/beta_R)"
          : "Rayleigh-phase scattering of all orders without phase; radiance = p_R(nu)*RGB + "
            "p_M(nu)*mie");
  set_scattering3d_metadata(out.mie.metadata, atm, spec, out, phases,
                            "Mie-phase scattering of all orders without phase, RGB");
}

void set_gathering_sum_metadata(Metadata& g, const Atmosphere& atm, const Scattering3dSpec& spec,
                                const Scattering3dTextures& out) {
  const bool tail_mode = spec.tolerance > 0.0 && spec.geometric_tail;
  set_meta(g, "parameterization", std::string("gathering_sum"));
  set_meta(g, "quantity",
           std::string("sum over orders 1..N-1 of the light gathered from all directions, "
                       "int L dw (radiance x sr); multiple scattering toward a viewer = "
                       "p_c(nu) int sigma_s,c T G_sum ds (Bodare & Sandberg 4.7.3, 6.4)"));
  set_meta(g, "bottom_radius_m", atm.bottom_radius_m);
  set_meta(g, "top_radius_m", atm.top_radius_m);
  set_meta(g, "mu_s_min", kScattering3dMuSMin);
  set_meta(g, "orders", out.orders_used);
  set_meta(g, "last_residual", out.last_residual);
  set_meta(g, "geometric_tail", geometric_tail_metadata(tail_mode, out.tail_factor));
  set_meta(g, "mapping",
           std::string("coord(x, n) = 0.5/n + x*(1 - 1/n); u = coord(sqrt(h/(Rt - Rb)), width), "
                       "v = coord(0.5*(atan(max(mu_s, mu_s_min)*tan(0.945))/0.75 + 0.74), "
                       "height)"));
  set_meta(g, "units", std::string("relative to the sun_illuminance of the preset"));
}

}  // namespace

Scattering3dTextures bake_scattering3d(const Atmosphere& atm, const Texture& transmittance_lut,
                                       const Scattering3dSpec& spec, const BakeContext& ctx) {
  check_scattering3d_spec(spec);
  const Scattering3dShape shape = spec.shape();
  const ScatteringPhases phases = scattering_phases(atm);
  const bool converge = spec.tolerance > 0.0;
  const int last_order = converge ? spec.max_orders : spec.orders;
  // Stages: order 1 and orders 2..N; the tail and the outputs are quick.
  OrderProgress progress(ctx, last_order, spec.tolerance, 0);
  const int W = shape.height_size, Hv = shape.view_size, D = shape.sun_size;

  Texture rayleigh(W, Hv, D, 1, {"R", "G", "B"}), mie(W, Hv, D, 1, {"R", "G", "B"});
  bake_single_scattering3d(atm, TransmittanceReader(transmittance_lut, atm), spec, rayleigh, mie,
                           progress.order_context(1));
  Scattering3dTextures out;
  out.shape = shape;
  out.orders_used = 1;
  out.single_rayleigh = rayleigh;
  out.single_mie = mie;
  Scattering3dIteration orders(atm, transmittance_lut, spec, phases, std::move(rayleigh),
                               std::move(mie));
  for (int k = 2; k <= last_order; ++k) {
    const double residual = orders.add_next_order(k, progress.order_context(k));
    progress.order_done(k, residual);
    out.orders_used = k;
    out.last_residual = residual;
    out.residuals.push_back(residual);
    if (converge && residual < spec.tolerance) break;
  }
  if (converge && spec.geometric_tail) out.tail_factor = orders.add_geometric_tail();
  assemble_scattering3d(atm, spec, phases, orders.total_rayleigh(), std::move(orders.total_mie()),
                        out);
  out.gathering_sum = std::move(orders.gathering_sum());
  set_gathering_sum_metadata(out.gathering_sum.metadata, atm, spec, out);
  const glm::dvec3 balance = sun_zenith_out_over_in_3d(atm, out, transmittance_lut);
  for (Texture* t : {&out.scattering, &out.gathering_sum})
    set_meta(t->metadata, "energy_out_over_in", balance);
  if (ctx.on_progress) ctx.on_progress(1.0);
  return out;
}

// ---- Lookups ----

glm::dvec3 lookup_scattering3d_rgb(const Texture& table, const Scattering3dShape& shape,
                                   const Atmosphere& atm, double h, double mu, double mu_s,
                                   bool ray_hits_ground, int first_channel) {
  const glm::dvec3 uvw = scattering3d_uvw_from_h_mu_mu_s(atm, shape, h, mu, mu_s, ray_hits_ground);
  return read3(table, axis_tap(uvw.x, shape.height_size), axis_tap(uvw.y, shape.view_size),
               axis_tap(uvw.z, shape.sun_size), first_channel);
}

glm::dvec3 lookup_scattering3d(const Texture& scattering, const Texture& mie,
                               const Scattering3dShape& shape, const Atmosphere& atm, double h,
                               double mu, double mu_s, double nu, bool ray_hits_ground) {
  const ScatteringPhases phases = scattering_phases(atm);
  const glm::dvec3 rgb =
      lookup_scattering3d_rgb(scattering, shape, atm, h, mu, mu_s, ray_hits_ground);
  glm::dvec3 m(0.0);
  if (!mie.data.empty()) {
    m = lookup_scattering3d_rgb(mie, shape, atm, h, mu, mu_s, ray_hits_ground);
  } else if (scattering.channel_count() >= 4) {
    // Alpha alone: read channels 1..3 and keep the last.
    const double alpha =
        lookup_scattering3d_rgb(scattering, shape, atm, h, mu, mu_s, ray_hits_ground, 1).z;
    const glm::dvec3 beta_r = phases.rayleigh_per_m, beta_m = phases.mie_per_m;
    if (rgb.r > 0.0 && beta_r.r > 0.0 && beta_m.r > 0.0)
      for (int c = 0; c < 3; ++c)
        m[c] = beta_r[c] > 0.0
                   ? rgb[c] * (alpha / rgb.r) * (beta_r.r / beta_m.r) * (beta_m[c] / beta_r[c])
                   : 0.0;
  }
  return rgb * phases.rayleigh(nu) + m * phases.mie(nu);
}

}  // namespace skybake
