// worley_nearest_row over lanes (Highway, every target from one source):
// worley3_f1's single-precision expressions per lane, two accumulators to
// halve the chain of dependent minima (a minimum is exact: the split changes
// no bit). See the header.
#include "noise/kernels/worley_nearest.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "noise/kernels/worley_nearest.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void WorleyNearestRow(const float* frac, const float* cell_f, const int* cell, int size,
                      const float* ox, const float* q, const float* col, const int* start,
                      float* out) {
  const hn::CappedTag<float, 8> d;  // frac and cell_f hold 7 lanes past the row
  using V = hn::Vec<decltype(d)>;
  const int lanes = int(hn::Lanes(d));
  const V one = hn::Set(d, 1.0f);
  for (int x0 = 0; x0 < size; x0 += lanes) {
    const int last = std::min(x0 + lanes - 1, size - 1);
    const int k_end = start[cell[last] + 3];
    const V fs = hn::LoadU(d, frac + x0), cs = hn::LoadU(d, cell_f + x0);
    // d2 of the lanes to candidate k: the shift col - cell per lane.
    auto d2 = [&](int k) {
      const V dx = hn::Sub(fs, hn::Add(hn::Sub(hn::Set(d, col[k]), cs), hn::Set(d, ox[k])));
      return hn::Add(hn::Mul(dx, dx), hn::Set(d, q[k]));
    };
    V b0 = one, b1 = one;
    int k = start[cell[x0]];
    for (; k + 1 < k_end; k += 2) {
      b0 = hn::Min(d2(k), b0);
      b1 = hn::Min(d2(k + 1), b1);
    }
    if (k < k_end) b0 = hn::Min(d2(k), b0);
    const V value = hn::Sub(one, hn::Sqrt(hn::Min(b0, b1)));
    if (x0 + lanes <= size) {
      hn::StoreU(value, d, out + x0);
    } else {
      HWY_ALIGN float tail[hn::MaxLanes(d)];
      hn::Store(value, d, tail);
      std::copy(tail, tail + (size - x0), out + x0);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(WorleyNearestRow);

void worley_nearest_row(const float* frac, const float* cell_f, const int* cell, int size,
                        const float* ox, const float* q, const float* col, const int* start,
                        float* out) {
  HWY_DYNAMIC_DISPATCH(WorleyNearestRow)(frac, cell_f, cell, size, ox, q, col, start, out);
}

}  // namespace skybake
#endif  // HWY_ONCE
