// Shader constants headers: a GLSL and an HLSL file per output holding the
// constants its manifest entry records (sizes, radii, mapping constants...),
// so that a shader reads a baked table with the numbers it was baked with
// (docs/runtime.md "Shader constants"; `skybake bake --emit-shader-constants`).
//
// Names: SKYBAKE_<OUTPUT>_<KEY>, upper case, every run of characters other
// than letters and digits turned into one '_' ("mu_s.min" of output
// "transmittance" -> SKYBAKE_TRANSMITTANCE_MU_S_MIN); the entry's dimensions
// as _WIDTH, _HEIGHT, _DEPTH (volumes) and _LAYERS (arrays), first, unless
// the metadata records a key of that name itself. A name two keys map to
// gets _2, _3... in key order.
// Types: integers that fit an int are `int`, other integers up to 2^32 - 1
// `uint` (a longer string of digits is a hash: a comment), other numbers
// `float`, printed with 17 significant digits so that
// the shader compiler rounds the recorded double itself (never a rounding
// of a rounding); booleans `bool`; arrays of 2 or 3 numbers (int2, double3
// metadata) `ivec2`... `vec3` (HLSL `int2`... `float3`). A value of any
// other kind (text, longer lists) or a float beyond the float32 range is
// written as a comment.
// GLSL: `const float NAME = v;`  HLSL: `static const float NAME = v;`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/manifest.hpp"

namespace skybake {

enum class ShaderLanguage { glsl, hlsl };

// "glsl", "hlsl": the file extension and the manifest's file format.
const char* shader_language_name(ShaderLanguage language);

// The identifier part of a key: upper case, runs of non-alphanumerics as one '_'.
std::string shader_identifier(const std::string& key);

// The header text of one manifest entry. `tool` goes into its first line.
std::string shader_constants_text(const ManifestEntry& entry, ShaderLanguage language,
                                  const std::string& tool);

// Writes <name>.glsl and <name>.hlsl beside the files of each named output
// of the scene folder's manifest, from the entry as the manifest records it,
// and records them in that entry's files (format "glsl" / "hlsl", encoding
// "text"), under the folder lock. Returns the paths written. Throws IoError
// when a file cannot be written or a name is not in the manifest.
std::vector<std::filesystem::path> emit_shader_constants(const std::filesystem::path& scene_dir,
                                                         const std::vector<std::string>& outputs,
                                                         const std::string& tool);

}  // namespace skybake
