// skybake validate: schema and semantic checks of each preset; one line per
// file; exit 0 when all are valid, 1 otherwise (every file is checked).
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "pipeline/preset_loader.hpp"

namespace skybake::cli {

int run_validate(const ValidateArgs& args) {
  require_files(args.presets);
  int status = kExitOk;
  nlohmann::json results = nlohmann::json::array();
  for (const std::string& preset : args.presets) {
    try {
      const Scene scene = load_scene(preset);
      results.push_back({{"preset", preset}, {"valid", true}, {"scene", scene.name}});
      if (!args.quiet && !args.json)
        std::printf("ok      %s (scene '%s', %zu outputs)\n", preset.c_str(), scene.name.c_str(),
                    scene.outputs.size());
    } catch (const PresetError& e) {
      status = kExitFailure;
      results.push_back({{"preset", preset},
                         {"valid", false},
                         {"file", e.file()},
                         {"pointer", e.pointer()},
                         {"rule", e.rule()},
                         {"message", e.what()}});
      if (!args.json) std::fprintf(stderr, "skybake: error: %s\n", e.what());
    } catch (const IoError& e) {
      status = kExitFailure;
      results.push_back({{"preset", preset}, {"valid", false}, {"message", e.what()}});
      if (!args.json) std::fprintf(stderr, "skybake: error: %s\n", e.what());
    }
  }
  if (args.json)
    std::cout << nlohmann::json{{"ok", status == kExitOk}, {"presets", results}}.dump(2) << "\n";
  return status;
}

}  // namespace skybake::cli
