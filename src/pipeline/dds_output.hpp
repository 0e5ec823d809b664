// What an output's DDS file is: its format (dds_format, the product's
// default, or from precision) and its header (dds_header), and the rules the
// scene schema cannot state about them (docs/presets.md "DDS outputs",
// docs/formats.md "DDS"). The loader reports the rules; the output writer
// uses the same choice, so what validates is what is written.
#pragma once

#include <vector>

#include "io/dds.hpp"
#include "pipeline/product.hpp"

namespace skybake {

// The DDS format of `spec` for a texture of `channels` channels: dds_format
// when given; the product's default otherwise, where "unorm8" is R8_UNORM,
// R8G8_UNORM or R8G8B8A8_UNORM by channel count; with neither, float:
// precision "half" gives R16_FLOAT (one channel) or R16G16B16A16_FLOAT, else
// R32G32B32A32_FLOAT.
DdsFormat output_dds_format(const OutputSpec& spec, const ProductInfo& info, int channels);

// dds_header: "dx10" or "legacy" when given; else dds_default_header of the
// format for a texture of `layers` layers (legacy for the 8-bit and block
// formats tools outside engines read, DX10 for the rest).
DdsHeader output_dds_header(const OutputSpec& spec, DdsFormat format, int layers);

// The DDS rules of one output, with pointers relative to the output object:
// a dds_format with fewer channels than the product; a block format on a
// product that is not 8-bit [0, 1] data (the float tables), or whose channel
// count differs from the product's; a legacy header for a format without
// one, or for a product written as a 2D array (skyview's views, the sky
// preview's panels). Empty when the output writes no DDS (its DDS keys then
// have no effect: a warning of the preset loader).
std::vector<ProductProblem> dds_output_problems(const OutputSpec& spec, const ProductInfo& info);

}  // namespace skybake
