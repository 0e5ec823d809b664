#include "pipeline/freshness.hpp"

#include <fmt/format.h>

#include "pipeline/output_writer.hpp"

namespace skybake {

Freshness check_freshness(const GraphNode& node, const Manifest& manifest,
                          const std::filesystem::path& scene_dir) {
  auto it = manifest.entries.find(node.spec.name);
  if (it == manifest.entries.end()) return {false, "not baked yet"};
  const ManifestEntry& entry = it->second;
  if (entry.input_hash != node.input_hash)
    return {false, fmt::format("inputs changed (hash {} -> {})", entry.input_hash,
                               node.input_hash)};
  for (const std::string& file : output_files(node.spec))
    if (!std::filesystem::exists(scene_dir / file)) return {false, "missing file " + file};
  return {true, "up to date"};
}

}  // namespace skybake
