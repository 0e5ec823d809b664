#include "pipeline/warnings.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>

#include <fmt/format.h>

#include "atmosphere/energy_balance.hpp"
#include "atmosphere/mid_texel_error.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {

namespace {

// A number of the metadata (an int or a double), NaN when absent or of
// another type; NaN fails every comparison below.
double meta_number(const Texture& t, const std::string& key) {
  if (const double* v = find_meta<double>(t.metadata, key)) return *v;
  if (const int* v = find_meta<int>(t.metadata, key)) return double(*v);
  return NAN;
}

// The largest channel of a double3 metadata value, NaN when absent.
double meta_max(const Texture& t, const std::string& key) {
  const glm::dvec3* v = find_meta<glm::dvec3>(t.metadata, key);
  return v ? std::max({v->x, v->y, v->z}) : NAN;
}

// A number of a record, or `fallback` when absent or not a number (JSON has
// no infinity: a ratio that is infinite is recorded as null).
double number_or(const nlohmann::json& j, const char* key, double fallback) {
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

// Largest value of the colour channels (R, G, B).
double colour_max(const Texture& t) {
  double best = 0.0;
  const int channels = t.channel_count(), colour = std::min(channels, 3);
  for (size_t i = 0; i < t.data.size(); ++i)
    if (int(i % size_t(channels)) < colour) best = std::max(best, double(t.data[i]));
  return best;
}

// Without `max_error` in the output: the smallest of 0.1, 0.2, 0.5, 1, 2, 5,
// 10, 20 at or above 10x the largest max_rel the shipped presets measure for
// the product (docs/decisions/warnings.md), so the default flags a table
// an order of magnitude worse than the shipped planets' at their settings.
const std::map<std::string, double> kDefaultMaxError = {
    {"transmittance", 0.5},      {"multiscattering", 20.0}, {"skyview", 0.1},
    {"aerial_perspective", 5.0}, {"scattering", 5.0},       {"single_mie", 20.0},
    {"irradiance", 10.0},        {"scattering3d", 10.0},    {"gathering_sum", 5.0}};

// Products whose colour channels hold scattered light.
const std::set<std::string> kScatteredLight = {
    "multiscattering", "skyview",    "aerial_perspective", "scattering",
    "single_mie",      "irradiance", "scattering3d",       "gathering_sum"};

// Whether the medium scatters light the product holds (single_mie: the
// Mie group only).
bool scatters(const Scene& scene, const std::string& product) {
  for (const MediumComponent& c : scene.atmosphere.components) {
    if (c.phase == PhaseKind::none || c.scattering_per_m == glm::dvec3(0.0)) continue;
    if (product != "single_mie" || c.phase != PhaseKind::rayleigh) return true;
  }
  return false;
}

// Products whose values sum the scattering orders (single_mie carries the
// family's order metadata but holds order 1 only).
const std::set<std::string> kSumsOrders = {"scattering", "irradiance", "scattering3d",
                                           "gathering_sum"};

void order_warnings(const Texture& t, std::vector<OutputWarning>& out) {
  const double tolerance = meta_number(t, "tolerance"), residual = meta_number(t, "last_residual");
  const double orders = meta_number(t, "orders");
  if (tolerance > 0.0 && residual >= tolerance)
    out.push_back({"not_converged",
                   fmt::format("{:g} orders, last residual {:.3g} above the tolerance {:g}", orders,
                               residual, tolerance),
                   {{"orders", orders}, {"last_residual", residual}, {"tolerance", tolerance}}});
  const double tail = meta_max(t, "geometric_tail");
  if (tail > 0.0 && tail * residual > kMaxTailShare)
    out.push_back(
        {"tail_dominates",
         fmt::format("geometric tail factor {:.3g} x last residual {:.3g}: the tail "
                     "stands for up to {:.0f}% of a texel",
                     tail, residual, 100.0 * tail * residual),
         {{"geometric_tail", tail}, {"last_residual", residual}, {"tail_share", tail * residual}}});
}

// A 4D table that returns more than the sunlight (atmosphere/energy_balance.hpp).
void energy_warnings(const Texture& t, std::vector<OutputWarning>& out) {
  const double ratio = meta_max(t, "energy_out_over_in");
  if (!(ratio > 1.0 + kEnergyGainTolerance)) return;
  out.push_back({"energy_gain",
                 fmt::format("with the sun at the zenith the table returns {:.3g} of the sunlight "
                             "(up through the top + absorbed by the ground, at most 1): a sharp "
                             "forward phase lerped over too few mu texels; more mu texels "
                             "(scattering.shape) bring it down",
                             ratio),
                 {{"out_over_in", ratio}, {"tolerance", kEnergyGainTolerance}}});
}

// A 4D table whose second order, read between mu texels, is far from its
// quadrature (atmosphere/mid_texel_error.hpp).
void mid_texel_warnings(const Texture& t, std::vector<OutputWarning>& out) {
  const double error = meta_max(t, "mid_texel_error");
  if (!(error > kMidTexelErrorLimit)) return;
  out.push_back({"coarse_table",
                 fmt::format("the second order read between mu texels is {:.3g} (RMS, relative) "
                             "from its quadrature at their midpoints: the mu axis is too coarse "
                             "for this sky (a thin shell, a sharp lobe); more mu texels "
                             "(scattering.shape) bring it down",
                             error),
                 {{"mid_texel_error", error}, {"limit", kMidTexelErrorLimit}}});
}

// Texels of the transmittance table that are 0 in some channel: the optical
// depth to the top is above ~103 there and float32 holds 0, so an engine's
// transmittance between two points, a ratio of two reads, is 0 / 0.
void underflow_warnings(const Texture& t, std::vector<OutputWarning>& out) {
  size_t zero = 0;
  const int channels = t.channel_count();
  for (size_t texel = 0; texel < t.texel_count(); ++texel)
    for (int c = 0; c < std::min(channels, 3); ++c)
      if (t.data[texel * size_t(channels) + size_t(c)] == 0.0f) {
        ++zero;
        break;
      }
  if (zero == 0) return;
  const double fraction = double(zero) / double(t.texel_count());
  out.push_back({"transmittance_underflow",
                 fmt::format("{} of {} texels ({:.1f}%) are 0 in float32 (optical depth above "
                             "~103): a ratio of two reads is undefined there",
                             zero, t.texel_count(), 100.0 * fraction),
                 {{"zero_texels", zero}, {"fraction", fraction}}});
}

void multiscattering_warnings(const Texture& t, std::vector<OutputWarning>& out) {
  const double clamped = meta_number(t, "fms_clamped_texels");
  if (!(clamped > 0.0)) return;
  const double fms_max = meta_number(t, "fms_max"), clamp = meta_number(t, "fms_clamp");
  const double largest = colour_max(t);
  out.push_back({"fms_clamped",
                 fmt::format("f_ms reached {:.9g} in {:g} texels, clamped to {:.9g}; Psi_ms up "
                             "to {:.3g}",
                             fms_max, clamped, clamp, largest),
                 {{"clamped_texels", clamped},
                  {"fms_max", fms_max},
                  {"fms_clamp", clamp},
                  {"max_value", largest}}});
}

}  // namespace

nlohmann::json OutputWarning::json() const {
  nlohmann::json j = {{"code", code}, {"message", message}};
  for (const auto& [key, value] : numbers.items()) j[key] = value;
  return j;
}

std::vector<OutputWarning> output_warnings(const Scene& scene, const OutputSpec& spec,
                                           const Texture& texture, const nlohmann::json& error,
                                           const nlohmann::json& tiling) {
  std::vector<OutputWarning> out;
  if (kSumsOrders.count(spec.product)) order_warnings(texture, out);
  energy_warnings(texture, out);
  mid_texel_warnings(texture, out);
  if (spec.product == "multiscattering") multiscattering_warnings(texture, out);
  if (spec.product == "transmittance") underflow_warnings(texture, out);
  if (kScatteredLight.count(spec.product) && scatters(scene, spec.product) &&
      colour_max(texture) == 0.0)
    out.push_back({"black_output",
                   "every colour texel is 0 though the medium scatters light",
                   {{"max_value", 0.0}}});
  if (error.is_object()) {
    auto fallback = kDefaultMaxError.find(spec.product);
    const double limit = option_double(
        spec, "max_error", fallback != kDefaultMaxError.end() ? fallback->second : INFINITY);
    const double max_rel = number_or(error, "max_rel", 0.0);
    const double rms_rel = number_or(error, "rms_rel", 0.0);
    if (max_rel > limit)
      out.push_back({"error_above_limit",
                     fmt::format("measured max_rel {:.3g} (rms_rel {:.3g}) above max_error {:g}",
                                 max_rel, rms_rel, limit),
                     {{"max_rel", max_rel}, {"rms_rel", rms_rel}, {"max_error", limit}}});
  }
  // "cannot_tell" (white noise, axes under 16 texels) is recorded, not warned.
  if (tiling.is_object() && tiling.value("verdict", std::string()) == "seam") {
    const double ratio = number_or(tiling, "worst_ratio", INFINITY);
    const double tol = number_or(tiling, "tolerance", 0.0);
    out.push_back({"not_tileable",
                   fmt::format("the seam stands out from the interior faces: worst score / "
                               "limit {:.3g} (tolerance {:g})",
                               ratio, tol),
                   {{"worst_ratio", ratio}, {"tolerance", tol}}});
  }
  return out;
}

std::string warning_line(const nlohmann::json& warning) {
  return fmt::format("{}: {}", warning.value("code", std::string("warning")),
                     warning.value("message", std::string()));
}

}  // namespace skybake
