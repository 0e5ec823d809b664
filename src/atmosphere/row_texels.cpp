// The texels of a multiple-scattering row. See the header.
#include "atmosphere/row_texels.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

namespace {

int round_up8(int n) { return (n + 7) / 8 * 8; }

}  // namespace

RowTexels::RowTexels(const ScatteringShape& shape) {
  // Two groups, each padded to 8, and 16 more for the taps of sixteen lanes
  // (kernels/node_slice_reads.cpp).
  const int W = shape.texture_width(), size = round_up8(W) + 24;
  mu_s.assign(size, 0.0);
  nu.assign(size, 0.0);
  for (auto* v : {&nu_i0, &nu_i1, &at0, &at1}) v->assign(size, 0);
  nu_w.assign(size, 0.0f);
  lw.assign(size, 0.0f);
  for (auto* v : {&nu_f, &sin_nu, &sun_nu_w, &pw}) v->assign(size, 0.0f);
  sun_nu_i0.assign(size, 0);
  sun_nu_i1.assign(size, 0);
  slot.assign(W, 0);
  spread_.assign(shape.mu_s_size, 0.0);
  staged_.assign(W, Staged{});
  place_.assign(W, 0);
}

void RowTexels::make(const ScatteringTexelGrid& texels, const ScatteringShape& shape, double mu) {
  const int W = shape.texture_width(), n_mu_s = shape.mu_s_size;
  for (int l = 0; l < n_mu_s; ++l) spread_[l] = ScatteringTexelGrid::spread(mu, texels.mu_s[l]);
  // The distinct texels in row order (staged_), and how many read one
  // slice: a weight of exactly 0 or 1 in float.
  int n = 0, ones = 0;
  for (int x = 0; x < W; ++x) {
    const int l = x % n_mu_s, below = x - n_mu_s;
    const double mu_mu_s = mu * texels.mu_s[l];
    const double v = std::clamp(texels.nu[x / n_mu_s], mu_mu_s - spread_[l], mu_mu_s + spread_[l]);
    if (below >= 0 && staged_[slot[below]].nu == v) {
      slot[x] = slot[below];
      continue;
    }
    const AxisTap tn = nu_slice_tap(0.5 * (v + 1.0), shape.nu_size);
    Staged& t = staged_[n];
    t = {texels.mu_s[l], v, tn.i0 * n_mu_s, tn.i1 * n_mu_s, float(tn.w)};
    if (t.nu_w == 1.0f) t.nu_i0 = t.nu_i1;
    if (t.nu_w == 0.0f || t.nu_w == 1.0f) {
      t.nu_w = 0.0f;
      ++ones;
    }
    slot[x] = n++;
  }
  single = round_up8(ones);
  end = single + round_up8(n - ones);
  // The padding: valid texels whose sums are not read.
  std::fill(mu_s.begin(), mu_s.begin() + end, 0.0);
  std::fill(nu.begin(), nu.begin() + end, 0.0);
  std::fill(nu_i0.begin(), nu_i0.begin() + end, 0);
  std::fill(nu_i1.begin(), nu_i1.begin() + end, 0);
  std::fill(nu_w.begin(), nu_w.begin() + end, 0.0f);
  // One-slice texels first, then the others, in row order within each.
  for (int k = 0, a = 0, b = single; k < n; ++k) {
    const Staged& t = staged_[k];
    const int to = place_[k] = t.nu_w == 0.0f ? a++ : b++;
    mu_s[to] = t.mu_s;
    nu[to] = t.nu;
    nu_i0[to] = t.nu_i0;
    nu_i1[to] = t.nu_i1;
    nu_w[to] = t.nu_w;
  }
  for (int x = 0; x < W; ++x) slot[x] = place_[slot[x]];
}

// A texel of one slice (k < single) reads its slice's node alone: its nu
// is the slice's, or within a float's rounding of it (a 4D weight that
// rounds to 1 in float), so the nearer node.
void RowTexels::make_sun_frame_nu(const std::vector<double>& grid, int mu_s_size) {
  for (int k = 0; k < end; ++k) {
    nu_f[k] = float(nu[k]);
    sin_nu[k] = float(std::sqrt(std::max(1.0 - nu[k] * nu[k], 0.0)));
    AxisTap t = sun_frame_nu_tap(grid, nu[k]);
    if (k < single) t = t.w > 0.5 ? AxisTap{t.i1, t.i1, 0.0} : AxisTap{t.i0, t.i0, 0.0};
    sun_nu_i0[k] = t.i0 * mu_s_size;
    sun_nu_i1[k] = t.i1 * mu_s_size;
    sun_nu_w[k] = float(t.w);
  }
}

NodeRow RowTexels::node(double r, double s, double inv_r_i) {
  NodeRow q{r, s, inv_r_i, single, mu_s.data(), nu.data(), nu_i0.data(), nu_i1.data(),
            nu_w.data(), at0.data(), at1.data(), lw.data()};
  return q;
}

SunFrameNode RowTexels::sun_frame_node(double r, double s, double inv_r_i, double mu_i,
                                       int phi_size) {
  SunFrameNode q;
  q.r = r;
  q.s = s;
  q.inv_r_i = inv_r_i;
  q.mu_i = float(mu_i);
  q.phi_size = phi_size;
  q.single = single;
  q.mu_s = mu_s.data();
  q.nu = nu.data();
  q.nu_f = nu_f.data();
  q.sin_nu = sin_nu.data();
  q.nu_i0 = sun_nu_i0.data();
  q.nu_i1 = sun_nu_i1.data();
  q.nu_w = sun_nu_w.data();
  q.at0 = at0.data();
  q.at1 = at1.data();
  q.lw = lw.data();
  q.pw = pw.data();
  return q;
}

}  // namespace skybake
