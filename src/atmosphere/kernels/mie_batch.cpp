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

// lanes[c][l]: the sum of channel c (R, G, B, weight) in lane l.
void MieLaneSums(const MieKernel& k, const glm::dvec3& v, const float* x, const float* y,
                 const float* z, const float* blocks, size_t n,
                 float lanes[4][MieBatch::kLanes]) {
  const hn::CappedTag<float, MieBatch::kLanes> d;
  using V = hn::Vec<decltype(d)>;
  constexpr size_t kMax = MieBatch::kLanes;
  const size_t N = hn::Lanes(d), groups = kMax / N;
  const V one = hn::Set(d, 1.0f), zero = hn::Zero(d);
  const V a = hn::Set(d, float(k.a)), b = hn::Set(d, float(k.b));
  const V cs = hn::Set(d, k.cornette_shanks ? 1.0f : 0.0f);
  const V vx = hn::Set(d, float(v.x)), vy = hn::Set(d, float(v.y)), vz = hn::Set(d, float(v.z));
  V acc[4][kMax];
  for (auto& c : acc)
    for (size_t h = 0; h < groups; ++h) c[h] = zero;
  for (size_t j = 0; j < n; j += kMax)
    for (size_t h = 0; h < groups; ++h) {
      const size_t at = j + h * N;
      const V in_plane = hn::Add(hn::Mul(vx, hn::LoadU(d, x + at)), hn::Mul(vz, hn::LoadU(d, z + at)));
      const V across = hn::Mul(vy, hn::LoadU(d, y + at));
      const V cp = hn::Add(in_plane, across), cm = hn::Sub(in_plane, across);
      const V wp = hn::Add(a, hn::Mul(b, hn::Max(hn::Sub(one, cp), zero)));
      const V wm = hn::Add(a, hn::Mul(b, hn::Max(hn::Sub(one, cm), zero)));
      const V qp = hn::Mul(wp, hn::Sqrt(wp)), qm = hn::Mul(wm, hn::Sqrt(wm));
      const V np = hn::Add(one, hn::Mul(cs, hn::Mul(cp, cp)));
      const V nm = hn::Add(one, hn::Mul(cs, hn::Mul(cm, cm)));
      const V p = hn::Div(hn::Add(hn::Mul(np, qm), hn::Mul(nm, qp)), hn::Mul(qp, qm));
      for (int c = 0; c < 4; ++c)
        acc[c][h] = hn::Add(acc[c][h], hn::Mul(p, hn::LoadU(d, blocks + MieBatch::field(c, at))));
    }
  for (int c = 0; c < 4; ++c)
    for (size_t h = 0; h < groups; ++h) hn::StoreU(acc[c][h], d, lanes[c] + h * N);
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
