// The density's Mie loop over lanes (Highway, every target from one
// source): pair j adds into lane j % 8 of each sum on every target (with
// fewer than 8 lanes, the sums are several vectors), so the same bits. See
// the header.
#include "atmosphere/kernels/mie_batch.hpp"

#include <algorithm>
#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "atmosphere/kernels/mie_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace skybake {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The kernel's lanes: eight pairs (one block), or sixteen (two blocks) where
// the vectors hold sixteen floats, so that the square roots and the division
// run at the full width.
#if HWY_TARGET == HWY_AVX3
using KernelTag = hn::ScalableTag<float>;
#else
using KernelTag = hn::CappedTag<float, MieBatch::kLanes>;
#endif
// The sums' lanes: at most eight, so that pair j adds into lane j % 8.
using SumTag = hn::CappedTag<float, MieBatch::kLanes>;

// Part i of the kernel's lanes as the sums' lanes.
HWY_INLINE hn::Vec<SumTag> SumLanes(hn::Vec<KernelTag> p, size_t i) {
#if HWY_TARGET == HWY_AVX3
  return i == 0 ? hn::LowerHalf(p) : hn::UpperHalf(SumTag(), p);
#else
  (void)i;
  return p;
#endif
}

// lanes[c][l]: the sum of channel c (R, G, B, weight) in lane l.
void MieLaneSums(const MieKernel& k, const glm::dvec3& v, const float* x, const float* y,
                 const float* z, const float* blocks, size_t n,
                 float lanes[4][MieBatch::kLanes]) {
  const KernelTag d;
  const SumTag ds;
  using V = hn::Vec<KernelTag>;
  using S = hn::Vec<SumTag>;
  constexpr size_t kMax = MieBatch::kLanes;
  const size_t N = hn::Lanes(d), NS = hn::Lanes(ds);
  const V one = hn::Set(d, 1.0f), zero = hn::Zero(d);
  const V a = hn::Set(d, float(k.a)), b = hn::Set(d, float(k.b));
  const V cs = hn::Set(d, k.cornette_shanks ? 1.0f : 0.0f);
  const V vx = hn::Set(d, float(v.x)), vy = hn::Set(d, float(v.y)), vz = hn::Set(d, float(v.z));
  S acc[4][kMax];
  for (auto& c : acc)
    for (size_t h = 0; h < kMax / NS; ++h) c[h] = hn::Zero(ds);
  // Past the last pair (n is a multiple of 8): lanes of weight 0, not added.
  auto load = [&](const float* p, size_t j) {
    return j + N <= n ? hn::LoadU(d, p + j) : hn::MaskedLoad(hn::FirstN(d, n - j), d, p + j);
  };
  for (size_t j = 0; j < n; j += N) {
    const V in_plane = hn::Add(hn::Mul(vx, load(x, j)), hn::Mul(vz, load(z, j)));
    const V across = hn::Mul(vy, load(y, j));
    const V cp = hn::Add(in_plane, across), cm = hn::Sub(in_plane, across);
    const V wp = hn::Add(a, hn::Mul(b, hn::Max(hn::Sub(one, cp), zero)));
    const V wm = hn::Add(a, hn::Mul(b, hn::Max(hn::Sub(one, cm), zero)));
    const V qp = hn::Mul(wp, hn::Sqrt(wp)), qm = hn::Mul(wm, hn::Sqrt(wm));
    const V np = hn::Add(one, hn::Mul(cs, hn::Mul(cp, cp)));
    const V nm = hn::Add(one, hn::Mul(cs, hn::Mul(cm, cm)));
    const V p = hn::Div(hn::Add(hn::Mul(np, qm), hn::Mul(nm, qp)), hn::Mul(qp, qm));
    for (size_t i = 0; i < N / NS && j + i * NS < n; ++i) {
      const size_t at = j + i * NS, h = at % kMax / NS;
      const S part = SumLanes(p, i);
      for (int c = 0; c < 4; ++c)
        acc[c][h] = hn::Add(acc[c][h], hn::Mul(part, hn::LoadU(ds, blocks + MieBatch::field(c, at))));
    }
  }
  for (int c = 0; c < 4; ++c)
    for (size_t h = 0; h < kMax / NS; ++h) hn::StoreU(acc[c][h], ds, lanes[c] + h * NS);
}

}  // namespace HWY_NAMESPACE
}  // namespace skybake
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skybake {

HWY_EXPORT(MieLaneSums);

MieBatch::MieBatch(const SphereGrid& grid) {
  const int half = grid.azimuths / 2;
  for (int l = 0; l < grid.bands; ++l)
    for (int m = 0; m < half; ++m) first.push_back(size_t(l) * grid.azimuths + m);
  n = (first.size() + kLanes - 1) / kLanes * kLanes;
  for (auto* v : {&x, &y, &z}) v->assign(n, 0.0f);
  blocks.assign(4 * n, 0.0f);
  for (size_t k = 0; k < first.size(); ++k) {
    const glm::dvec3& w = grid.directions[first[k]];
    x[k] = float(w.x);
    y[k] = float(w.y);
    z[k] = float(w.z);
    blocks[field(3, k)] = float(grid.solid_angle[first[k]]);
  }
  grid_azimuths = grid.azimuths;
}

void MieBatch::set_field(const std::vector<glm::dvec3>& L) {
  for (size_t k = 0; k < first.size(); ++k) {
    const size_t j = first[k], mirror = j + grid_azimuths - 1 - 2 * (j % grid_azimuths);
    const glm::dvec3 mean = 0.5 * (L[j] + L[mirror]);
    const float dw = blocks[field(3, k)];
    for (int c = 0; c < 3; ++c) blocks[field(c, k)] = float(mean[c] * dw);
  }
}

void MieBatch::sums(const MieKernel& k, const glm::dvec3& v, double out[4]) const {
  float lanes[4][kLanes];
  HWY_DYNAMIC_DISPATCH(MieLaneSums)(k, v, x.data(), y.data(), z.data(), blocks.data(), n, lanes);
  for (int c = 0; c < 4; ++c) {
    const float* s = lanes[c];
    out[c] = ((double(s[0]) + s[1]) + (double(s[2]) + s[3])) +
             ((double(s[4]) + s[5]) + (double(s[6]) + s[7]));
  }
}

}  // namespace skybake
#endif  // HWY_ONCE
