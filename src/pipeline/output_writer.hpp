// Writes one baked texture in every format its output asks for, each to a
// temporary name first; all are renamed into place only once every format
// has been written, so a failure leaves neither partial nor mixed files.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/texture.hpp"
#include "io/manifest.hpp"
#include "pipeline/product.hpp"

namespace skybake {

// Every format write_outputs writes, in the order help text lists them:
// "exr", "dds", "ktx2", "vdb", "png" (each product allows some of them).
const std::vector<std::string>& output_formats();

// The file names an output writes, one per format, relative to the scene folder.
std::vector<std::string> output_files(const OutputSpec& spec);

// `on_file`, when given, hears each file's name before it is written, with
// the fraction of the output's files written so far.
using WriteProgress = std::function<void(const std::string& file, double fraction)>;
std::vector<ManifestFile> write_outputs(const Texture& tex, const ProductInfo& info,
                                        const OutputSpec& spec,
                                        const std::filesystem::path& scene_dir,
                                        const WriteProgress& on_file = {});

}  // namespace skybake
