// The row blend over lanes (Highway, every target from one source): the
// floats of the rows (R, G, B and the pad of each texel alike) in the lanes,
// each (w0 a + w1 b) + (w2 c + w3 d), so the same bits on every target
// (tests/atmosphere/kernels_test.cpp). See the header.
#include "atmosphere/kernels/row_blend.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/row_blend.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Floats [i, i + Lanes(d)) of the blend.
template <class D>
HWY_INLINE void Blend(D d, const float* const rows[4], const float w[4], size_t i, float* out) {
  const hn::Vec<D> ab = hn::Add(hn::Mul(hn::Set(d, w[0]), hn::LoadU(d, rows[0] + i)),
                                hn::Mul(hn::Set(d, w[1]), hn::LoadU(d, rows[1] + i)));
  const hn::Vec<D> cd = hn::Add(hn::Mul(hn::Set(d, w[2]), hn::LoadU(d, rows[2] + i)),
                                hn::Mul(hn::Set(d, w[3]), hn::LoadU(d, rows[3] + i)));
  hn::StoreU(hn::Add(ab, cd), d, out + i);
}

void BlendRows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  const float* const r[4] = {rows[0][0].v, rows[1][0].v, rows[2][0].v, rows[3][0].v};
  const size_t floats = 4 * size_t(n);
  // Whole vectors, then (8 lanes, an odd n) the last texel: a texel is four
  // floats.
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 4> d4;
  size_t i = 0;
  for (; i + hn::Lanes(d) <= floats; i += hn::Lanes(d)) Blend(d, r, w, i, out[0].v);
  for (; i < floats; i += hn::Lanes(d4)) Blend(d4, r, w, i, out[0].v);
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(BlendRows);

void blend_rows(const Rgb4* const rows[4], const float w[4], int n, Rgb4* out) {
  HWY_DYNAMIC_DISPATCH(BlendRows)(rows, w, n, out);
}

}  // namespace skybake
#endif  // HWY_ONCE
