// The core layer's kernels on every SIMD target this CPU runs against the
// one-value functions they stand for, bit for bit (docs/architecture.md
// "Kernels"): exp_block and expm1_block against exp_one and expm1_one.
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/kernels/exp_block.hpp"
#include "support/simd_targets.hpp"

namespace skybake {
namespace {

using test::KernelsOnEachTarget;

// Exponents over the precondition's range, and many in the narrow range the
// marches take (-40 to 1), at every length and alignment a target's whole
// vectors and its tail can take.
std::vector<double> exponents(uint64_t seed, size_t n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> wide(-708.0, 708.0), narrow(-40.0, 1.0);
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = i % 3 ? narrow(rng) : wide(rng);
  for (double v : {0.0, -0.0, 1e-300, -1e-300, 708.0, -708.0}) x.push_back(v);
  return x;
}

TEST_P(KernelsOnEachTarget, ExpBlockIsExpOne) {
  const std::vector<double> x = exponents(11, 4099);
  for (size_t offset : {0u, 1u, 3u})
    for (size_t n : {size_t(0), size_t(1), size_t(3), size_t(5), size_t(17), x.size() - 3}) {
      std::vector<double> a(x.begin() + offset, x.begin() + offset + n);
      exp_block(a.data(), n);
      for (size_t i = 0; i < n; ++i) {
        const double one = exp_one(x[offset + i]);
        ASSERT_EQ(std::memcmp(&a[i], &one, sizeof one), 0) << "x = " << x[offset + i];
      }
    }
}

TEST_P(KernelsOnEachTarget, Expm1BlockIsExpm1One) {
  const std::vector<double> x = exponents(5, 4099);
  for (size_t offset : {0u, 2u})
    for (size_t n : {size_t(1), size_t(3), size_t(5), size_t(16), x.size() - 2}) {
      std::vector<double> a(x.begin() + offset, x.begin() + offset + n);
      expm1_block(a.data(), n);
      for (size_t i = 0; i < n; ++i) {
        const double one = expm1_one(x[offset + i]);
        ASSERT_EQ(std::memcmp(&a[i], &one, sizeof one), 0) << "x = " << x[offset + i];
      }
    }
}

SKYBAKE_INSTANTIATE_KERNELS_ON_EACH_TARGET();

}  // namespace
}  // namespace skybake
