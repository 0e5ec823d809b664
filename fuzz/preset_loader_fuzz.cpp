// The preset loader on arbitrary bytes: strict JSON parsing, the nesting
// limit, schema validation, reference inlining (the shipped atmosphere and
// cloud presets sit beside the input, so references resolve) and the
// semantic checks.
#include <filesystem>

#include "fuzz_support.hpp"
#include "pipeline/preset_loader.hpp"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const fs::path presets = fs::path(SKYBAKE_SOURCE_DIR) / "presets";
  for (const char* folder : {"atmospheres", "clouds"})
    fs::copy(presets / folder, skybake::fuzz::work_dir() / folder,
             fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "scene.json");
  skybake::fuzz::expect_no_internal_error([&] { skybake::load_scene(path); });
  return 0;
}
