// The error a bake records for the Bruneton family is what `skybake report
// --quick` measures: earth_precomputed's scattering, irradiance and
// gathering sum within 2x of the report's operating points (the check of
// bake_error_test.cpp, whose 4D tables and ladders put it in this tier).
#include <gtest/gtest.h>

#include "report/bake_error_checks.hpp"

namespace skybake {
namespace {

using namespace bake_error;

TEST(BakeErrorAgreesWithReport, EarthPrecomputed) {
  expect_within_2x(bake("earth_precomputed"), {"scattering", "irradiance", "gathering_sum"});
}

}  // namespace
}  // namespace skybake
