// One output of a scene preset into an OutputSpec (preset_loader.cpp calls
// it for each): the product's own keys against its schema with their
// defaults, the name (a file name on every system), the size, the formats
// and the writers' keys, and the memory budgets (output_budget.hpp).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/preset_source.hpp"
#include "pipeline/product.hpp"

namespace skybake::preset {

// `products` and `names` hold the outputs read so far (for the "once per
// scene" and "one name" rules); `out` receives the defaults it lacked.
OutputSpec output_from(nlohmann::json& out, size_t index, const std::string& file,
                       std::map<std::string, size_t>& products,
                       std::map<std::string, size_t>& names, bool has_atmosphere,
                       bool has_clouds, Problems& problems);

// A name that becomes a folder or file name: no control character (a NUL
// would cut it short), at most 255 bytes with `longest_suffix`.
void check_name_bytes(const std::string& name, const std::string& longest_suffix,
                      const Source& src, const std::string& pointer);

// Every texture of a scene stays in memory until the scene is baked; with
// the largest bake's working memory, within the bake budget.
void check_scene_budget(const std::vector<OutputSpec>& outputs, const Source& src);

}  // namespace skybake::preset
