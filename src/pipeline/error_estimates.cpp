#include "pipeline/error_estimates.hpp"

#include <algorithm>
#include <cmath>

#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {

namespace {

// Accumulates (value, reference) pairs of one or more channels.
class ErrorTally {
 public:
  void add(double value, double reference) { pairs_.push_back({value, reference}); }
  nlohmann::json json(const std::string& reference) const {
    double scale = 0.0;
    for (const auto& [v, r] : pairs_) scale = std::max(scale, std::abs(r));
    const double floor = std::max(1e-3 * scale, 1e-30);
    double max_abs = 0.0, max_rel = 0.0, sum_sq = 0.0;
    for (const auto& [v, r] : pairs_) {
      const double abs_err = std::abs(v - r);
      const double rel = abs_err / std::max(std::abs(r), floor);
      max_abs = std::max(max_abs, abs_err);
      max_rel = std::max(max_rel, rel);
      sum_sq += rel * rel;
    }
    const double n = double(std::max<size_t>(pairs_.size(), 1));
    return {{"reference", reference},
            {"samples", pairs_.size()},
            {"max_abs", max_abs},
            {"max_rel", max_rel},
            {"rms_rel", std::sqrt(sum_sq / n)}};
  }

 private:
  std::vector<std::pair<double, double>> pairs_;
};

// n evenly spread texel indices of an axis of `size` texels, ends included.
std::vector<int> sample_indices(int size, int n) {
  std::vector<int> out;
  n = std::min(n, size);
  for (int i = 0; i < n; ++i)
    out.push_back(n == 1 ? 0 : int(std::lround(double(i) * (size - 1) / (n - 1))));
  return out;
}

}  // namespace

nlohmann::json estimate_transmittance_error(const Scene& scene, const OutputSpec& spec,
                                            const ProductInputs&, const Texture& lut) {
  const int steps = option_int(spec, "steps", 40) * 8;
  ErrorTally tally;
  for (int y : sample_indices(lut.height, 8))
    for (int x : sample_indices(lut.width, 8)) {
      double r, mu;
      r_mu_from_transmittance_uv(scene.atmosphere,
                                 {texel_center(x, lut.width), texel_center(y, lut.height)},
                                 lut.width, lut.height, r, mu);
      const glm::dvec3 ref = compute_transmittance_to_top(scene.atmosphere, r, mu, steps);
      for (int c = 0; c < 3; ++c) tally.add(lut.at(x, y, 0, 0, c), ref[c]);
    }
  return tally.json("same integral with 8x the steps at 64 texels");
}

nlohmann::json estimate_multiscattering_error(const Scene& scene, const OutputSpec& spec,
                                              const ProductInputs& in, const Texture& lut) {
  const std::vector<glm::dvec3> dirs =
      fibonacci_sphere_directions(option_int(spec, "directions", 64) * 16);
  const int steps = option_int(spec, "steps", 20) * 4;
  ErrorTally tally;
  for (int y : sample_indices(lut.height, 4))
    for (int x : sample_indices(lut.width, 4)) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          scene.atmosphere, {texel_center(x, lut.width), texel_center(y, lut.height)}, lut.width,
          lut.height);
      const MultiscatteringSample ref = compute_multiscattering(
          scene.atmosphere, *in.at("transmittance"), p.r, p.mu_s, dirs, steps);
      for (int c = 0; c < 3; ++c) tally.add(lut.at(x, y, 0, 0, c), ref.psi_ms[c]);
    }
  return tally.json("16x the directions and 4x the steps at 16 texels");
}

nlohmann::json estimate_skyview_error(const Scene& scene, const OutputSpec& spec,
                                      const ProductInputs& in, const Texture& lut) {
  const SkyviewLutSpec baked = skyview_spec(spec);
  const Atmosphere& atm = scene.atmosphere;
  IntegrationOptions options;
  options.distribution = baked.distribution;
  ErrorTally tally;
  for (int layer = 0; layer < lut.layers; ++layer) {
    const SkyviewView& view = baked.views.at(size_t(layer));
    const double r = atm.bottom_radius_m + std::max(view.altitude_m, 0.0);
    const glm::dvec3 sun_dir(std::sin(view.sun_zenith_rad), 0.0, std::cos(view.sun_zenith_rad));
    for (int y : sample_indices(lut.height, 8))
      for (int x : sample_indices(lut.width / 2, 4)) {
        const SkyviewDirection d = view_from_skyview_uv(
            atm, r, {texel_center(x, lut.width), texel_center(y, lut.height)}, lut.width,
            lut.height);
        const ScatteringResult ref =
            integrate_scattered_luminance(atm, *in.at("transmittance"), in.at("multiscattering"),
                                          {0.0, 0.0, r}, skyview_vector_from_direction(d), sun_dir,
                                          INFINITY, baked.steps * 10, options);
        for (int c = 0; c < 3; ++c) tally.add(lut.at(x, y, 0, layer, c), ref.luminance[c]);
      }
  }
  return tally.json("10x the steps at 32 texels per layer");
}

nlohmann::json estimate_aerial_perspective_error(const Scene& scene, const OutputSpec& spec,
                                                 const ProductInputs& in, const Texture& lut) {
  // The volume is cheap: bake all of it again with 8x the steps per slice.
  AerialPerspectiveSpec fine = aerial_perspective_spec(spec);
  fine.steps_per_slice *= 8;
  const Texture ref = bake_aerial_perspective_lut(scene.atmosphere, *in.at("transmittance"),
                                                  *in.at("multiscattering"), fine, BakeContext{});
  ErrorTally tally;
  for (size_t i = 0; i < lut.data.size(); ++i) tally.add(lut.data[i], ref.data[i]);
  return tally.json("8x the steps per slice at every froxel (RGB and A)");
}

}  // namespace skybake
