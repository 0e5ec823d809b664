// The multiple-scattering table's error record (pipeline/atmosphere_errors.cpp)
// detects a wrong table: a table whose own record is e0 (max_rel), scaled by
// 1.1, has a record within 1.1 e0 of 0.1, whatever its reference, since
// |1.1 v - ref| / d = |0.1 ref + 1.1 (v - ref)| / d with d >= |ref| the
// floored denominator of core/error_stats.hpp.
#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/scene.hpp"
#include "support/test_atmospheres.hpp"

namespace skybake {
namespace {

TEST(MultiscatteringErrorRecord, ScaledTableMovesMaxRelByItsScale) {
  Scene scene;
  scene.has_atmosphere = true;
  scene.atmosphere = fixtures::earth_atmosphere();
  const Atmosphere& atm = scene.atmosphere;
  const Texture t = bake_transmittance_lut(atm, TransmittanceLutSpec{}, {});
  // A fine table, so that its own record is small next to 0.1.
  MultiscatteringLutSpec fine;
  fine.width = fine.height = 64;
  fine.directions = 128;
  fine.steps = 20;
  fine.sun_mapping = SunMapping::terminator;
  fine.altitude_mapping = AltitudeMapping::quadratic;
  fine.quadrature = DirectionQuadrature::symmetric_gauss;
  const Texture lut = bake_multiscattering_lut(atm, t, fine, {});
  OutputSpec spec;
  spec.product = "multiscattering";
  spec.options = nlohmann::json::object();
  const ProductInputs in = {{"transmittance", &t}};
  // Measured: e0 0.0149; scaled by 1.1, 0.1164 (the table above the reference
  // at its worst point, so the two add); by 0.9, 0.1080.
  const double e0 = measure_multiscattering_error(scene, spec, in, lut)["max_rel"];
  ASSERT_LT(e0, 0.03) << "the fine table should be far closer than the scale tested";
  for (double scale : {1.1, 0.9}) {
    Texture wrong = lut;
    for (float& v : wrong.data) v = float(v * scale);
    const double e = measure_multiscattering_error(scene, spec, in, wrong)["max_rel"];
    const double shift = std::abs(scale - 1.0);
    EXPECT_GE(e, shift - scale * e0 - 1e-5) << scale;
    EXPECT_LE(e, shift + scale * e0 + 1e-5) << scale;
  }
}

}  // namespace
}  // namespace skybake
