// One segment of the sky's march (sky_integrator.hpp) with its source known
// at the segment's two ends instead of at its midpoint: the aerial record's
// reference on optically thick air (IntegrationOptions::sources_at_ends,
// docs/decisions/error-records.md).
//
// Per channel, with constant extinction sigma over the segment of length dt
// (optical depth x = sigma dt, transmittance t = exp(-x), weight
// W = (1 - t) / sigma) and a source linear between a at the start and b at
// the end:
//   I = integral over [0, dt] of exp(-sigma s) (a + (b - a) s / dt) ds
//     = a W + (b - a) dt m(x),  m(x) = (1 - t (1 + x)) / x^2,
// the same as the constant source read at the weight's centroid (for a linear
// source), which is the midpoint in thin air and about 1 / sigma from the
// start in thick air; a midpoint read there sees a source the view ray's
// light never comes from (Hillaire 2020's energy-conserving segment keeps
// the weight exact, not where it falls). Linear, not exponential, between
// the ends: the sources are bilinear reads of the transmittance and
// multiple-scattering tables, linear along a short segment within a texel,
// and a log-linear fit of a read that starts near 0 (the first texel row
// above a ground at the sun's horizon) loses most of the light.
#pragma once

#include <cmath>

namespace skybake {

// The source term a W + (b - a) dt m(x) of I above for one channel, and W:
// x the segment's optical depth, em = expm1(-x) (t = 1 + em), dt its length.
// One division: W = -dt em / x and dt m(x) = (W - dt t) / x (within 5e-13
// relative down to x = 1e-3, where the difference cancels); below, the
// series of both (errors under x^6 / 5040 < 2e-22).
struct EndSourceWeights {
  double weight;  // W, the constant source's weight (sky_integrator.hpp segment_weights)
  double moment;  // dt m(x), the slope's
};
inline EndSourceWeights end_source_weights(double x, double em, double dt) {
  if (x < 1e-3) {
    const double m =
        0.5 - x * (1.0 / 3.0 - x * (1.0 / 8.0 - x * (1.0 / 30.0 - x * (1.0 / 144.0 - x / 840.0))));
    // W = dt (1 - t) / x by its series too: (1 - e^-x) / x.
    const double w =
        1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0 - x * (1.0 / 120.0 - x / 720.0))));
    return {dt * w, dt * m};
  }
  const double inverse = 1.0 / x;
  const double weight = -dt * em * inverse;
  return {weight, (weight - dt * (1.0 + em)) * inverse};
}

// I above for one channel: a, b the source at the ends.
inline double end_source_integral(double a, double b, const EndSourceWeights& w) {
  return a * w.weight + (b - a) * w.moment;
}

}  // namespace skybake
