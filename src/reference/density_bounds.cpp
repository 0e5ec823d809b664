// Kinks and maxima of density profiles; see the header for why they are exact.
#include "reference/density_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace skybake {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A layer's formula before the clamp, evaluated as density_at does.
double layer_formula(const DensityLayer& l, double h) {
  const double e = l.exp_term == 0.0 ? 0.0 : l.exp_term * std::exp(l.exp_scale_per_m * h);
  return e + l.linear_term_per_m * h + l.constant_term;
}

// The layer's critical point (f' = 0), or NaN when it has none.
double critical_altitude(const DensityLayer& l) {
  const double ab = l.exp_term * l.exp_scale_per_m;
  if (ab == 0.0 || l.linear_term_per_m == 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double q = -l.linear_term_per_m / ab;  // exp(b h*) = q
  if (!(q > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return std::log(q) / l.exp_scale_per_m;
}

// The altitude range [bottom, top) of each layer, as density_at assigns them
// (the first layer also takes every altitude below 0; the last extends up
// without bound).
struct LayerRange {
  const DensityLayer* layer;
  double bottom, top;
};
std::vector<LayerRange> layer_ranges(const DensityProfile& profile) {
  std::vector<LayerRange> out;
  double bottom = 0.0;
  for (size_t i = 0; i < profile.layers.size(); ++i) {
    const bool last = i + 1 == profile.layers.size();
    const double top = last ? kInfinity : bottom + profile.layers[i].width_m;
    out.push_back({&profile.layers[i], i == 0 ? -kInfinity : bottom, top});
    bottom = top;
  }
  return out;
}

// Where the monotone f crosses v on [lo, hi], by bisection to the last bit.
void add_crossing(const DensityLayer& l, double v, double lo, double hi, std::vector<double>& out) {
  double f_lo = layer_formula(l, lo) - v;
  const double f_hi = layer_formula(l, hi) - v;
  if (!(f_lo * f_hi < 0.0)) return;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const double f_mid = layer_formula(l, mid) - v;
    if ((f_mid < 0.0) == (f_lo < 0.0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  out.push_back(0.5 * (lo + hi));
}

}  // namespace

std::vector<double> profile_kink_altitudes(const DensityProfile& profile, double top_altitude_m) {
  std::vector<double> kinks;
  const auto inside = [&](double h) { return h > 0.0 && h < top_altitude_m; };
  for (const LayerRange& range : layer_ranges(profile)) {
    if (inside(range.top)) kinks.push_back(range.top);
    const double lo = std::max(range.bottom, 0.0), hi = std::min(range.top, top_altitude_m);
    if (!(lo < hi)) continue;
    // Monotone pieces of the layer's formula on [lo, hi].
    std::vector<double> ends = {lo};
    const double h_star = critical_altitude(*range.layer);
    if (h_star > lo && h_star < hi) ends.push_back(h_star);
    ends.push_back(hi);
    for (size_t i = 0; i + 1 < ends.size(); ++i)
      for (double v : {0.0, 1.0}) add_crossing(*range.layer, v, ends[i], ends[i + 1], kinks);
  }
  kinks.erase(std::remove_if(kinks.begin(), kinks.end(), [&](double h) { return !inside(h); }),
              kinks.end());
  std::sort(kinks.begin(), kinks.end());
  kinks.erase(std::unique(kinks.begin(), kinks.end()), kinks.end());
  return kinks;
}

std::vector<double> density_kink_altitudes(const Atmosphere& atm) {
  const double top = atm.top_radius_m - atm.bottom_radius_m;
  std::vector<double> kinks;
  for (const MediumComponent& c : atm.components) {
    if (c.scattering_per_m + c.absorption_per_m == glm::dvec3(0.0)) continue;
    const std::vector<double> k = profile_kink_altitudes(c.density, top);
    kinks.insert(kinks.end(), k.begin(), k.end());
  }
  std::sort(kinks.begin(), kinks.end());
  kinks.erase(std::unique(kinks.begin(), kinks.end()), kinks.end());
  return kinks;
}

namespace {

// The extreme (max when `maximum`, else min) of density_at over [lo_m, hi_m]:
// per layer, its formula at the ends of its share of the interval and at its
// critical point; clamping is monotone, so it commutes with the extreme.
double density_extreme(const DensityProfile& profile, double lo_m, double hi_m, bool maximum) {
  bool any = false;
  double best = 0.0;
  for (const LayerRange& range : layer_ranges(profile)) {
    const double lo = std::max(lo_m, range.bottom), hi = std::min(hi_m, range.top);
    if (lo > hi || lo_m >= range.top) continue;  // a layer's top is open
    const DensityLayer& l = *range.layer;
    const double f_lo = layer_formula(l, lo), f_hi = layer_formula(l, hi);
    double e = maximum ? std::max(f_lo, f_hi) : std::min(f_lo, f_hi);
    const double h_star = critical_altitude(l);
    if (h_star > lo && h_star < hi)
      e = maximum ? std::max(e, layer_formula(l, h_star)) : std::min(e, layer_formula(l, h_star));
    e = std::clamp(e, 0.0, 1.0);
    best = !any ? e : (maximum ? std::max(best, e) : std::min(best, e));
    any = true;
  }
  return best;
}

}  // namespace

double max_density_over(const DensityProfile& profile, double lo_m, double hi_m) {
  return density_extreme(profile, lo_m, hi_m, true);
}

double min_density_over(const DensityProfile& profile, double lo_m, double hi_m) {
  return density_extreme(profile, lo_m, hi_m, false);
}

}  // namespace skybake
