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

// The kernel k(v . w) of the pairs from j (both directions of each pair,
// their two phases over one division), Lanes(KernelTag) of them.
struct MieLanesConstants {
  hn::Vec<KernelTag> one, zero, a, b, cs, vx, vy, vz;
};
HWY_INLINE hn::Vec<KernelTag> MiePairKernel(const MieLanesConstants& k, const float* x,
                                            const float* y, const float* z, size_t j, size_t n) {
  const KernelTag d;
  using V = hn::Vec<KernelTag>;
  // Past the last pair (n is a multiple of 8): lanes of weight 0, not added.
  const auto load = [&](const float* p) {
    return j + hn::Lanes(d) <= n ? hn::LoadU(d, p + j)
                                 : hn::MaskedLoad(hn::FirstN(d, n - j), d, p + j);
  };
  const V in_plane = hn::Add(hn::Mul(k.vx, load(x)), hn::Mul(k.vz, load(z)));
  const V across = hn::Mul(k.vy, load(y));
  const V cp = hn::Add(in_plane, across), cm = hn::Sub(in_plane, across);
  const V wp = hn::Add(k.a, hn::Mul(k.b, hn::Max(hn::Sub(k.one, cp), k.zero)));
  const V wm = hn::Add(k.a, hn::Mul(k.b, hn::Max(hn::Sub(k.one, cm), k.zero)));
  const V qp = hn::Mul(wp, hn::Sqrt(wp)), qm = hn::Mul(wm, hn::Sqrt(wm));
  const V np = hn::Add(k.one, hn::Mul(k.cs, hn::Mul(cp, cp)));
  const V nm = hn::Add(k.one, hn::Mul(k.cs, hn::Mul(cm, cm)));
  return hn::Div(hn::Add(hn::Mul(np, qm), hn::Mul(nm, qp)), hn::Mul(qp, qm));
}

// The four sums (R, G, B, weight) of some lanes of a block of pairs, as
// named vectors: an array indexed in the loop, GCC keeps them on the stack
// and loads and stores them every step.
struct MieSums {
  hn::Vec<SumTag> r, g, b, w;
};
// sums += p times the fields of the pairs from `at`.
HWY_INLINE void AddMieBlock(hn::Vec<SumTag> p, const float* blocks, size_t at, MieSums& sums) {
  const SumTag ds;
  sums.r = hn::Add(sums.r, hn::Mul(p, hn::LoadU(ds, blocks + MieBatch::field(0, at))));
  sums.g = hn::Add(sums.g, hn::Mul(p, hn::LoadU(ds, blocks + MieBatch::field(1, at))));
  sums.b = hn::Add(sums.b, hn::Mul(p, hn::LoadU(ds, blocks + MieBatch::field(2, at))));
  sums.w = hn::Add(sums.w, hn::Mul(p, hn::LoadU(ds, blocks + MieBatch::field(3, at))));
}

// out[c] = ((s0 + s1) + (s2 + s3)) + ((s4 + s5) + (s6 + s7)) in double, s
// the eight lanes of channel c's sums: on AVX-512 the four channels' lanes
// widened to two vectors of eight doubles and added pairwise across them
// (each sum's operands and order as written), else one channel at a time.
HWY_INLINE void AddMieLanes(const MieSums* acc, double out[4]) {
#if HWY_TARGET == HWY_AVX3
  const hn::ScalableTag<double> dd;
  const auto rg = [&](hn::Vec<SumTag> a, hn::Vec<SumTag> b) {  // pairs (0 1) .. (6 7)
    const auto wa = hn::PromoteTo(dd, a), wb = hn::PromoteTo(dd, b);
    return hn::Add(hn::ConcatEven(dd, wb, wa), hn::ConcatOdd(dd, wb, wa));
  };
  const auto rg2 = rg(acc[0].r, acc[0].g), bw2 = rg(acc[0].b, acc[0].w);
  // R01 R23 R45 R67 G01 .. and B01 .. W67 -> R0123 R4567 G0123 G4567 B.. W..
  const auto quads = hn::Add(hn::ConcatEven(dd, bw2, rg2), hn::ConcatOdd(dd, bw2, rg2));
  const auto sums = hn::Add(hn::ConcatEven(dd, quads, quads), hn::ConcatOdd(dd, quads, quads));
  hn::StoreU(hn::LowerHalf(sums), hn::Half<decltype(dd)>(), out);
  return;
#endif
  const SumTag ds;
  constexpr size_t NS = hn::MaxLanes(SumTag());
  HWY_ALIGN float lanes[4][MieBatch::kLanes];
  for (size_t h = 0; h < MieBatch::kLanes / NS; ++h) {
    hn::Store(acc[h].r, ds, lanes[0] + h * NS);
    hn::Store(acc[h].g, ds, lanes[1] + h * NS);
    hn::Store(acc[h].b, ds, lanes[2] + h * NS);
    hn::Store(acc[h].w, ds, lanes[3] + h * NS);
  }
  for (int c = 0; c < 4; ++c) {
    const float* s = lanes[c];
    out[c] = ((double(s[0]) + s[1]) + (double(s[2]) + s[3])) +
             ((double(s[4]) + s[5]) + (double(s[6]) + s[7]));
  }
}

// MieBatch::sums: kSums vectors of NS lanes per channel hold the eight lanes
// of its sums, pair j adding into lane j % 8.
void MieLaneSums(const MieKernel& kernel, const glm::dvec3& v, const float* x, const float* y,
                 const float* z, const float* blocks, size_t n, double out[4]) {
  const KernelTag d;
  const SumTag ds;
  constexpr size_t kMax = MieBatch::kLanes;
  constexpr size_t N = hn::MaxLanes(KernelTag()), NS = hn::MaxLanes(SumTag());
  constexpr size_t kSums = kMax / NS;  // sum vectors per channel
  const MieLanesConstants k{hn::Set(d, 1.0f),
                            hn::Zero(d),
                            hn::Set(d, float(kernel.a)),
                            hn::Set(d, float(kernel.b)),
                            hn::Set(d, kernel.cornette_shanks ? 1.0f : 0.0f),
                            hn::Set(d, float(v.x)),
                            hn::Set(d, float(v.y)),
                            hn::Set(d, float(v.z))};
  MieSums acc[kSums];
  for (MieSums& a : acc) a = MieSums{hn::Zero(ds), hn::Zero(ds), hn::Zero(ds), hn::Zero(ds)};
#if HWY_TARGET == HWY_AVX3
  // Sixteen pairs a step: two blocks into the one vector of sums.
  static_assert(N == 2 * kMax && kSums == 1, "two blocks of eight a step");
  for (size_t j = 0; j < n; j += N) {
    const hn::Vec<KernelTag> p = MiePairKernel(k, x, y, z, j, n);
    AddMieBlock(hn::LowerHalf(p), blocks, j, acc[0]);
    if (j + kMax < n) AddMieBlock(hn::UpperHalf(ds, p), blocks, j + kMax, acc[0]);
  }
#else
  // One block a step: kSums kernel vectors (N == NS), the h-th into sums h.
  static_assert(N == NS, "the kernel's lanes are the sums'");
  for (size_t j = 0; j < n; j += kMax)
    for (size_t h = 0; h < kSums; ++h)
      AddMieBlock(MiePairKernel(k, x, y, z, j + h * NS, n), blocks, j + h * NS, acc[h]);
#endif
  AddMieLanes(acc, out);
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
  HWY_DYNAMIC_DISPATCH(MieLaneSums)(k, v, x.data(), y.data(), z.data(), blocks.data(), n, out);
}

}  // namespace skybake
#endif  // HWY_ONCE
