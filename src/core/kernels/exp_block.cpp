// exp_block and expm1_block over lanes (Highway, every target from one
// source): per lane exp_one's and expm1_one's IEEE operations on the same
// operands in the same order, 2^k built in the exponent bits as there, so
// every target gives their bits (tests/core/kernels_test.cpp). See the
// header.
#include "core/kernels/exp_block.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/kernels/exp_block.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// exp_reduce in each lane.
template <class D>
struct ExpReducedLanes {
  hn::Vec<D> y, scale;
};
template <class D>
HWY_INLINE ExpReducedLanes<D> ExpReduceLanes(D d, hn::Vec<D> v) {
  const hn::Vec<D> shifter = hn::Set(d, kExpShifter);
  const hn::Vec<D> t = hn::Add(hn::Mul(v, hn::Set(d, kExpLog2e)), shifter);
  const hn::Vec<D> k = hn::Sub(t, shifter);
  const hn::Vec<D> y = hn::Sub(hn::Sub(v, hn::Mul(k, hn::Set(d, kExpLn2Hi))),
                               hn::Mul(k, hn::Set(d, kExpLn2Lo)));
  const hn::RebindToUnsigned<D> du;
  const auto bits = hn::BitCast(du, t);
  const auto scale_bits = hn::ShiftLeft<52>(hn::Add(bits, hn::Set(du, uint64_t{1023})));
  return {y, hn::BitCast(d, scale_bits)};
}

// a + y b, the polynomials' pairs, in exp_one's operand order.
template <class D>
HWY_INLINE hn::Vec<D> PairLanes(D d, double a, hn::Vec<D> y, double b) {
  return hn::Add(hn::Set(d, a), hn::Mul(y, hn::Set(d, b)));
}

// exp_one in each lane of x[j, j + Lanes(d)).
template <class D>
HWY_INLINE void ExpLanes(D d, double* x, size_t j) {
  const ExpReducedLanes<D> r = ExpReduceLanes(d, hn::LoadU(d, x + j));
  const hn::Vec<D> y = r.y, y2 = hn::Mul(y, y), y4 = hn::Mul(y2, y2);
  const hn::Vec<D> c01 = hn::Add(hn::Set(d, 1.0), y), c23 = PairLanes(d, 0.5, y, 1.0 / 6.0);
  const hn::Vec<D> c45 = PairLanes(d, 1.0 / 24.0, y, 1.0 / 120.0);
  const hn::Vec<D> c67 = PairLanes(d, 1.0 / 720.0, y, 1.0 / 5040.0);
  const hn::Vec<D> c89 = PairLanes(d, 1.0 / 40320.0, y, 1.0 / 362880.0);
  const hn::Vec<D> c1011 = PairLanes(d, 1.0 / 3628800.0, y, 1.0 / 39916800.0);
  const hn::Vec<D> c1213 = PairLanes(d, 1.0 / 479001600.0, y, 1.0 / 6227020800.0);
  const hn::Vec<D> c0_3 = hn::Add(c01, hn::Mul(y2, c23)), c4_7 = hn::Add(c45, hn::Mul(y2, c67));
  const hn::Vec<D> c8_11 = hn::Add(c89, hn::Mul(y2, c1011));
  const hn::Vec<D> p = hn::Add(
      c0_3, hn::Mul(y4, hn::Add(c4_7, hn::Mul(y4, hn::Add(c8_11, hn::Mul(y4, c1213))))));
  hn::StoreU(hn::Mul(p, r.scale), d, x + j);
}

// expm1_one in each lane of x[j, j + Lanes(d)).
template <class D>
HWY_INLINE void Expm1Lanes(D d, double* x, size_t j) {
  const ExpReducedLanes<D> r = ExpReduceLanes(d, hn::LoadU(d, x + j));
  const hn::Vec<D> y = r.y, y2 = hn::Mul(y, y), y4 = hn::Mul(y2, y2), y8 = hn::Mul(y4, y4);
  const hn::Vec<D> c01 = hn::Add(hn::Set(d, 1.0), hn::Mul(y, hn::Set(d, 0.5)));
  const hn::Vec<D> c23 = PairLanes(d, 1.0 / 6.0, y, 1.0 / 24.0);
  const hn::Vec<D> c45 = PairLanes(d, 1.0 / 120.0, y, 1.0 / 720.0);
  const hn::Vec<D> c67 = PairLanes(d, 1.0 / 5040.0, y, 1.0 / 40320.0);
  const hn::Vec<D> c89 = PairLanes(d, 1.0 / 362880.0, y, 1.0 / 3628800.0);
  const hn::Vec<D> c1011 = PairLanes(d, 1.0 / 39916800.0, y, 1.0 / 479001600.0);
  const hn::Vec<D> c12 = hn::Set(d, 1.0 / 6227020800.0);
  const hn::Vec<D> q =
      hn::Add(hn::Add(hn::Add(c01, hn::Mul(y2, c23)), hn::Mul(y4, hn::Add(c45, hn::Mul(y2, c67)))),
              hn::Mul(y8, hn::Add(hn::Add(c89, hn::Mul(y2, c1011)), hn::Mul(y4, c12))));
  const hn::Vec<D> scale = r.scale;
  hn::StoreU(hn::Add(hn::Mul(scale, hn::Mul(y, q)), hn::Sub(scale, hn::Set(d, 1.0))), d, x + j);
}

// Whole vectors, then the rest one lane at a time.
void ExpBlock(double* x, size_t n) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  size_t j = 0;
  for (; j + hn::Lanes(d) <= n; j += hn::Lanes(d)) ExpLanes(d, x, j);
  for (; j < n; ++j) ExpLanes(d1, x, j);
}

void Expm1Block(double* x, size_t n) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  size_t j = 0;
  for (; j + hn::Lanes(d) <= n; j += hn::Lanes(d)) Expm1Lanes(d, x, j);
  for (; j < n; ++j) Expm1Lanes(d1, x, j);
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(ExpBlock);
HWY_EXPORT(Expm1Block);

void exp_block(double* x, size_t n) { HWY_DYNAMIC_DISPATCH(ExpBlock)(x, n); }

void expm1_block(double* x, size_t n) { HWY_DYNAMIC_DISPATCH(Expm1Block)(x, n); }

}  // namespace skybake
#endif  // HWY_ONCE
