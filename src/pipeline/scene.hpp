// A loaded scene preset: everything in SI units, references to other preset
// files resolved, defaults filled in. Produced only by load_scene()
// (preset_loader.hpp), which validates against schemas/ first.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "core/error.hpp"
#include "pipeline/spectral_scene.hpp"

namespace skybake {

// One requested output: a product, how big, and in which files.
struct OutputSpec {
  std::string product;               // registry name, e.g. "transmittance"
  std::string name;                  // file stem inside out/<scene>/, never a path
  std::vector<int> size;             // product axes, e.g. {256, 64}; defaults filled in
  std::vector<std::string> formats;  // subset of "exr", "dds", "vdb", "png"
  std::string precision = "float";   // "float" or "half" (EXR channels, DDS float formats)
  nlohmann::json options;            // the output object as written (product-specific keys)
  std::string pointer;               // JSON pointer of this output in the preset, for messages
};

struct Scene {
  std::string name;             // output folder name under the output directory
  std::filesystem::path file;   // the preset file as given on the command line
  std::vector<std::filesystem::path> sources;  // file and the preset files it references
  bool has_atmosphere = false;  // planet + atmosphere given (cloud-only scenes have neither)
  Atmosphere atmosphere;        // SI units; defaults when !has_atmosphere
  // The spectral bake the preset asks for ("spectral"), or null: RGB.
  std::shared_ptr<const SpectralScene> spectral;
  nlohmann::json resolved;      // the preset with references inlined (hash input)
  std::vector<OutputSpec> outputs;
  // Keys written in the preset that change nothing (validate reports them).
  std::vector<PresetProblem> warnings;

  const OutputSpec* find_output(const std::string& product) const {
    for (const OutputSpec& o : outputs)
      if (o.product == product) return &o;
    return nullptr;
  }
};

}  // namespace skybake
