// Where float32 and half lose (`skybake report`, docs/report.md): the transmittance
// between two points, which engines take as the ratio of two lookups of the
// transmittance table (lookup_transmittance, Bruneton's GetTransmittance):
//   T(p, q) = T(p -> top) / T(q -> top)   (or of the reversed rays toward the ground).
// Near the horizon both factors are small and nearly equal; the ratio
// amplifies their relative errors, and when the optical depth to the top
// passes ~87 (float32) or ~17 (half) the factors underflow and the ratio is
// lost (0 / 0, returned as 0). Tiny planets bend the horizon ray sharply and
// dense atmospheres reach those depths at modest elevations.
//
// Cases: camera altitudes {0, 1%, 10%} of the atmosphere's thickness x view
// elevations from +10 to -10 degrees x path lengths {1, 10, 50, 100}% of the
// distance to the ground or the top. Reference: exp(-adaptive quadrature of
// the optical depth of the segment). Four ways to get the ratio:
//   lut         the operating-point table (float32 storage + bilinear lookup)
//   lut_half    the same table stored as half
//   exact_float the two factors integrated exactly, rounded to float32 (storage alone)
//   exact_half  the same rounded to half
// Per elevation: max relative error with a floor of 1e-6 on the denominator
// (transmittances below that carry no visible light), max absolute error,
// `lost` = cases with T > 1e-6 where the ratio is off by more than 50%, and
// `underflow` = cases whose denominator is 0 in that storage.
#pragma once

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

nlohmann::json horizon_transmittance_report(const ReportInputs& in);

}  // namespace skybake
