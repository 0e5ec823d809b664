// KTX2 format of an output, and its rules (ktx2_output.hpp).
#include "pipeline/ktx2_output.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "pipeline/output_budget.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {

namespace {

// The block format that stores exactly `channels` channels.
Ktx2Format block_format_for(int channels) {
  static const Ktx2Format by_channels[] = {Ktx2Format::BC4_UNORM_BLOCK, Ktx2Format::BC5_UNORM_BLOCK,
                                           Ktx2Format::BC1_RGB_UNORM_BLOCK,
                                           Ktx2Format::BC3_UNORM_BLOCK};
  return by_channels[std::clamp(channels, 1, 4) - 1];
}

std::string channels_word(int n) {
  return fmt::format("{} channel{}", n, n == 1 ? "" : "s");
}

}  // namespace

Ktx2Format output_ktx2_format(const OutputSpec& spec, const ProductInfo& info, int channels) {
  const std::string name = option_string(spec, "ktx2_format", "");
  if (!name.empty()) return ktx2_format_from_name(name);
  if (info.default_dds_format == "unorm8")
    return channels == 1   ? Ktx2Format::R8_UNORM
           : channels == 2 ? Ktx2Format::R8G8_UNORM
                           : Ktx2Format::R8G8B8A8_UNORM;
  if (spec.precision == "half" || info.half_files)
    return channels == 1 ? Ktx2Format::R16_SFLOAT : Ktx2Format::R16G16B16A16_SFLOAT;
  return channels == 1 ? Ktx2Format::R32_SFLOAT : Ktx2Format::R32G32B32A32_SFLOAT;
}

std::vector<ProductProblem> ktx2_output_problems(const OutputSpec& spec, const ProductInfo& info) {
  const bool ktx2 =
      std::find(spec.formats.begin(), spec.formats.end(), "ktx2") != spec.formats.end();
  // Without KTX2, ktx2_format has no effect: a warning of the preset loader.
  if (!spec.options.contains("ktx2_format") || !ktx2) return {};
  const int channels = output_channels(spec);
  const Ktx2FormatInfo& f = ktx2_format_info(output_ktx2_format(spec, info, channels));
  if (channels > f.components)
    return {{"/ktx2_format",
             fmt::format("expected a format with at least {} channels ({} has {}), got {} ({})",
                         channels, spec.product, channels, f.name, channels_word(f.components))}};
  if (f.encoding != Ktx2Encoding::bc) return {};
  if (info.default_dds_format != "unorm8")
    return {{"/ktx2_format",
             fmt::format("expected a float or uncompressed format for {}, got {}: block "
                         "compression stores [0, 1] at 8 bits per endpoint, for the 8-bit "
                         "cloud textures, not a float table",
                         spec.product, f.name)}};
  if (f.components != channels)
    return {{"/ktx2_format",
             fmt::format("expected the block format of {} ({} has {}), got {} ({}); a block "
                         "format stores exactly its channels",
                         ktx2_format_name(block_format_for(channels)), spec.product,
                         channels_word(channels), f.name, channels_word(f.components))}};
  return {};
}

}  // namespace skybake
