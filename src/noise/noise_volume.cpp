#include "noise/noise_volume.hpp"

#include <algorithm>
#include <memory>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "noise/fbm.hpp"
#include "noise/lattice_hash.hpp"
#include "noise/volume_rows.hpp"

namespace skybake {
namespace {

// Refused before anything is allocated (resource bombs, docs/architecture.md
// "Errors and exit codes"):
// a Worley field holds period^3 feature points (256^3 * 12 bytes = 200 MB),
// the volume size^3 * channels floats.
constexpr int kMaxPeriod = 256;
constexpr int kMaxSize = 1024;

void check_range(std::vector<SpecProblem>& out, const std::string& field, long value, long lo,
                 long hi) {
  if (value < lo || value > hi)
    out.push_back({field, fmt::format("expected {} .. {}, got {}", lo, hi, value)});
}

// Period and octave count of one fBm, and its finest period against the size.
void check_fbm(std::vector<SpecProblem>& out, const std::string& name, int period, int octaves,
               int size) {
  check_range(out, name + ".period", period, 1, kMaxPeriod);
  check_range(out, name + ".octaves", octaves, 1, kMaxOctaves);
  if (period < 1 || octaves < 1 || octaves > kMaxOctaves || size < 2) return;
  const long finest = long(period) << (octaves - 1);
  if (finest > size / 2 || finest > kMaxPeriod)
    out.push_back({name, fmt::format("expected the finest octave period (period * 2^(octaves - 1)) "
                                     "<= {} (size / 2, at least 2 voxels per cell), got {}",
                                     std::min(size / 2, kMaxPeriod), finest)});
}

void throw_if_invalid(const char* product, const std::vector<SpecProblem>& problems) {
  if (problems.empty()) return;
  throw Error(fmt::format("{}: {}: {}", product, problems[0].field, problems[0].message));
}

std::string worley_meaning(const WorleyFbmSpec& w) {
  std::string weights;
  for (int o = 0; o < w.octaves; ++o)
    weights += fmt::format("{}{}", o ? " " : "", worley_fbm_weight(o, w.octaves));
  return fmt::format("inverted Worley fBm, periods {}..{} cells, weights {}", w.period,
                     w.period << (w.octaves - 1), weights);
}

// The distinct Worley fields a volume needs (a period shared by several
// channels is evaluated once per voxel) and, per channel, its fBm as terms
// (field index, weight) in octave order, the summation order of worley_fbm3.
struct WorleyPlan {
  std::vector<std::unique_ptr<WorleyRows>> fields;
  std::vector<std::vector<std::pair<int, float>>> channels;

  WorleyPlan(int size, uint32_t seed, const std::vector<WorleyFbmSpec>& specs) {
    std::vector<int> periods;
    for (const WorleyFbmSpec& w : specs) {
      std::vector<std::pair<int, float>> terms;
      for (int o = 0; o < w.octaves; ++o) {
        const int period = w.period << o;
        auto it = std::find(periods.begin(), periods.end(), period);
        if (it == periods.end()) it = periods.insert(periods.end(), period);
        terms.push_back({int(it - periods.begin()), worley_fbm_weight(o, w.octaves)});
      }
      channels.push_back(terms);
    }
    // The tables of the fields are independent: build them side by side.
    fields.resize(periods.size());
    tbb::parallel_for(size_t(0), periods.size(), [&](size_t i) {
      const int p = periods[i];
      fields[i] =
          std::make_unique<WorleyRows>(size, p, field_seed(seed, NoiseKind::worley, glm::ivec3(p)));
    });
  }

  // Fills rows[f * size ..] with field f along row (y, z).
  void eval_fields(int y, int z, int size, RowScratch& scratch, float* rows) const {
    for (size_t f = 0; f < fields.size(); ++f)
      fields[f]->eval_row(y, z, scratch, rows + f * size_t(size));
  }

  // out[x] = channel c's fBm along the row, from the rows of eval_fields.
  // Summed term by term in octave order: the order of worley_fbm3.
  void channel_row(int c, const float* rows, int size, float* out) const {
    std::fill(out, out + size, 0.0f);
    for (const auto& [field, weight] : channels[c]) {
      const float* row = rows + size_t(field) * size;
      for (int x = 0; x < size; ++x) out[x] += weight * row[x];
    }
  }
};

// R = perlin_worley(Perlin fBm / amplitude sum, Worley fBm), then the
// four channels interleaved. The remap is a template argument so that the
// loop holds no switch and vectorizes.
template <PerlinWorleyRemap kRemap>
void combine_row(const float* perlin, float amplitude_sum, const float* channels, int n,
                 float* out) {
  for (int x = 0; x < n; ++x) {
    out[4 * x] = perlin_worley(perlin[x] / amplitude_sum, channels[x], kRemap);
    out[4 * x + 1] = channels[n + x];
    out[4 * x + 2] = channels[2 * n + x];
    out[4 * x + 3] = channels[3 * n + x];
  }
}

void combine_shape_row(PerlinWorleyRemap remap, const float* perlin, float amplitude_sum,
                       const float* channels, int n, float* out) {
  switch (remap) {
    case PerlinWorleyRemap::worley_new_min:
      return combine_row<PerlinWorleyRemap::worley_new_min>(perlin, amplitude_sum, channels, n, out);
    case PerlinWorleyRemap::worley_old_min:
      return combine_row<PerlinWorleyRemap::worley_old_min>(perlin, amplitude_sum, channels, n, out);
    case PerlinWorleyRemap::dilate:
      return combine_row<PerlinWorleyRemap::dilate>(perlin, amplitude_sum, channels, n, out);
  }
}

}  // namespace

std::vector<SpecProblem> spec_problems(const NoiseShapeSpec& spec) {
  std::vector<SpecProblem> out;
  check_range(out, "size", spec.size, 2, kMaxSize);
  check_fbm(out, "perlin", spec.perlin_period, spec.perlin_octaves, spec.size);
  if (!(spec.perlin_gain > 0.0f && spec.perlin_gain <= 1.0f))
    out.push_back(
        {"perlin_gain", fmt::format("expected a value in (0, 1], got {}", spec.perlin_gain)});
  check_fbm(out, "perlin_worley", spec.perlin_worley.period, spec.perlin_worley.octaves, spec.size);
  for (int c = 0; c < 3; ++c)
    check_fbm(out, fmt::format("worley[{}]", c), spec.worley[c].period, spec.worley[c].octaves,
              spec.size);
  return out;
}

std::vector<SpecProblem> spec_problems(const NoiseDetailSpec& spec) {
  std::vector<SpecProblem> out;
  check_range(out, "size", spec.size, 2, kMaxSize);
  for (int c = 0; c < 3; ++c)
    check_fbm(out, fmt::format("worley[{}]", c), spec.worley[c].period, spec.worley[c].octaves,
              spec.size);
  return out;
}

Texture bake_noise_shape(const NoiseShapeSpec& spec, const BakeContext& ctx) {
  throw_if_invalid("noise_shape", spec_problems(spec));
  const int n = spec.size;
  // Channel 0 of the plan is the Perlin-Worley's Worley fBm, 1..3 are G, B, A.
  const WorleyPlan worley(n, spec.seed,
                          {spec.perlin_worley, spec.worley[0], spec.worley[1], spec.worley[2]});
  std::vector<std::unique_ptr<PerlinRows>> perlin;
  std::vector<float> amplitude;
  float amplitude_sum = 0.0f;
  for (int o = 0; o < spec.perlin_octaves; ++o) {
    const int p = spec.perlin_period << o;
    perlin.push_back(std::make_unique<PerlinRows>(
        n, p, field_seed(spec.seed, NoiseKind::perlin, glm::ivec3(p))));
    // Same amplitudes, same order as perlin_fbm3.
    amplitude.push_back(o == 0 ? 1.0f : amplitude.back() * spec.perlin_gain);
    amplitude_sum += amplitude.back();
  }

  Texture tex(n, n, n, 1, {"R", "G", "B", "A"});
  ProgressCounter progress(ctx, size_t(n));
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& zs) {
    RowScratch scratch;
    std::vector<float> rows(worley.fields.size() * size_t(n)), perlin_row(n),
        channels(4 * size_t(n));
    for (int z = zs.begin(); z < zs.end(); ++z) {
      for (int y = 0; y < n; ++y) {
        worley.eval_fields(y, z, n, scratch, rows.data());
        for (int c = 0; c < 4; ++c) worley.channel_row(c, rows.data(), n, &channels[c * size_t(n)]);
        std::fill(perlin_row.begin(), perlin_row.end(), 0.0f);
        for (size_t o = 0; o < perlin.size(); ++o)
          perlin[o]->accumulate_row(y, z, amplitude[o], scratch, perlin_row.data());
        combine_shape_row(spec.remap, perlin_row.data(), amplitude_sum, channels.data(), n,
                          tex.texel(0, y, z));
      }
      progress.tick();
    }
  });

  Metadata& m = tex.metadata;
  set_meta(m, "product", "noise_shape");
  set_meta(m, "seed", int(spec.seed));  // at most 2^31 - 1 (the schemas): an int
  set_meta(m, "tiling", "periodic on x, y, z");
  set_meta(m, "remap", remap_name(spec.remap));
  set_meta(m, "channel.R",
           fmt::format("Perlin-Worley ({}): Perlin fBm periods {}..{} lattice cells gain {}, "
                       "dilated by {}",
                       remap_name(spec.remap), spec.perlin_period,
                       spec.perlin_period << (spec.perlin_octaves - 1), spec.perlin_gain,
                       worley_meaning(spec.perlin_worley)));
  set_meta(m, "period.R", spec.perlin_period);
  set_meta(m, "octaves.R", spec.perlin_octaves);
  const char* names[3] = {"G", "B", "A"};
  for (int c = 0; c < 3; ++c) {
    set_meta(m, fmt::format("channel.{}", names[c]), worley_meaning(spec.worley[c]));
    set_meta(m, fmt::format("period.{}", names[c]), spec.worley[c].period);
    set_meta(m, fmt::format("octaves.{}", names[c]), spec.worley[c].octaves);
  }
  return tex;
}

Texture bake_noise_detail(const NoiseDetailSpec& spec, const BakeContext& ctx) {
  throw_if_invalid("noise_detail", spec_problems(spec));
  const int n = spec.size;
  const WorleyPlan worley(n, stream_seed(spec.seed, kDetailStream),
                          {spec.worley[0], spec.worley[1], spec.worley[2]});
  Texture tex(n, n, n, 1, {"R", "G", "B"});
  ProgressCounter progress(ctx, size_t(n));
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& zs) {
    RowScratch scratch;
    std::vector<float> rows(worley.fields.size() * size_t(n)), channels(3 * size_t(n));
    for (int z = zs.begin(); z < zs.end(); ++z) {
      for (int y = 0; y < n; ++y) {
        worley.eval_fields(y, z, n, scratch, rows.data());
        for (int c = 0; c < 3; ++c) worley.channel_row(c, rows.data(), n, &channels[c * size_t(n)]);
        float* out = tex.texel(0, y, z);
        for (int x = 0; x < n; ++x, out += 3)
          for (int c = 0; c < 3; ++c) out[c] = channels[c * size_t(n) + x];
      }
      progress.tick();
    }
  });

  Metadata& m = tex.metadata;
  set_meta(m, "product", "noise_detail");
  set_meta(m, "seed", int(spec.seed));  // at most 2^31 - 1 (the schemas): an int
  set_meta(m, "tiling", "periodic on x, y, z");
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    set_meta(m, fmt::format("channel.{}", names[c]), worley_meaning(spec.worley[c]));
    set_meta(m, fmt::format("period.{}", names[c]), spec.worley[c].period);
    set_meta(m, fmt::format("octaves.{}", names[c]), spec.worley[c].octaves);
  }
  return tex;
}

Texture pack_single_channel(const Texture& tex, PackWeights weights) {
  const int nc = tex.channel_count();
  if (nc < 1 || nc > 4 || (weights.mode == PackMode::dilate_base && nc < 2))
    throw Error(fmt::format("pack_single_channel: expected {} channels, got {}",
                            weights.mode == PackMode::dilate_base ? "2 .. 4" : "1 .. 4", nc));
  const auto& w = weights.weights;
  // Non-negative weights summing to at most 1 keep the result a blend of the
  // inputs (and 2 - fbm >= 1 in dilate_base).
  float total = 0.0f;
  for (int c = weights.mode == PackMode::dilate_base ? 1 : 0; c < nc; ++c) {
    if (!(w[c] >= 0.0f))
      throw Error(fmt::format("pack_single_channel: expected weight {} >= 0, got {}", c, w[c]));
    total += w[c];
  }
  if (total > 1.0f + 1e-6f)
    throw Error(
        fmt::format("pack_single_channel: expected weights summing to <= 1, got {}", total));
  Texture out(tex.width, tex.height, tex.depth, tex.layers, {"R"});
  // The source's per-channel descriptions move under "source.": they describe
  // channels the packed texture no longer has.
  for (const auto& [key, value] : tex.metadata) {
    const bool per_channel = key.rfind("channel.", 0) == 0 || key.rfind("period.", 0) == 0 ||
                             key.rfind("octaves.", 0) == 0;
    out.metadata[per_channel ? "source." + key : key] = value;
  }
  const size_t texels = tex.texel_count();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, texels, 4096),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t t = r.begin(); t < r.end(); ++t) {
                        const float* v = &tex.data[t * nc];
                        float value;
                        if (weights.mode == PackMode::dilate_base) {
                          float fbm = 0.0f;
                          for (int c = 1; c < nc; ++c) fbm += w[c] * v[c];
                          value = (v[0] + 1.0f - fbm) / (2.0f - fbm);
                        } else {
                          value = 0.0f;
                          for (int c = 0; c < nc; ++c) value += w[c] * v[c];
                        }
                        out.data[t] = std::clamp(value, 0.0f, 1.0f);
                      }
                    });
  const std::string formula =
      weights.mode == PackMode::dilate_base
          ? fmt::format("saturate((R + 1 - fbm) / (2 - fbm)), fbm = {} G + {} B + {} A", w[1], w[2],
                        w[3])
          : fmt::format("saturate({} R + {} G + {} B + {} A)", w[0], w[1], w[2], w[3]);
  set_meta(out.metadata, "packed", formula);
  set_meta(out.metadata, "channel.R", "packed: " + formula);
  return out;
}

}  // namespace skybake
