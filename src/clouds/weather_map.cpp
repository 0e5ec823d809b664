#include "clouds/weather_map.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "clouds/field_stats.hpp"
#include "core/error.hpp"
#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"  // cell_coord_from_texel

namespace skybake {

namespace {

// Independent noise streams of one seed (ASCII tags).
constexpr uint32_t kCoverageStream = 0x636f7665;       // "cove"
constexpr uint32_t kPrecipitationStream = 0x70726563;  // "prec"
constexpr uint32_t kTypeStream = 0x74797065;           // "type"

constexpr int kMaxPeriod = 1024;

// One periodic Perlin fBm signal sampled at the texel centres of the map.
struct Signal {
  int period = 1;
  int octaves = 1;
  uint32_t seed = 0;
};

Signal signal_for(const WeatherSpec& spec, double feature_km, int octaves, uint32_t stream) {
  Signal s;
  s.period = period_from_feature_km(spec.world_size_km, feature_km);
  s.octaves = octaves_within_size(s.period, octaves, spec.size);
  s.seed = stream_seed(spec.seed, stream);
  return s;
}

float sample(const Signal& s, int x, int y, int n) {
  const glm::vec2 p(cell_coord_from_texel(x, n, s.period), cell_coord_from_texel(y, n, s.period));
  return perlin_fbm2(p, glm::ivec2(s.period), s.octaves, s.seed);
}

// Divides by the largest |value| so the field spans [-1, 1].
void normalize(TexelVector& v) {
  const float m = max_abs(v);
  if (m > 0.0f)
    for (float& x : v) x /= m;
}

// p per texel from the precipitation noise m (see the header).
TexelVector precipitation_from(const TexelVector& m, const WeatherPrecipitation& P) {
  const size_t n = m.size();
  TexelVector p(n);  // zeros (TexelVector's allocator)
  const size_t k1 = texels_from_fraction(P.area, n);
  if (k1 == 0) return p;
  const size_t k0 = std::min(n, k1 + texels_from_fraction(P.edge, n));
  const float t1 = kth_largest(m, k1);
  const float t0 = k0 < n ? kth_largest(m, k0 + 1) : *std::min_element(m.begin(), m.end());
  for (size_t i = 0; i < n; ++i) {
    if (m[i] >= t1)
      p[i] = 1.0f;
    else if (m[i] > t0 && t1 > t0)
      p[i] = std::clamp(float((double(m[i]) - t0) / (double(t1) - t0)), 0.0f, 1.0f);
  }
  return p;
}

double raw_coverage(double n, double t, double contrast) {
  return std::clamp(0.5 + contrast * (n - t), 0.0, 1.0);
}

// Mean of max(raw_coverage, 0.7 p) over the map: per-row sums in parallel,
// added in row order (deterministic for any thread count).
double mean_coverage(const TexelVector& nc, const TexelVector& p, double t,
                     double contrast, int size) {
  std::vector<double> rows(size);
  tbb::parallel_for(0, size, [&](int y) {
    double s = 0.0;
    for (size_t i = size_t(y) * size; i < size_t(y + 1) * size; ++i)
      s += std::max(raw_coverage(nc[i], t, contrast), double(kRainCoverage * p[i]));
    rows[y] = s;
  });
  double sum = 0.0;
  for (double r : rows) sum += r;
  return sum / double(nc.size());
}

// The threshold t for which the mean coverage is `target`. The mean falls
// monotonically (and continuously) from 1 at t = lo to mean(0.7 p) at
// t = hi, so bisection converges to it; a target below mean(0.7 p) (refused
// by the pipeline) ends at hi.
double coverage_threshold(const TexelVector& nc, const TexelVector& p,
                          const WeatherCoverage& C, int size) {
  double lo = -2.0 - 0.5 / C.contrast, hi = 2.0 + 0.5 / C.contrast;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mean_coverage(nc, p, mid, C.contrast, size) > C.mean)
      lo = mid;
    else
      hi = mid;
  }
  return hi;  // the side where the mean is <= the target: coverage 0 stays exactly 0
}

void set_signal_meta(Metadata& m, const std::string& name, const Signal& s, double world_km) {
  set_meta(m, name + ".period", s.period);
  set_meta(m, name + ".feature_km", feature_km_from_period(world_km, s.period));
  set_meta(m, "octaves_used." + name, s.octaves);
}

// The three noise signals of the map, one stream each.
struct WeatherSignals {
  Signal coverage, rain, type;
};

WeatherSignals weather_signals(const WeatherSpec& spec) {
  return {signal_for(spec, spec.coverage.feature_km, spec.coverage.octaves, kCoverageStream),
          signal_for(spec, spec.precipitation.feature_km, spec.precipitation.octaves,
                     kPrecipitationStream),
          signal_for(spec, spec.type.feature_km, spec.type.octaves, kTypeStream)};
}

// Per texel: the coverage and type noise normalized to [-1, 1], and the
// precipitation p (all 0 where it does not rain).
struct WeatherFields {
  TexelVector coverage, type, precipitation;
};

WeatherFields sample_weather_fields(const WeatherSpec& spec, const WeatherSignals& signals,
                                    const ProgressCounter& progress) {
  const int n = spec.size;
  const size_t count = size_t(n) * size_t(n);
  const bool rains = texels_from_fraction(spec.precipitation.area, count) > 0;
  TexelVector nc(count), np(rains ? count : 0), nt(count);
  tbb::parallel_for(0, n, [&](int y) {
    for (int x = 0; x < n; ++x) {
      const size_t i = size_t(y) * n + x;
      nc[i] = sample(signals.coverage, x, y, n);
      nt[i] = sample(signals.type, x, y, n);
      if (rains) np[i] = sample(signals.rain, x, y, n);
    }
    progress.tick();
  });
  normalize(nc);
  normalize(nt);
  TexelVector p(count);
  if (rains) {
    normalize(np);
    const float w = float(spec.precipitation.correlation);
    for (size_t i = 0; i < count; ++i) np[i] = (1.0f - w) * np[i] + w * nc[i];
    p = precipitation_from(np, spec.precipitation);
  }
  return {std::move(nc), std::move(nt), std::move(p)};
}

Texture weather_texture(const WeatherSpec& spec) {
  const bool schneider = spec.layout == WeatherLayout::schneider;
  return Texture(
      spec.size, spec.size, 1, 1,
      schneider ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"R", "G"});
}

// What the map holds, summed over its texels (for the metadata).
struct WeatherTotals {
  double coverage_sum = 0.0;
  size_t raining = 0;
};

// Coverage and type of every texel at threshold t, rain rules applied (see
// the header); row sums added in row order (same for any thread count).
WeatherTotals write_weather_texels(const WeatherSpec& spec, const WeatherFields& fields, double t,
                                   Texture& tex, const ProgressCounter& progress) {
  const int n = spec.size;
  const bool schneider = spec.layout == WeatherLayout::schneider;
  const TexelVector &nc = fields.coverage, &nt = fields.type, &p = fields.precipitation;
  std::vector<double> row_coverage(n);
  std::vector<size_t> row_raining(n);
  tbb::parallel_for(0, n, [&](int y) {
    double sum = 0.0;
    size_t raining = 0;
    for (int x = 0; x < n; ++x) {
      const size_t i = size_t(y) * n + x;
      const float c =
          coverage_with_rain(float(raw_coverage(nc[i], t, spec.coverage.contrast)), p[i]);
      const float type_raw =
          float(std::clamp(spec.type.mean + spec.type.variation * nt[i], 0.0, 1.0));
      float* texel = tex.texel(x, y);
      texel[0] = c;
      if (schneider) {
        texel[1] = p[i];
        texel[2] = std::clamp(type_with_rain(type_raw, p[i]), 0.0f, 1.0f);
      } else {
        const double index = frostbite_type_index(type_raw, p[i]);
        texel[1] = float(std::clamp((index + 0.5) / spec.type_count, 0.0, 1.0));
      }
      sum += c;
      raining += p[i] == 1.0f;
    }
    row_coverage[y] = sum;
    row_raining[y] = raining;
    progress.tick();
  });
  WeatherTotals totals;
  for (int y = 0; y < n; ++y) {
    totals.coverage_sum += row_coverage[y];
    totals.raining += row_raining[y];
  }
  return totals;
}

void set_weather_metadata(Metadata& m, const WeatherSpec& spec, const WeatherSignals& signals,
                          double t, const WeatherTotals& totals) {
  const bool schneider = spec.layout == WeatherLayout::schneider;
  const double count = double(spec.size) * double(spec.size);
  set_meta(m, "product", "weather");
  set_meta(m, "weather_layout", schneider ? "schneider" : "frostbite");
  set_meta(m, "tiling", "periodic on x, y");
  set_meta(m, "seed", int(spec.seed));  // at most 2^31 - 1 (the schemas): an int
  set_meta(m, "world_size_km", spec.world_size_km);
  set_meta(m, "texel_size_m", spec.world_size_km * 1e3 / spec.size);
  set_meta(m, "coverage.mean", spec.coverage.mean);
  set_meta(m, "coverage.mean_baked", totals.coverage_sum / count);
  set_meta(m, "coverage.contrast", spec.coverage.contrast);
  set_meta(m, "coverage.threshold", t);
  set_signal_meta(m, "coverage", signals.coverage, spec.world_size_km);
  set_meta(m, "precipitation.area", spec.precipitation.area);
  set_meta(m, "precipitation.area_baked", double(totals.raining) / count);
  set_meta(m, "precipitation.edge", spec.precipitation.edge);
  set_meta(m, "precipitation.correlation", spec.precipitation.correlation);
  set_signal_meta(m, "precipitation", signals.rain, spec.world_size_km);
  set_meta(m, "type.mean", spec.type.mean);
  set_meta(m, "type.variation", spec.type.variation);
  set_signal_meta(m, "type", signals.type, spec.world_size_km);
  set_meta(m, "rain_rule",
           "coverage = max(c, 0.7 p); type = (1 - p) type + p (schneider), type index = "
           "(1 - p) 2 type + 3 p (frostbite); p = 1 gives coverage >= 0.7 and cumulonimbus");
  if (schneider) {
    set_meta(m, "channel.R", "coverage");
    set_meta(m, "channel.G", "precipitation");
    set_meta(m, "channel.B",
             "cloud type: 0 stratus, 0.5 stratocumulus, 1 cumulus (1 with G = 1: cumulonimbus)");
  } else {
    set_meta(m, "type_count", spec.type_count);
    set_meta(m, "channel.R", "density (coverage)");
    set_meta(m, "channel.G",
             "cloud_types u = (index + 0.5) / type_count; index 0 stratus, 1 stratocumulus, "
             "2 cumulus, 3 cumulonimbus");
  }
}

}  // namespace

int period_from_feature_km(double world_size_km, double feature_km) {
  const double cells = std::round(world_size_km / feature_km);
  return int(std::clamp(cells, 1.0, double(kMaxPeriod)));
}

std::vector<SpecProblem> spec_problems(const WeatherSpec& s) {
  std::vector<SpecProblem> out;
  auto in = [&](const std::string& field, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi))
      out.push_back({field, fmt::format("expected a value in [{}, {}], got {}", lo, hi, v)});
  };
  auto positive = [&](const std::string& field, double v) {
    if (!(v > 0.0 && std::isfinite(v)))
      out.push_back({field, fmt::format("expected a value > 0, got {}", v)});
  };
  if (s.size < 2 || s.size > 8192)
    out.push_back({"size", fmt::format("expected 2 .. 8192, got {}", s.size)});
  positive("world_size_km", s.world_size_km);
  if (s.layout == WeatherLayout::frostbite && s.type_count < 4)
    out.push_back({"type_count", fmt::format("expected >= 4 types, got {}", s.type_count)});
  in("coverage.mean", s.coverage.mean, 0.0, 1.0);
  positive("coverage.contrast", s.coverage.contrast);
  in("precipitation.area", s.precipitation.area, 0.0, 1.0);
  in("precipitation.edge", s.precipitation.edge, 0.0, 1.0 - s.precipitation.area);
  in("precipitation.correlation", s.precipitation.correlation, 0.0, 1.0);
  in("type.mean", s.type.mean, 0.0, 1.0);
  in("type.variation", s.type.variation, 0.0, 1.0);
  const std::pair<const char*, double> features[3] = {
      {"coverage.feature_km", s.coverage.feature_km},
      {"precipitation.feature_km", s.precipitation.feature_km},
      {"type.feature_km", s.type.feature_km}};
  for (const auto& [field, km] : features) {
    positive(field, km);
    if (km > 0.0 && s.world_size_km > 0.0 && s.world_size_km / km > kMaxPeriod + 0.5)
      out.push_back({field, fmt::format("expected at least world_size_km / {} = {} km (at most {} "
                                        "features across the map), got {}",
                                        kMaxPeriod, s.world_size_km / kMaxPeriod, kMaxPeriod, km)});
  }
  for (const auto& [field, o] :
       {std::pair<const char*, int>{"coverage.octaves", s.coverage.octaves},
        {"precipitation.octaves", s.precipitation.octaves},
        {"type.octaves", s.type.octaves}})
    if (o < 1 || o > kMaxOctaves)
      out.push_back({field, fmt::format("expected 1 .. {}, got {}", kMaxOctaves, o)});
  // The rain floor alone covers up to 0.7 (area + edge) of the map on
  // average; a lower mean coverage cannot be reached.
  const double floor = 0.7 * std::min(1.0, s.precipitation.area + s.precipitation.edge);
  if (s.precipitation.area > 0.0 && s.coverage.mean < floor - 1e-12)
    out.push_back({"coverage.mean",
                   fmt::format("expected at least 0.7 x (precipitation area + edge) = {} (where it "
                               "rains, coverage is at least 0.7), got {}",
                               floor, s.coverage.mean)});
  return out;
}

Texture bake_weather_map(const WeatherSpec& spec, const BakeContext& ctx) {
  const auto problems = spec_problems(spec);
  if (!problems.empty())
    throw Error(fmt::format("weather: {}: {}", problems[0].field, problems[0].message));
  const WeatherSignals signals = weather_signals(spec);
  ProgressCounter progress(ctx, size_t(spec.size) * 2);
  WeatherFields fields = sample_weather_fields(spec, signals, progress);
  const double t =
      coverage_threshold(fields.coverage, fields.precipitation, spec.coverage, spec.size);
  Texture tex = weather_texture(spec);
  const WeatherTotals totals = write_weather_texels(spec, fields, t, tex, progress);
  set_weather_metadata(tex.metadata, spec, signals, t, totals);
  return tex;
}

}  // namespace skybake
