// A baker that returns a NaN or an infinity for a preset that passed every
// check: the preset's values are past what that baker computes, which is a
// preset problem (exit 3, at the output's entry in "outputs"), never a file
// error (docs/presets.md, "Numerical limits").
#pragma once

#include <string>

#include "core/texture.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Where `tex` first holds a NaN or an infinity: "nan at texel x=0 y=27 z=0
// layer=0 channel R"; empty when every value is finite.
std::string first_non_finite(const Texture& tex);

// Throws PresetError naming the scene file, the output's pointer, the texel
// and the product when `tex`, baked for `node`, is not all finite.
void refuse_non_finite(const Scene& scene, const GraphNode& node, const Texture& tex);

}  // namespace skybake
