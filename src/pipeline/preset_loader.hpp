// Loading a scene preset (docs/presets.md): read, parse strictly, validate
// against schemas/scene.schema.json, inline the referenced planet / atmosphere
// files (validated against their own schemas), fill defaults, convert to SI
// units, validate each output against the product registry and
// schemas/products/<product>.schema.json, then run the semantic checks a
// schema cannot express (top radius above the ground, tent order, sizes and
// memory budget, unique products and names, allowed formats).
//
// Every user error is a PresetError naming the file that holds the mistake,
// the JSON pointer inside it and the rule; one error lists every problem
// found in the preset and the files it references (schema violations, then
// the semantic checks of the sections whose schema holds); nothing is
// allocated for an output before its size has passed the budget.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/product.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Loads and validates a scene preset. Scene.resolved is the preset with
// references inlined, defaults filled in and "$schema" / "description" keys
// removed (they do not change any output), dumped by nlohmann with sorted
// keys: a canonical hash input.
// Throws IoError when `file` cannot be read, PresetError for any invalid
// content (including a referenced file that is missing or invalid).
Scene load_scene(const std::filesystem::path& file);

// The scenes of one run, loaded in order. Two scenes of one name would bake
// into one folder (out/<name>/), the later overwriting the earlier's
// manifest: a PresetError (exit 3) at the later file's /name, naming the
// earlier file.
std::vector<Scene> load_scenes(const std::vector<std::filesystem::path>& files);

// That error: `file` holds a scene named `name`, as does `first_file`.
PresetError duplicate_scene_name(const std::string& file, const std::string& name,
                                 const std::string& first_file);

// What `skybake validate` learns of a preset file of any kind.
struct PresetCheck {
  std::string kind;                     // "scene", "planet", "atmosphere" or "clouds"
  std::string scene_name;               // scenes only
  size_t outputs = 0;                   // scenes only
  std::vector<PresetProblem> warnings;  // keys that have no effect (Scene::warnings)
};

// Checks a preset of the kind its "$schema" names by file name (scene,
// planet, atmosphere or clouds .schema.json; a scene when there is none)
// against that schema of schemas/ and the semantic rules of that kind (a
// scene through load_scene). Throws IoError when the file cannot be read,
// PresetError listing every problem found, also for a "$schema" that names
// none of them.
PresetCheck check_preset(const std::filesystem::path& file);

// Memory budget of one output, checked before anything is allocated.
constexpr std::uint64_t kMaxOutputBytes = std::uint64_t(2) << 30;  // 2 GiB

// Bytes an output of `size` texels (all axes) takes at 4 float32 channels.
std::uint64_t output_bytes(const std::vector<int>& size);

// Checks `size` against the product's axis count, per-axis maximum and the
// memory budget. Throws PresetError(file, pointer or pointer/<axis>, rule).
void check_output_size(const ProductInfo& product, const std::vector<int>& size,
                       const std::string& file, const std::string& pointer);

}  // namespace skybake
