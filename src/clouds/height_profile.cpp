#include "clouds/height_profile.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

namespace skybake {

std::vector<CloudTypeProfile> default_cloud_types() {
  return {
      {"stratus", {0.02, 0.05, 0.09, 0.11}, 0.2, 0.4},
      {"stratocumulus", {0.02, 0.2, 0.48, 0.625}, 0.5, 0.6},
      {"cumulus", {0.01, 0.0625, 0.78, 1.0}, 0.8, 0.6},
      {"cumulonimbus", {0.01, 0.04, 0.9, 1.0}, 0.7, 0.3},
  };
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double compute_height_density(const HeightRamp& r, double h) {
  // Clamped: rounding cannot leave [0, 1] for a valid ramp, but an
  // overlapping one (c < b, refused by ramp_problems) could.
  return std::clamp(smoothstep(r.a, r.b, h) - smoothstep(r.c, r.d, h), 0.0, 1.0);
}

double compute_height_erosion(const CloudTypeProfile& type, double h) {
  const HeightRamp& r = type.density;
  const double t = std::clamp((h - r.a) / (r.d - r.a), 0.0, 1.0);
  return type.erosion_base + t * (type.erosion_top - type.erosion_base);
}

std::vector<SpecProblem> ramp_problems(const HeightRamp& r, const std::string& field) {
  const double v[4] = {r.a, r.b, r.c, r.d};
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0 || v[i] > 1.0)
      return {{fmt::format("{}[{}]", field, i),
               fmt::format("expected a normalized height in [0, 1], got {}", v[i])}};
  const bool ordered = r.a < r.b && r.b <= r.c && r.c < r.d;
  if (ordered) return {};
  return {{field, fmt::format("expected a < b <= c < d (density = smoothstep(a, b, h) - "
                              "smoothstep(c, d, h)), got [{}, {}, {}, {}]",
                              r.a, r.b, r.c, r.d)}};
}

std::vector<SpecProblem> cloud_type_problems(const std::vector<CloudTypeProfile>& types) {
  std::vector<SpecProblem> out;
  std::set<std::string> names;
  for (size_t i = 0; i < types.size(); ++i) {
    const CloudTypeProfile& t = types[i];
    const std::string at = fmt::format("types[{}]", i);
    if (t.name.empty()) out.push_back({at + ".name", "expected a name, got an empty string"});
    if (!names.insert(t.name).second)
      out.push_back({at + ".name", fmt::format("type name '{}' is already used", t.name)});
    for (const SpecProblem& p : ramp_problems(t.density, at + ".density")) out.push_back(p);
    for (double e : {t.erosion_base, t.erosion_top})
      if (!(e >= 0.0 && e <= 1.0))
        out.push_back({at + ".erosion", fmt::format("expected amounts in [0, 1], got {}", e)});
  }
  return out;
}

}  // namespace skybake
