// Stamps for build tools that compare file times: <scene_dir>/.stamps/<output
// name>.stamp holds the output's input hash. It is rewritten only when the
// hash changes, so ninja with `restat` sees an unchanged stamp when a re-run
// was a no-op (docs/farm.md).
#pragma once

#include <filesystem>
#include <string>

namespace skybake {

std::filesystem::path stamp_path(const std::filesystem::path& scene_dir, const std::string& name);

// Writes the stamp atomically unless it already holds `hash`.
void update_stamp(const std::filesystem::path& scene_dir, const std::string& name,
                  const std::string& hash);

}  // namespace skybake
