// Reads a current output back from disk instead of recomputing it, so that
// `bake --only X` can use X's inputs baked by another farm node.
#pragma once

#include <filesystem>
#include <optional>

#include "core/texture.hpp"
#include "io/manifest.hpp"

namespace skybake {

// The texture of a manifest entry, read from one of its lossless files (float
// EXR, float32 KTX2, or R32G32B32A32_FLOAT DDS trimmed to the entry's
// channels, with the entry's metadata). float32 values come back bit-exactly, so a dependent is
// identical whether its input was read or recomputed. nullopt when no file is
// lossless or readable.
std::optional<Texture> read_lossless_output(const ManifestEntry& entry,
                                            const std::filesystem::path& dir);

}  // namespace skybake
