#include "pipeline/non_finite_output.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

std::string first_non_finite(const Texture& tex) {
  if (texture_is_finite(tex)) return "";
  const size_t nc = tex.channels.size();
  for (size_t i = 0; i < tex.data.size(); ++i) {
    if (std::isfinite(tex.data[i])) continue;
    size_t t = i / nc;
    const int x = int(t % size_t(tex.width));
    t /= size_t(tex.width);
    const int y = int(t % size_t(tex.height));
    t /= size_t(tex.height);
    return fmt::format("{} at texel x={} y={} z={} layer={} channel {}", tex.data[i], x, y,
                       int(t % size_t(tex.depth)), int(t / size_t(tex.depth)),
                       tex.channels[i % nc]);
  }
  return "";
}

void refuse_non_finite(const Scene& scene, const GraphNode& node, const Texture& tex) {
  const std::string where = first_non_finite(tex);
  if (where.empty()) return;
  std::string pointer = "/outputs";
  for (size_t i = 0; i < scene.outputs.size(); ++i)
    if (scene.outputs[i].name == node.spec.name) pointer = fmt::format("/outputs/{}", i);
  throw PresetError(scene.file.string(), pointer,
                    fmt::format("{} came out non-finite ({}): this preset's values are past "
                                "what the {} baker computes; see docs/presets.md, \"Numerical "
                                "limits\"",
                                node.spec.name == node.info->name
                                    ? node.spec.name
                                    : node.spec.name + " (" + node.info->name + ")",
                                where, node.info->name));
}

}  // namespace skybake
