// DDS format and header of an output, and their rules (dds_output.hpp).
#include "pipeline/dds_output.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "pipeline/output_budget.hpp"
#include "pipeline/product_options.hpp"

namespace skybake {
namespace {

// The block format that stores exactly `channels` channels.
DdsFormat block_format_for(int channels) {
  static const DdsFormat by_channels[] = {DdsFormat::BC4_UNORM, DdsFormat::BC5_UNORM,
                                          DdsFormat::BC1_UNORM, DdsFormat::BC3_UNORM};
  return by_channels[std::clamp(channels, 1, 4) - 1];
}

std::string channels_word(int n) {
  return fmt::format("{} channel{}", n, n == 1 ? "" : "s");
}

// A hint for products that can bake fewer channels.
std::string fewer_channels_hint(const OutputSpec& spec) {
  if (spec.product == "curl") return "; curl's \"channels\": \"rg\" bakes the 2D curl alone";
  return "";
}

std::vector<ProductProblem> format_problems(const OutputSpec& spec, const ProductInfo& info,
                                            DdsFormat format, int channels) {
  const std::string name = dxgi_format_name(format);
  const int components = dds_component_count(format);
  if (channels > components)
    return {{"/dds_format",
             fmt::format("expected a format with at least {} channels ({} has {}), got {} ({}){}",
                         channels, spec.product, channels, name, channels_word(components),
                         fewer_channels_hint(spec))}};
  if (!dds_is_block_compressed(format)) return {};
  if (info.default_dds_format != "unorm8")
    return {{"/dds_format",
             fmt::format("expected a float or uncompressed format for {}, got {}: block "
                         "compression stores [0, 1] at 8 bits per endpoint, for the 8-bit "
                         "cloud textures (noise_shape, noise_detail, curl, weather, "
                         "cloud_types, height_gradients, cirrus), not a float table",
                         spec.product, name)}};
  if (components != channels)
    return {{"/dds_format",
             fmt::format("expected the block format of {} ({} has {}), got {} ({}); a "
                         "block format stores exactly its channels",
                         dxgi_format_name(block_format_for(channels)), spec.product,
                         channels_word(channels), name, channels_word(components))}};
  return {};
}

std::vector<ProductProblem> header_problems(const OutputSpec& spec, DdsFormat format) {
  // Only a legacy header the preset asks for: the default is legacy only where it can be.
  if (option_string(spec, "dds_header", "") != "legacy") return {};
  if (!dds_has_legacy_form(format))
    return {{"/dds_header",
             fmt::format("{} has no legacy (pre-DX10) pixel format; use dds_header \"dx10\" or "
                         "another dds_format",
                         dxgi_format_name(format))}};
  const int layers = output_layers(spec);
  if (layers > 1)
    return {{"/dds_header",
             fmt::format("a legacy (pre-DX10) header has no array size, and {} writes {} layers "
                         "as a 2D array; use dds_header \"dx10\"",
                         spec.product, layers)}};
  return {};
}

}  // namespace

DdsFormat output_dds_format(const OutputSpec& spec, const ProductInfo& info, int channels) {
  const std::string name = option_string(spec, "dds_format", info.default_dds_format);
  if (name == "unorm8")
    return channels == 1   ? DdsFormat::R8_UNORM
           : channels == 2 ? DdsFormat::R8G8_UNORM
                           : DdsFormat::R8G8B8A8_UNORM;
  if (!name.empty()) return dds_format_from_name(name);
  if (spec.precision == "half" || info.half_files)
    return channels == 1 ? DdsFormat::R16_FLOAT : DdsFormat::R16G16B16A16_FLOAT;
  return DdsFormat::R32G32B32A32_FLOAT;
}

DdsHeader output_dds_header(const OutputSpec& spec, DdsFormat format, int layers) {
  const std::string header = option_string(spec, "dds_header", "");
  if (header.empty()) return dds_default_header(format, layers);
  return header == "legacy" ? DdsHeader::legacy : DdsHeader::dx10;
}

std::vector<ProductProblem> dds_output_problems(const OutputSpec& spec, const ProductInfo& info) {
  const bool dds = std::find(spec.formats.begin(), spec.formats.end(), "dds") != spec.formats.end();
  if (!dds) return {};  // dds_format and dds_header without DDS: warnings
  const int channels = output_channels(spec);
  const DdsFormat format = output_dds_format(spec, info, channels);
  std::vector<ProductProblem> problems = format_problems(spec, info, format, channels);
  for (ProductProblem& p : header_problems(spec, format)) problems.push_back(std::move(p));
  return problems;
}

}  // namespace skybake
