#include "core/tiling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/tiling_profiles.hpp"

namespace skybake {

namespace {

// Level 0 is judged from 16 texels along an axis; a smaller mip level only
// from 32, since its few faces make the interior distribution unreliable
// (measured on the shipped products with other seeds: a 16-texel axis
// would fail by chance about once in 600 tests, a 32-texel one once in 2500).
constexpr int kMinJudgedTexels = 16;
constexpr int kMinJudgedMipTexels = 32;
constexpr double kSpreadFactor = 4.0;  // limits sit 4 (q90 - median) above the median at least
constexpr double kSlopeMargin = 1.5;   // slopes may turn 2.5x the median at the seam
constexpr double kInf = std::numeric_limits<double>::infinity();

// Linearly interpolated quantile of a non-empty sample.
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const size_t i = size_t(pos);
  if (i + 1 >= v.size()) return v.back();
  const double t = pos - double(i);
  return t == 0.0 ? v[i] : v[i] + t * (v[i + 1] - v[i]);
}

double ratio_or_one(double a, double b) {
  if (b > 0.0) return a / b;
  return a > 0.0 ? kInf : 1.0;  // a face no different from flat neighbours
}

// Score of every face: num over den.
std::vector<double> scores(const std::vector<double>& num, const std::vector<double>& den) {
  std::vector<double> s(num.size());
  for (size_t f = 0; f < num.size(); ++f) s[f] = ratio_or_one(num[f], den[f]);
  return s;
}

// The seam (face n - 1) against the faces from `first` to `last`.
SeamScore seam_score(const std::vector<double>& s, int first, int last, double margin) {
  SeamScore r;
  const std::vector<double> interior(s.begin() + first, s.begin() + last + 1);
  r.seam = s.back();
  r.median = quantile(interior, 0.5);
  r.q90 = quantile(interior, 0.9);
  r.limit = std::isfinite(r.q90)
                ? r.median + std::max(margin * r.median, kSpreadFactor * (r.q90 - r.median))
                : kInf;
  return r;
}

int min_judged_texels(int level) { return level == 0 ? kMinJudgedTexels : kMinJudgedMipTexels; }

// `p`: the axis's profiles of the channel, null when the axis is too short.
AxisTiling measure_axis(const Texture& t, int level, int layer, int channel, int axis,
                        const TilingProfiles* p, double tolerance) {
  const int n[3] = {t.width, t.height, t.depth};
  AxisTiling a;
  a.level = level;
  a.layer = layer;
  a.axis = char('x' + axis);
  a.channel = t.channels[channel];
  a.texels = n[axis];
  const TilingVerdict unjudged = level == 0 ? TilingVerdict::cannot_tell : TilingVerdict::not_judged;
  const int min_texels = min_judged_texels(level);
  if (!p) {
    a.verdict = unjudged;
    a.reason = fmt::format("{} texels, at least {} are needed to judge a seam", a.texels,
                           min_texels);
    return a;
  }
  if (*std::max_element(p->jump.begin(), p->jump.end()) == 0.0) {
    a.reason = "constant";
    return a;
  }
  const int len = a.texels;
  // Interior faces: the values stencil spans texels f - 2 .. f + 3, the
  // slopes stencil f - 4 .. f + 5; neither may hold both texels n - 1 and 0.
  a.values = seam_score(scores(p->jump, p->jump_side), 2, len - 4, tolerance);
  a.slopes = seam_score(scores(p->turn, p->turn_side), 4, len - 6, kSlopeMargin);
  const double typical_jump =
      quantile(std::vector<double>(p->jump.begin() + 2, p->jump.begin() + len - 3), 0.5);
  a.contrast = ratio_or_one(p->far, typical_jump);
  // A join of unrelated texels scores about contrast x the median score.
  const double needed = ratio_or_one(a.values.limit, a.values.median);
  if (!(a.contrast > needed)) {
    a.verdict = unjudged;
    a.reason = fmt::format(
        "too rough for a seam to show: texels far apart differ {:.3g}x as much as neighbours, "
        "a seam must stand out {:.3g}x",
        a.contrast, needed);
    return a;
  }
  a.ratio = std::max(ratio_or_one(a.values.seam, a.values.limit),
                     ratio_or_one(a.slopes.seam, a.slopes.limit));
  a.verdict = a.ratio > 1.0 ? TilingVerdict::seam : TilingVerdict::tiles;
  a.tiles = a.verdict == TilingVerdict::tiles;
  return a;
}

void measure_level(const Texture& t, int level, double tolerance, std::vector<AxisTiling>& out) {
  const int n[3] = {t.width, t.height, t.depth};
  struct Job {
    int layer, axis;
  };
  std::vector<Job> jobs;  // every channel of a layer's axis at once: each texel read once
  for (int layer = 0; layer < t.layers; ++layer)
    for (int axis = 0; axis < 3; ++axis)
      if (n[axis] >= 2) jobs.push_back({layer, axis});
  const int nc = t.channel_count();
  std::vector<AxisTiling> results(jobs.size() * size_t(nc));
  tbb::parallel_for(size_t(0), jobs.size(), [&](size_t i) {
    const Job& job = jobs[i];
    std::vector<TilingProfiles> p;
    if (n[job.axis] >= min_judged_texels(level)) p = compute_tiling_profiles(t, job.layer, job.axis);
    for (int c = 0; c < nc; ++c)
      results[i * size_t(nc) + size_t(c)] = measure_axis(t, level, job.layer, c, job.axis,
                                                          p.empty() ? nullptr : &p[size_t(c)],
                                                          tolerance);
  });
  for (AxisTiling& a : results) {
    a.tiles = a.verdict == TilingVerdict::tiles || a.verdict == TilingVerdict::not_judged;
    out.push_back(std::move(a));
  }
}

}  // namespace

const char* tiling_verdict_name(TilingVerdict v) {
  switch (v) {
    case TilingVerdict::tiles:
      return "tiles";
    case TilingVerdict::seam:
      return "seam";
    case TilingVerdict::cannot_tell:
      return "cannot_tell";
    case TilingVerdict::not_judged:
      return "not_judged";
  }
  return "?";
}

TilingReport measure_tiling(const Texture& level0, const std::vector<Texture>& lower_levels,
                            double tolerance) {
  TilingReport report;
  measure_level(level0, 0, tolerance, report.axes);
  // A channel too rough to show a seam is not counted when another channel
  // along the same axis of the layer is judged: channels are cut together.
  for (AxisTiling& a : report.axes) {
    if (a.verdict != TilingVerdict::cannot_tell) continue;
    for (const AxisTiling& b : report.axes) {
      const bool judged = b.verdict == TilingVerdict::seam ||
                          (b.verdict == TilingVerdict::tiles && b.reason.empty());
      if (b.layer == a.layer && b.axis == a.axis && judged) {
        a.verdict = TilingVerdict::not_judged;
        a.tiles = true;
        a.reason += fmt::format("; axis {} is judged on channel {}", a.axis, b.channel);
        break;
      }
    }
  }
  for (size_t i = 0; i < lower_levels.size(); ++i)
    measure_level(lower_levels[i], int(i + 1), tolerance, report.axes);
  bool any_seam = false, any_unknown = false;
  for (const AxisTiling& a : report.axes) {
    any_seam = any_seam || a.verdict == TilingVerdict::seam;
    any_unknown = any_unknown || a.verdict == TilingVerdict::cannot_tell;
    report.worst_ratio = std::max(report.worst_ratio, a.ratio);
  }
  report.verdict = any_seam      ? TilingVerdict::seam
                   : any_unknown ? TilingVerdict::cannot_tell
                                 : TilingVerdict::tiles;
  report.tiles = report.verdict == TilingVerdict::tiles;
  return report;
}

TilingReport measure_tiling(const Texture& tex, double tolerance) {
  return measure_tiling(tex, {}, tolerance);
}

}  // namespace skybake
