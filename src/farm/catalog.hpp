// A catalog: the scene presets named on a command line as files, folders
// (searched recursively) or glob patterns. In a folder, a .json file is a
// scene preset when it has an "outputs" key; other JSON there (atmosphere or
// planet presets it references) is skipped. Files named explicitly are always
// taken as scenes, so their errors are reported.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace skybake {

// Sorted, without duplicates. Throws UsageError when an entry matches nothing.
std::vector<std::filesystem::path> expand_catalog(const std::vector<std::string>& entries);

}  // namespace skybake
