// The FILE arguments of `info` and `check-tiling`: files, folders and glob
// patterns, as bake takes presets (docs/formats.md "Reading files").
#pragma once

#include <string>
#include <vector>

namespace skybake::cli {

// Each entry expanded: a file as named; a folder to the files below it,
// recursively, whose extension is one read_texture_file reads (exr, dds,
// ktx2, vdb); a pattern to what it matches, a matched folder as a folder.
// Sorted within each entry, entries in the order given, each path once.
// A named file or folder that does not exist is an IoError ("<path>: no
// such file", exit 4); a pattern that matches nothing, or a folder with no
// texture file, a UsageError (exit 2).
std::vector<std::string> expand_texture_files(const std::vector<std::string>& entries);

}  // namespace skybake::cli
