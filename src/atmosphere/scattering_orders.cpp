// The iteration over the scattering orders of the 4D table and its
// stopping rule: order 1, then each order k >= 2 from order k - 1 (the steps
// in incident_radiance, scattering_density and multiple_scattering), the
// geometric tail and the textures. See the header for the equations.
#include "atmosphere/scattering_orders.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "atmosphere/bruneton_outputs.hpp"
#include "atmosphere/energy_balance.hpp"
#include "atmosphere/geometric_tail.hpp"
#include "atmosphere/irradiance_lut.hpp"
#include "atmosphere/mid_texel_error.hpp"
#include "atmosphere/order_progress.hpp"
#include "core/error.hpp"

namespace skybake {

namespace {

void check_transmittance_input(const Texture& transmittance_lut) {
  if (transmittance_lut.channel_count() < 3 || transmittance_lut.width < 2 ||
      transmittance_lut.height < 2)
    throw Error(
        fmt::format("scattering: expected an RGB transmittance LUT of at least 2x2, got {} "
                    "with {} channels",
                    transmittance_lut.shape_string(), transmittance_lut.channel_count()));
}

// The phases of each texel: Mie at the texel's own nu (clamped to what its
// mu and mu_s allow), Rayleigh at its slice's nu before that clamp, for the
// / p_R of the orders >= 2 and the residual (header, "Storage of orders
// >= 2").
struct TexelPhases {
  std::vector<float> rayleigh, mie;
};

TexelPhases texel_phases(const Atmosphere& atm, const ScatteringShape& shape,
                         const ScatteringPhases& phases, const Texture& table) {
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  TexelPhases out{std::vector<float>(table.texel_count()), std::vector<float>(table.texel_count())};
  tbb::parallel_for(
      tbb::blocked_range<int>(0, shape.r_size), [&](const tbb::blocked_range<int>& zs) {
        for (int z = zs.begin(); z != zs.end(); ++z)
          for (int y = 0; y < shape.mu_size; ++y)
            for (int x = 0; x < shape.texture_width(); ++x) {
              const size_t t = table.index(x, y, z) / 3;
              out.rayleigh[t] = float(phases.rayleigh(texels.nu[x / shape.mu_s_size]));
              out.mie[t] = float(phases.mie(texels.params(x, y, z).nu));
            }
      });
  return out;
}

// A texel of the sums with factor times an order's DeltaS added (DeltaS is
// stored times the Rayleigh phase, the sums without it).
inline float with_order(float sum, double factor, float delta, double rayleigh_phase) {
  return float(sum + factor * double(delta) / rayleigh_phase);
}

// to = from, both of one size, in parallel blocks.
void parallel_copy(const TexelVector& from, TexelVector& to) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, from.size(), size_t(1) << 16),
                    [&](const tbb::blocked_range<size_t>& b) {
                      std::copy(from.begin() + b.begin(), from.begin() + b.end(),
                                to.begin() + b.begin());
                    });
}

// What one order changes: its residual (header) and its total per channel,
// the geometric tail's ratio of this order to the last.
struct OrderChange {
  double residual = 0.0;
  glm::dvec3 sum{0.0};
};

// Residual (header): peak of L_{<=k}, then the largest relative change;
// then the order added to the sums (add_order with a factor of 1, in the
// same pass: each texel is measured before it is added).
// In parallel over runs of texels (an r slice each), the totals added run
// by run in order: the same values for any thread count.
OrderChange measure_and_add_order(Texture& accumulated, const Texture& single_mie,
                                  const TexelPhases& phase, const Texture& delta) {
  const size_t runs = size_t(std::max(accumulated.depth, 1));
  const size_t per_run = accumulated.texel_count() / runs;
  auto radiance = [&](size_t t, int c) {
    return double(phase.rayleigh[t]) * accumulated.data[3 * t + c] +
           double(phase.mie[t]) * single_mie.data[3 * t + c] + double(delta.data[3 * t + c]);
  };
  std::vector<double> peaks(runs, 0.0), residuals(runs, 0.0);
  std::vector<glm::dvec3> sums(runs, glm::dvec3(0.0));
  tbb::parallel_for(size_t(0), runs, [&](size_t run) {
    for (size_t t = run * per_run; t < (run + 1) * per_run; ++t)
      for (int c = 0; c < 3; ++c) {
        peaks[run] = std::max(peaks[run], radiance(t, c));
        sums[run][c] += delta.data[3 * t + c];
      }
  });
  const double peak = *std::max_element(peaks.begin(), peaks.end());
  const double floor = std::max(1e-6 * peak, std::numeric_limits<double>::min());
  tbb::parallel_for(size_t(0), runs, [&](size_t run) {
    for (size_t t = run * per_run; t < (run + 1) * per_run; ++t)
      for (int c = 0; c < 3; ++c) {
        residuals[run] = std::max(residuals[run], double(delta.data[3 * t + c]) /
                                                      std::max(radiance(t, c), floor));
        accumulated.data[3 * t + c] =
            with_order(accumulated.data[3 * t + c], 1.0, delta.data[3 * t + c], phase.rayleigh[t]);
      }
  });
  OrderChange change;
  for (size_t run = 0; run < runs; ++run) change.sum += sums[run];
  change.residual = *std::max_element(residuals.begin(), residuals.end());
  return change;
}

// accumulated += factor DeltaS / p_R per channel (header, "Storage of
// orders >= 2").
void add_order(Texture& accumulated, const Texture& delta, const TexelPhases& phase,
               glm::dvec3 factor) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, accumulated.texel_count()),
                    [&](const tbb::blocked_range<size_t>& ts) {
                      for (size_t t = ts.begin(); t != ts.end(); ++t)
                        for (int c = 0; c < 3; ++c)
                          accumulated.data[3 * t + c] =
                              with_order(accumulated.data[3 * t + c], factor[c],
                                         delta.data[3 * t + c], phase.rayleigh[t]);
                    });
}

// The orders k >= 2 of one bake (header, "One order k >= 2 from order
// k - 1"): the sums so far and what the next order reads of the last.
class BrunetonIteration {
 public:
  BrunetonIteration(const Atmosphere& atm, const Texture& transmittance_lut,
                    const BrunetonSpec& spec, const ScatteringPhases& phases,
                    const SingleScatteringTables& single)
      : atm_(atm),
        lut_(transmittance_lut),
        spec_(spec),
        shape_(spec.shape()),
        phases_(phases),
        single_(single),
        phase_(texel_phases(atm, shape_, phases, single.rayleigh)),
        // The density reads the previous order with its ground rows per
        // opacity (header, ground_row_opacity); the irradiance reads only the sky.
        opacity_(ground_row_opacity(atm, shape_)),
        accumulated_(single.rayleigh),
        irradiance_(spec.irradiance_width, spec.irradiance_height, 1, 1, {"R", "G", "B"}),
        previous_{&single.rayleigh, &single.mie, nullptr, &phases} {}

  // Order k: DeltaS_k into the sums, E_{k-1} into the irradiance; returns
  // the residual.
  double add_next_order(int k, const BakeContext& ctx) {
    const bool sun_frame = spec_.density_in_sun_frame;
    if (sun_frame) {
      bake_sun_frame_density(atm_, lut_, shape_, density_previous(k), ground_,
                             spec_.density_directions, sun_frame_azimuths(shape_),
                             stage_context(ctx, 0.0, 0.45), sun_density_);
      divide_by_scattering(atm_, sun_density_);
    } else {
      bake_scattering_density(atm_, lut_, shape_, density_previous(k), ground_,
                              spec_.density_directions, stage_context(ctx, 0.0, 0.45), density_);
    }
    // Order 1 per opacity is read by order 2's density alone: two tables
    // fewer from here on (the bake's peak memory is the orders after it).
    single_r_per_opacity_ = Texture();
    single_m_per_opacity_ = Texture();
    Texture E = bake_indirect_irradiance(atm_, shape_, previous_, spec_.irradiance_width,
                                         spec_.irradiance_height, spec_.irradiance_directions,
                                         BakeContext{});
    for (size_t i = 0; i < irradiance_.data.size(); ++i) irradiance_.data[i] += E.data[i];
    if (sun_frame)
      bake_multiple_scattering(atm_, sun_density_, spec_.ray_nodes, stage_context(ctx, 0.5, 1.0),
                               delta_, work_);
    else
      bake_multiple_scattering(atm_, shape_, density_, spec_.ray_nodes,
                               stage_context(ctx, 0.5, 1.0), delta_, work_);
    if (sun_frame && k == 2)
      mid_texel_error_ = mid_texel_error(atm_, sun_density_, delta_, spec_.ray_nodes);
    const OrderChange change = measure_and_add_order(accumulated_, single_.mie, phase_, delta_);
    // The geometric tail (header): f from this order's total and the last's.
    tail_factor_ =
        k >= 3 ? geometric_tail_factor(change.sum, previous_order_sum_) : glm::dvec3(0.0);
    previous_order_sum_ = change.sum;
    // The order before's buffer takes the next order's DeltaS.
    std::swap(previous_radiance_, delta_);
    ground_table_ = std::move(E);
    previous_ = ScatteringOrder{nullptr, nullptr, &previous_radiance_, &phases_};
    ground_.table = &ground_table_;
    return change.residual;
  }

  // Orders k > N stand as DeltaS_N lambda^(k - N): their sum is f DeltaS_N.
  glm::dvec3 add_geometric_tail() {
    add_order(accumulated_, previous_radiance_, phase_, tail_factor_);
    return tail_factor_;
  }

  // The irradiance of every order: the sky of the last order lights the
  // ground too (header), its tail with it, and the direct part on request.
  Texture take_irradiance(glm::dvec3 tail_factor, const Texture& direct) {
    const Texture E_last = bake_indirect_irradiance(atm_, shape_, previous_, spec_.irradiance_width,
                                                    spec_.irradiance_height,
                                                    spec_.irradiance_directions, BakeContext{});
    for (size_t i = 0; i < irradiance_.data.size(); ++i)
      irradiance_.data[i] += E_last.data[i] * (1.0 + tail_factor[i % 3]);
    if (spec_.irradiance_includes_direct)
      for (size_t i = 0; i < irradiance_.data.size(); ++i) irradiance_.data[i] += direct.data[i];
    return std::move(irradiance_);
  }

  const Texture& accumulated() const { return accumulated_; }
  double measured_mid_texel_error() const { return mid_texel_error_; }

  // After take_irradiance nothing reads the next order's buffers: freed
  // before the outputs are assembled, whose copies would otherwise peak on
  // top of them.
  void release_order_buffers() {
    density_ = Texture();
    sun_density_ = SunFrameDensity();
    delta_ = Texture();
    previous_per_opacity_ = Texture();
    previous_radiance_ = Texture();
    ground_table_ = Texture();
  }

 private:
  // Order k - 1 as the density reads it, ground rows per opacity.
  ScatteringOrder density_previous(int k) {
    if (k < 3) {
      single_r_per_opacity_ = divide_ground_rows_by_opacity(single_.rayleigh, shape_, opacity_);
      single_m_per_opacity_ = divide_ground_rows_by_opacity(single_.mie, shape_, opacity_);
      return ScatteringOrder{&single_r_per_opacity_, &single_m_per_opacity_, nullptr, &phases_,
                             true};
    }
    // Copied into the buffer of the order before (no fresh pages to fault
    // in), in parallel: a serial copy of the table each order held back the
    // second thread.
    if (previous_per_opacity_.data.size() != previous_radiance_.data.size())
      previous_per_opacity_ = previous_radiance_;
    else
      parallel_copy(previous_radiance_.data, previous_per_opacity_.data);
    divide_ground_rows_by_opacity_in_place(previous_per_opacity_, shape_, opacity_);
    return ScatteringOrder{nullptr, nullptr, &previous_per_opacity_, &phases_, true};
  }

  const Atmosphere& atm_;
  const Texture& lut_;
  const BrunetonSpec& spec_;
  const ScatteringShape shape_;
  const ScatteringPhases& phases_;
  const SingleScatteringTables& single_;
  const TexelPhases phase_;
  const std::vector<glm::dvec3> opacity_;
  Texture single_r_per_opacity_, single_m_per_opacity_;  // order 2's density only
  Texture accumulated_;           // RGB of the scattering texture
  Texture irradiance_;            // E_1 .. E_{k-1}
  Texture previous_radiance_;     // DeltaS of the previous order (k >= 3)
  Texture previous_per_opacity_;  // the same, ground rows per opacity
  // Buffers every order rewrites whole, kept so that the kernel does not
  // fault in and clear fresh pages each order (about 3% of a tolerance bake).
  Texture density_, delta_;
  SunFrameDensity sun_density_;  // J / sigma_s in the sun's frame (header)
  MultipleScatteringWork work_;   // J / sigma_s and the rows' nodes
  Texture ground_table_;          // E_{k-2} for k >= 3
  ScatteringOrder previous_;      // order k - 1 as the irradiance reads it
  GroundIrradiance ground_;       // direct sunlight for order 2
  glm::dvec3 previous_order_sum_{0.0}, tail_factor_{0.0};
  double mid_texel_error_ = -1.0;  // of order 2 (mid_texel_error.hpp); -1: not measured
};

}  // namespace

// ---- Spec ----

void check_bruneton_spec(const BrunetonSpec& spec) {
  check_scattering_shape(spec.shape());
  if (spec.orders < 1 || spec.orders > kMaxScatteringOrders)
    throw Error(fmt::format("scattering: expected orders in [1, {}], got {}", kMaxScatteringOrders,
                            spec.orders));
  if (!(spec.tolerance >= 0.0) || !std::isfinite(spec.tolerance))
    throw Error(fmt::format("scattering: expected tolerance >= 0, got {}", spec.tolerance));
  if (spec.tolerance > 0.0 && (spec.max_orders < 2 || spec.max_orders > kMaxScatteringOrders))
    throw Error(fmt::format("scattering: expected max_orders in [2, {}], got {}",
                            kMaxScatteringOrders, spec.max_orders));
  if (spec.irradiance_width < 2 || spec.irradiance_height < 2)
    throw Error(fmt::format("irradiance: expected at least 2x2 texels, got {}x{}",
                            spec.irradiance_width, spec.irradiance_height));
  if (spec.ray_nodes < 2 || spec.density_directions < 2 || spec.irradiance_directions < 2)
    throw Error(fmt::format(
        "scattering: expected ray_nodes, density_directions and irradiance_directions >= 2, got "
        "{}, {}, {}",
        spec.ray_nodes, spec.density_directions, spec.irradiance_directions));
}

// ---- The iteration ----

BrunetonTextures bake_bruneton(const Atmosphere& atm, const Texture& transmittance_lut,
                               const BrunetonSpec& spec, const BakeContext& ctx) {
  check_bruneton_spec(spec);
  check_transmittance_input(transmittance_lut);
  const bool converge = spec.tolerance > 0.0;
  const int last_order = converge ? spec.max_orders : spec.orders;
  // Stages: single scattering, orders 2..N, the final irradiance.
  OrderProgress progress(ctx, last_order, spec.tolerance, 1);
  const ScatteringPhases phases = scattering_phases(atm);

  BrunetonTextures out;
  out.shape = spec.shape();
  SingleScatteringTables single = bake_single_scattering(atm, transmittance_lut, out.shape,
                                                         spec.ray_nodes, progress.order_context(1));
  out.orders_used = 1;
  BrunetonIteration orders(atm, transmittance_lut, spec, phases, single);
  for (int k = 2; k <= last_order; ++k) {
    const double residual = orders.add_next_order(k, progress.order_context(k));
    progress.order_done(k, residual);
    out.orders_used = k;
    out.last_residual = residual;
    out.residuals.push_back(residual);
    if (converge && residual < spec.tolerance) break;
  }
  if (converge && spec.geometric_tail) out.tail_factor = orders.add_geometric_tail();
  out.mid_texel_error = orders.measured_mid_texel_error();
  out.direct_irradiance = bake_direct_irradiance(atm, transmittance_lut, spec.irradiance_width,
                                                 spec.irradiance_height, BakeContext{});
  Texture irradiance = orders.take_irradiance(out.tail_factor, out.direct_irradiance);
  orders.release_order_buffers();
  assemble_bruneton_outputs(atm, spec, orders.accumulated(), std::move(single.mie),
                            std::move(irradiance), out);
  const glm::dvec3 balance = sun_zenith_out_over_in(atm, out, spec.irradiance_includes_direct);
  set_meta(out.scattering.metadata, "energy_out_over_in", balance);
  set_meta(out.irradiance.metadata, "energy_out_over_in", balance);
  out.single_rayleigh = std::move(single.rayleigh);
  if (ctx.on_progress) ctx.on_progress(1.0);
  return out;
}

}  // namespace skybake
