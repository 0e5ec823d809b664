// The kernels' SIMD targets (docs/architecture.md "Kernels") that this CPU
// runs, for the one parameterised test per layer that holds every kernel on
// every target to the one-value functions (tests/<layer>/kernels_test.cpp):
// KernelsOnEachTarget's parameter is the target, and SimdTargetAs(t) makes
// every kernel dispatch to t alone for its scope.
#pragma once

#include <cstdint>
#include <string>

#include <gtest/gtest.h>
#include <hwy/targets.h>

namespace skybake::test {

struct SimdTargetAs {
  explicit SimdTargetAs(int64_t target) { hwy::SetSupportedTargetsForTest(target); }
  ~SimdTargetAs() { hwy::SetSupportedTargetsForTest(0); }
  SimdTargetAs(const SimdTargetAs&) = delete;
  SimdTargetAs& operator=(const SimdTargetAs&) = delete;
};

class KernelsOnEachTarget : public testing::TestWithParam<int64_t> {
 protected:
  KernelsOnEachTarget() : as_(GetParam()) {}

 private:
  SimdTargetAs as_;
};

inline std::string simd_target_name(const testing::TestParamInfo<int64_t>& info) {
  return hwy::TargetName(info.param);
}

}  // namespace skybake::test

// In one file of each test executable that has KernelsOnEachTarget tests.
#define SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET()                                   \
  INSTANTIATE_TEST_SUITE_P(Simd, KernelsOnEachTarget,                                   \
                           testing::ValuesIn(hwy::SupportedAndGeneratedTargets()),      \
                           skybake::test::simd_target_name)
