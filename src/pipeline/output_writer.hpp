// Writes one baked texture in every format its output asks for, each to a
// temporary name first; all are renamed into place only once every format
// has been written, so a failure leaves neither partial nor mixed files.
#pragma once

#include <filesystem>
#include <vector>

#include "core/texture.hpp"
#include "io/manifest.hpp"
#include "pipeline/product.hpp"

namespace skybake {

std::vector<ManifestFile> write_outputs(const Texture& tex, const ProductInfo& info,
                                        const OutputSpec& spec,
                                        const std::filesystem::path& scene_dir);

}  // namespace skybake
