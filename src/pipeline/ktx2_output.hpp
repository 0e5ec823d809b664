// What an output's KTX2 file is: its format (ktx2_format, else the DDS
// default's choice in the smallest format that holds the channels) and the
// rules the scene schema cannot state about it (docs/presets.md,
// docs/formats.md "KTX2"). The loader reports the rules; the output writer
// uses the same choice, so what validates is what is written.
#pragma once

#include <vector>

#include "io/ktx2_format.hpp"
#include "pipeline/product.hpp"

namespace skybake {

// The KTX2 format of `spec` for a texture of `channels` channels:
// ktx2_format when given; for the products whose DDS is 8-bit, R8_UNORM,
// R8G8_UNORM or R8G8B8A8_UNORM by channel count; otherwise float: precision
// "half" gives R16_SFLOAT (one channel) or R16G16B16A16_SFLOAT, else
// R32_SFLOAT or R32G32B32A32_SFLOAT.
Ktx2Format output_ktx2_format(const OutputSpec& spec, const ProductInfo& info, int channels);

// The KTX2 rules of one output, with pointers relative to the output object:
// ktx2_format without "ktx2" in formats; a format with fewer channels than
// the product's texture; a block format on a product that is not 8-bit
// [0, 1] data (the float tables), or whose channel count differs from the
// product's (as for DDS).
std::vector<ProductProblem> ktx2_output_problems(const OutputSpec& spec, const ProductInfo& info);

}  // namespace skybake
