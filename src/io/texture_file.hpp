// Reads any texture file skybake writes (EXR, DDS, KTX2, VDB), chosen by
// extension, into the one Texture type: for `skybake info`, `check-tiling`
// and tests.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/texture.hpp"
#include "io/read_budget.hpp"

namespace skybake {

struct LoadedTexture {
  Texture texture;       // level 0
  std::string format;    // "exr", "dds", "ktx2", "vdb"
  std::string encoding;  // "half", "float", DXGI format name...
  int mip_levels = 1;
  std::vector<Texture> lower_levels;  // mip levels 1, 2, ... of a DDS or KTX2 mip chain; else empty
  nlohmann::json details = nlohmann::json::object();  // format-specific header fields
};

// The formats read_texture_file reads, by extension without the dot:
// "exr", "dds", "ktx2", "vdb" (for messages and help text).
const std::vector<std::string>& texture_file_formats();

// Throws IoError for unknown extensions and unreadable files, and for a file
// whose header announces more than `budget` bytes of what its reader holds
// at once (io/read_budget.hpp: info and check-tiling pass --max-memory).
LoadedTexture read_texture_file(const std::string& path, uint64_t budget = kNoReadBudget);

}  // namespace skybake
