#include "report/precision.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/half.hpp"
#include "report/stats.hpp"
#include "reference/atmosphere_quadrature.hpp"

namespace skybake {

namespace {

constexpr double kVisibleFloor = 1e-6;
constexpr double kTolerance = 1e-10;
const double kElevationsDeg[] = {10.0, 2.0, 0.5, 0.1, 0.0, -0.1, -0.5, -2.0, -10.0};
const double kAltitudeFractions[] = {0.0, 0.01, 0.1};
const double kPathFractions[] = {0.01, 0.1, 0.5, 1.0};

// The factors of the ratio for the segment of length d from (r, mu), as
// lookup_transmittance takes them: numerator and denominator per channel.
struct Factors {
  glm::dvec3 numerator{1.0}, denominator{1.0};
};

Factors exact_factors(const Atmosphere& atm, double r, double mu, double d, bool hits_ground) {
  const double r_d = std::clamp(radius_after(r, mu, d), atm.bottom_radius_m, atm.top_radius_m);
  const double mu_d = mu_after(r, mu, d, r_d);
  auto top = [&](double rr, double mm) {
    return reference_transmittance_to_top(atm, rr, mm, kTolerance).value;
  };
  if (hits_ground) return {top(r_d, -mu_d), top(r, -mu)};
  return {top(r, mu), top(r_d, mu_d)};
}

// The ratio from factors stored in float32 or half, with lookup_transmittance's rule.
glm::dvec3 stored_ratio(const Factors& f, bool half) {
  glm::dvec3 t(0.0);
  for (int c = 0; c < 3; ++c) {
    float n = float(f.numerator[c]), d = float(f.denominator[c]);
    if (half) {
      n = float_from_half(half_from_float(n));
      d = float_from_half(half_from_float(d));
    }
    t[c] = d > 0.0f ? std::min(double(n) / double(d), 1.0) : 0.0;
  }
  return t;
}

bool underflows(const Factors& f, bool half) {
  for (int c = 0; c < 3; ++c) {
    const float d = float(f.denominator[c]);
    if ((half ? float_from_half(half_from_float(d)) : d) == 0.0f) return true;
  }
  return false;
}

struct Case {
  double altitude_m = 0.0, elevation_deg = 0.0, fraction = 0.0;
  bool valid = false;
  glm::dvec3 reference{0.0}, lut{0.0}, lut_half{0.0}, exact_float{0.0}, exact_half{0.0};
  bool underflow_float = false, underflow_half = false;
};

// Max relative and absolute error, and the lost cases, of one method.
struct MethodTally {
  double max_rel = 0.0, max_abs = 0.0;
  int lost = 0, underflow = 0;
  void add(glm::dvec3 v, glm::dvec3 ref, bool underflowed) {
    bool off = false;
    for (int c = 0; c < 3; ++c) {
      const double abs_err = std::abs(v[c] - ref[c]);
      const double rel = abs_err / std::max(ref[c], kVisibleFloor);
      max_rel = std::max(max_rel, rel);
      max_abs = std::max(max_abs, abs_err);
      off = off || (ref[c] > kVisibleFloor && rel > 0.5);
    }
    lost += off;
    underflow += underflowed;
  }
  nlohmann::json json() const {
    return {{"max_rel", max_rel}, {"max_abs", max_abs}, {"lost", lost}, {"underflow", underflow}};
  }
};

}  // namespace

nlohmann::json horizon_transmittance_report(const ReportInputs& in) {
  in.stage("precision: transmittance between two points near the horizon");
  const Atmosphere& atm = in.scene.atmosphere;
  const Texture half_lut = half_round_trip(in.transmittance);
  const double thickness = atm.top_radius_m - atm.bottom_radius_m;
  std::vector<Case> cases;
  for (double e : kElevationsDeg)
    for (double a : kAltitudeFractions)
      for (double f : kPathFractions) cases.push_back({a * thickness, e, f});
  tbb::parallel_for(size_t(0), cases.size(), [&](size_t i) {
    Case& k = cases[i];
    const double r = atm.bottom_radius_m + k.altitude_m, mu = std::sin(k.elevation_deg * kDeg);
    const bool hits = ray_intersects_ground(atm.bottom_radius_m, r, mu);
    const double d = k.fraction * distance_to_nearest_boundary(atm.bottom_radius_m,
                                                               atm.top_radius_m, r, mu, hits);
    if (d < 1.0) return;  // a camera on the ground looking down: no path
    k.valid = true;
    k.reference = glm::exp(-reference_optical_depth(atm, r, mu, d, kTolerance).value);
    k.lut = lookup_transmittance(in.transmittance, atm, r, mu, d, hits);
    k.lut_half = lookup_transmittance(half_lut, atm, r, mu, d, hits);
    const Factors f = exact_factors(atm, r, mu, d, hits);
    k.exact_float = stored_ratio(f, false);
    k.exact_half = stored_ratio(f, true);
    k.underflow_float = underflows(f, false);
    k.underflow_half = underflows(f, true);
  });

  nlohmann::json rows = nlohmann::json::array();
  for (double e : kElevationsDeg) {
    MethodTally lut, lut_half, exact_float, exact_half;
    int count = 0;
    double ref_min = 1.0, ref_max = 0.0;
    for (const Case& k : cases) {
      if (!k.valid || k.elevation_deg != e) continue;
      ++count;
      for (int c = 0; c < 3; ++c) {
        ref_min = std::min(ref_min, k.reference[c]);
        ref_max = std::max(ref_max, k.reference[c]);
      }
      lut.add(k.lut, k.reference, k.underflow_float);
      lut_half.add(k.lut_half, k.reference, k.underflow_half);
      exact_float.add(k.exact_float, k.reference, k.underflow_float);
      exact_half.add(k.exact_half, k.reference, k.underflow_half);
    }
    if (count == 0) continue;
    rows.push_back({{"elevation_deg", e},
                    {"cases", count},
                    {"reference_min", ref_min},
                    {"reference_max", ref_max},
                    {"lut", lut.json()},
                    {"lut_half", lut_half.json()},
                    {"exact_float", exact_float.json()},
                    {"exact_half", exact_half.json()}});
  }
  return {{"what",
           "transmittance between two points as the ratio of two table lookups "
           "(lookup_transmittance) near the horizon"},
          {"altitudes_m",
           {kAltitudeFractions[0] * thickness, kAltitudeFractions[1] * thickness,
            kAltitudeFractions[2] * thickness}},
          {"path_fractions", kPathFractions},
          {"reference",
           fmt::format("exp(-adaptive quadrature of the segment's optical depth), tolerance {:g}",
                       kTolerance)},
          {"relative_floor", kVisibleFloor},
          {"rows", rows}};
}

}  // namespace skybake
