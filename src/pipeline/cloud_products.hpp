// The cloud products' rules that the preset loader also needs.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/product.hpp"

namespace skybake {

// Semantic rules of a scene's resolved "clouds" section (pointers relative to
// the section), checked at preset load.
std::vector<ProductProblem> clouds_section_problems(const nlohmann::json& clouds);

}  // namespace skybake
