// What an output takes, known from its spec before anything is allocated:
// the smallest size its baker accepts, the channels and layers of its texture,
// and the memory its bake peaks at. load_scene refuses an output (or a scene)
// over the budgets here with the JSON pointer and the rule, so a bake never
// starts what it cannot finish (docs/decisions/output-budgets.md).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "pipeline/scene.hpp"

namespace skybake {

// Memory one bake may peak at: every texture of the scene (they stay in
// memory until the scene is baked) plus the working memory of its largest
// bake.
constexpr std::uint64_t kMaxBakeBytes = std::uint64_t(8) << 30;  // 8 GiB

struct ProductLimits {
  // Smallest texels per size axis the product's baker accepts (empty: 1).
  std::vector<int> min_size;
  // Peak resident memory of baking the output and writing it in one format,
  // per byte of its texture at 4 float32 channels (output_texture_bytes), by
  // format: the slope of /usr/bin/time -v's maximum resident set between two
  // sizes, rounded up to the next 0.5. Empty: kMinWorkingFactor.
  std::map<std::string, double> working;
};

// The factor of a product whose texture is small next to what it reads.
constexpr double kMinWorkingFactor = 2.0;

// The limits of a product of the registry; defaults for any other name.
const ProductLimits& product_limits(const std::string& product);

// Peak memory per byte of texture of baking `spec` in all its formats: the
// product's cheapest format, plus what each format asks beyond it (writers
// run one after the other, but freed memory is not all reused), at least
// kMinWorkingFactor.
double working_factor(const OutputSpec& spec);

// Layers of the output's texture: sky-view views, sky-preview panels; else 1.
int output_layers(const OutputSpec& spec);

// Channels of the output's texture (4 for a product this table does not know).
int output_channels(const OutputSpec& spec);

// Texels of the output's texture, all layers (and for cloud_types its type
// columns, counting the most types a clouds section can hold); saturates at
// UINT64_MAX.
std::uint64_t output_texels(const OutputSpec& spec);

// The budget's unit: output_texels at 4 float32 channels (16 bytes).
std::uint64_t output_texture_bytes(const OutputSpec& spec);

// Peak memory of baking the output: working_factor x output_texture_bytes.
std::uint64_t output_peak_bytes(const OutputSpec& spec);

}  // namespace skybake
