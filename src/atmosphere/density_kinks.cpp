#include "atmosphere/density_kinks.hpp"

#include <cmath>
#include <limits>

namespace skybake {

void add_profile_kinks(const DensityProfile& profile, double top_h, std::vector<double>& out) {
  const double inf = std::numeric_limits<double>::infinity();
  double bottom = 0.0;
  for (size_t i = 0; i < profile.layers.size(); ++i) {
    const DensityLayer& l = profile.layers[i];
    const bool last = i + 1 == profile.layers.size();
    const double top = last ? inf : bottom + l.width_m;
    auto add = [&](double h, double lo, double hi) {
      if (h > lo && h < hi && h > 0.0 && h < top_h) out.push_back(h);
    };
    if (!last) add(top, -inf, inf);
    for (double v : {0.0, 1.0}) {
      if (l.exp_term == 0.0 && l.linear_term_per_m != 0.0) {
        add((v - l.constant_term) / l.linear_term_per_m, bottom, top);
      } else if (l.linear_term_per_m == 0.0 && l.exp_term != 0.0 && l.exp_scale_per_m != 0.0) {
        const double q = (v - l.constant_term) / l.exp_term;  // exp(b h) = q
        if (q > 0.0) add(std::log(q) / l.exp_scale_per_m, bottom, top);
      }
    }
    bottom = top;
  }
}

bool is_piecewise_linear(const DensityProfile& profile) {
  for (const DensityLayer& l : profile.layers)
    if (l.exp_term != 0.0) return false;
  return true;
}

}  // namespace skybake
