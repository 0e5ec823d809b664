// The settings of the error records' references for Hillaire's tables
// (pipeline/atmosphere_errors.cpp), in one place so that the tests that hold
// each reference to a much denser one (tests/report/bake_error_test.cpp,
// tests/pipeline/error_references_test.cpp) test the settings the bake uses.
//
// Query counts: the report's --quick counts (report/*.cpp), so the bake's
// points are the first of the report's. References: the fewest steps or
// directions at which the measured max_rel and rms_rel of the shipped and
// extreme presets stop moving in their third digit, each checked against a
// much denser rule (docs/decisions/error-records.md,
// "Error records at a tenth of the bake").
#pragma once

#include <algorithm>
#include <cmath>

#include "atmosphere/sky_integrator.hpp"
#include "verify/psi_ms_reference.hpp"

namespace skybake {

constexpr int kTransmittanceQueries = 512;
// 3-point Gauss segments from scratch (compute_transmittances_to_top); the
// table's 6 segments of 8 points are a rule it does not share. 24 steps:
// within 2e-5 of 400 steps at the 512 points of every shipped and extreme
// preset, a thousandth of the smallest table error among them.
constexpr int kTransmittanceReferenceSteps = 24;

constexpr int kMultiscatteringQueries = 24;
// 6 + 24 zenith cosines x 4 azimuths (x 2 mirrored), 32 graded segments:
// 3.5e-3 max_rel of a rule 4x finer in zenith and steps and 2x in azimuth on
// Earth, 1.2e-2 under 100x Rayleigh (tests/atmosphere/
// psi_ms_reference_test.cpp), 1-2% of the tables' own errors there; the
// 6-azimuth, 40-segment rule halved that for twice the time, which put the
// record above a tenth of the table's AVX2 bake (docs/decisions/error-records.md).
constexpr PointQuadrature kMultiscatteringReference = {6, 24, 4, 32};

constexpr int kSkyviewQueries = 128;
// The march of the table's step distribution with 100 and 50 segments, cut
// at the planet's shadow, extrapolated to zero step
// (extrapolated_scattered_luminance): 150 segments a query where the plain
// march took 300 for 2-7x the error (tests/pipeline/error_references_test.cpp).
constexpr int kSkyviewReferenceSteps = 50;

constexpr int kAerialQueries = 256;
// Steps over the whole depth range; a query marches as many as its distance
// needs for the same step length (at least kAerialMinSteps), so a short
// query costs less and no query is marched with longer steps than a
// full-range one. The sun's transmittance and Psi_ms are read at the
// segments' ends and integrated linear across each against its exponential
// weight (IntegrationOptions::sources_at_ends): on 1000x Rayleigh the
// midpoint march of 100 steps was 0.27 / 0.10 (max / rms relative) off a 32x
// denser march, 2% / 13% of the table's own error, this one at 80 steps is
// 1e-2 / 1e-3; on every shipped and extreme preset it is within 1.5% of the
// table's error, for the CPU of the 100 midpoint steps (tests/pipeline/
// error_references_test.cpp; docs/decisions/error-records.md).
constexpr int kAerialReferenceSteps = 80;
constexpr int kAerialMinSteps = 8;

// The segments of an aerial query `distance_m` long: `steps_over_range` over
// the depth range, in proportion, at least kAerialMinSteps.
inline int aerial_reference_segments(double distance_m, double depth_range_m,
                                     int steps_over_range = kAerialReferenceSteps) {
  return std::max(kAerialMinSteps, int(std::ceil(steps_over_range * distance_m / depth_range_m)));
}

// The march options of the aerial record's reference (the multiple-
// scattering table's mapping is the caller's).
inline IntegrationOptions aerial_reference_options() {
  IntegrationOptions options;
  options.block_exponentials = true;
  options.sources_at_ends = true;
  return options;
}

}  // namespace skybake
