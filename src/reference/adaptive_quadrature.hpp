// Globally adaptive Gauss-Kronrod quadrature (G7-K15) of a scalar or RGB
// integrand on [a, b], to a requested absolute / relative tolerance, with
// the interval first cut at given breakpoints (density kinks, the perigee,
// the edge of the planet's shadow). The scheme of QUADPACK's QAG (Piessens
// et al. 1983): keep a list of intervals, each with a 15-point Kronrod value
// and an error estimate; bisect the interval with the largest (scaled) error
// until the summed error meets the tolerance in every channel.
//
// Why it can be trusted: the 15-point Kronrod rule integrates polynomials
// of degree <= 22 exactly, its embedded 7-point Gauss rule those of degree
// <= 13 (tested). The error estimate of an interval is the plain difference
// |K15 - G7|, the error of the lower-order rule, which for a smooth integrand
// over-estimates the error of K15 by orders of magnitude (QUADPACK scales it
// down; we do not), floored at 50 ulp of integral of |f| for rounding. What
// no sampling-based quadrature can promise: a feature narrower than the node
// spacing that every node misses (a spike) is invisible to it; callers
// split at every place where the integrand is not smooth instead.
//
// Cost: 15 evaluations per interval; picking the worst interval scans the
// list, so the work is quadratic in the interval count. Meant for smooth
// pieces that need tens to hundreds of intervals, not for pathological ones
// (max_evaluations bounds them and `converged` reports the failure).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

namespace skybake {

struct QuadratureOptions {
  double absolute_tolerance = 0.0;    // per channel, units of the integral
  double relative_tolerance = 1e-10;  // per channel, relative to |integral|
  int64_t max_evaluations = 200000;   // integrand evaluations before giving up
};

// The integral of a scalar (double) or RGB (glm::dvec3) integrand.
template <typename V>
struct QuadratureResult {
  V value = V(0.0);         // the integral
  V error = V(0.0);         // estimated absolute error, per channel
  int64_t evaluations = 0;  // integrand evaluations spent
  bool converged = false;   // error <= max(absolute, relative |value|) in every channel
};

namespace quadrature_detail {

// Per-channel access, so one algorithm serves double and dvec3.
template <typename V>
struct Channels;
template <>
struct Channels<double> {
  static constexpr int count = 1;
  static double get(const double& v, int) { return v; }
  static void set(double& v, int, double x) { v = x; }
};
template <>
struct Channels<glm::dvec3> {
  static constexpr int count = 3;
  static double get(const glm::dvec3& v, int c) { return v[c]; }
  static void set(glm::dvec3& v, int c, double x) { v[c] = x; }
};

// Kronrod nodes on [-1, 1] (the positive half, the centre last; the odd
// indices 1, 3, 5 are the 7-point Gauss nodes, with the centre) and weights,
// QUADPACK qk15.
constexpr double kKronrodNodes[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr double kKronrodWeights[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// Gauss weights for the nodes kKronrodNodes[1], [3], [5] and the centre.
constexpr double kGaussWeights[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <typename V>
struct Interval {
  double a = 0.0, b = 0.0;
  V value = V(0.0), error = V(0.0);
  bool splittable = true;
};

// K15 on [a, b]; error = max(|K15 - G7|, 50 eps * integral of |f|) per channel.
template <typename V, typename F>
Interval<V> gauss_kronrod_15(F& f, double a, double b) {
  using C = Channels<V>;
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  const V f_centre = f(centre);
  V kronrod = kKronrodWeights[7] * f_centre, gauss = kGaussWeights[3] * f_centre;
  V absolute(0.0);
  for (int c = 0; c < C::count; ++c)
    C::set(absolute, c, kKronrodWeights[7] * std::abs(C::get(f_centre, c)));
  for (int j = 0; j < 7; ++j) {
    const V f_left = f(centre - half * kKronrodNodes[j]);
    const V f_right = f(centre + half * kKronrodNodes[j]);
    kronrod += kKronrodWeights[j] * (f_left + f_right);
    if (j % 2 == 1) gauss += kGaussWeights[j / 2] * (f_left + f_right);
    for (int c = 0; c < C::count; ++c)
      C::set(absolute, c,
             C::get(absolute, c) +
                 kKronrodWeights[j] * (std::abs(C::get(f_left, c)) + std::abs(C::get(f_right, c))));
  }
  Interval<V> out;
  out.a = a;
  out.b = b;
  out.value = half * kronrod;
  const double roundoff = 50.0 * std::numeric_limits<double>::epsilon();
  for (int c = 0; c < C::count; ++c) {
    const double difference = std::abs(half * (C::get(kronrod, c) - C::get(gauss, c)));
    C::set(out.error, c, std::max(difference, roundoff * std::abs(half) * C::get(absolute, c)));
  }
  return out;
}

template <typename V>
V sum_values(const std::vector<Interval<V>>& intervals) {
  V total(0.0);
  for (const Interval<V>& i : intervals) total += i.value;
  return total;
}
template <typename V>
V sum_errors(const std::vector<Interval<V>>& intervals) {
  V total(0.0);
  for (const Interval<V>& i : intervals) total += i.error;
  return total;
}

}  // namespace quadrature_detail

// Integral of f over [a, b] (b < a gives minus the integral over [b, a]).
// f maps a double to a double or a glm::dvec3. `breakpoints` strictly inside
// (a, b) cut the interval before any evaluation (others are ignored), so a
// kink or a jump there costs nothing. Deterministic; calls f from the
// calling thread only.
template <typename F>
auto integrate_adaptive(F&& f, double a, double b, const QuadratureOptions& options = {},
                        std::vector<double> breakpoints = {})
    -> QuadratureResult<std::decay_t<std::invoke_result_t<F&, double>>> {
  using V = std::decay_t<std::invoke_result_t<F&, double>>;
  using C = quadrature_detail::Channels<V>;
  using Interval = quadrature_detail::Interval<V>;
  QuadratureResult<V> result;
  if (a == b) {
    result.converged = true;
    return result;
  }
  if (b < a) {
    result = integrate_adaptive(f, b, a, options, std::move(breakpoints));
    result.value = -result.value;
    return result;
  }
  breakpoints.erase(std::remove_if(breakpoints.begin(), breakpoints.end(),
                                   [&](double x) { return !(x > a && x < b); }),
                    breakpoints.end());
  std::sort(breakpoints.begin(), breakpoints.end());
  breakpoints.erase(std::unique(breakpoints.begin(), breakpoints.end()), breakpoints.end());
  breakpoints.insert(breakpoints.begin(), a);
  breakpoints.push_back(b);

  std::vector<Interval> intervals;
  for (size_t i = 0; i + 1 < breakpoints.size(); ++i) {
    intervals.push_back(
        quadrature_detail::gauss_kronrod_15<V>(f, breakpoints[i], breakpoints[i + 1]));
    result.evaluations += 15;
  }
  for (;;) {
    const V value = quadrature_detail::sum_values(intervals);
    const V error = quadrature_detail::sum_errors(intervals);
    double tolerance[C::count];
    bool met = true;
    for (int c = 0; c < C::count; ++c) {
      tolerance[c] = std::max(options.absolute_tolerance,
                              options.relative_tolerance * std::abs(C::get(value, c)));
      met = met && C::get(error, c) <= tolerance[c];
    }
    result.value = value;
    result.error = error;
    if (met) {
      result.converged = true;
      break;
    }
    if (result.evaluations + 30 > options.max_evaluations) break;
    // The interval whose error uses the largest share of its channel's tolerance.
    int worst = -1;
    double worst_share = -1.0;
    for (size_t i = 0; i < intervals.size(); ++i) {
      if (!intervals[i].splittable) continue;
      double share = 0.0;
      for (int c = 0; c < C::count; ++c)
        share = std::max(share, C::get(intervals[i].error, c) /
                                    std::max(tolerance[c], std::numeric_limits<double>::min()));
      if (share > worst_share) {
        worst_share = share;
        worst = int(i);
      }
    }
    if (worst < 0) break;  // every interval is down to rounding width
    const double lo = intervals[worst].a, hi = intervals[worst].b, mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi) || hi - lo <= 64.0 * std::numeric_limits<double>::epsilon() *
                                                  std::max(std::abs(lo), std::abs(hi))) {
      intervals[worst].splittable = false;
      continue;
    }
    intervals[worst] = quadrature_detail::gauss_kronrod_15<V>(f, lo, mid);
    intervals.push_back(quadrature_detail::gauss_kronrod_15<V>(f, mid, hi));
    result.evaluations += 30;
  }
  return result;
}

}  // namespace skybake
