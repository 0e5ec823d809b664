// skybake validate: schema and semantic checks of each preset, of the kind
// its $schema names (scene, planet, atmosphere, clouds); every problem of a
// file in one error (pipeline/preset_loader.hpp); folders and globs expand
// to scene presets as in bake (cli/errors.hpp); keys that have no effect
// as warnings (errors under --strict); exit 0 when all are valid, 1
// otherwise (every file is checked).
#include <cstdio>
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "core/error.hpp"
#include "pipeline/preset_loader.hpp"

namespace skybake::cli {

namespace {

nlohmann::json problems_json(const std::vector<PresetProblem>& problems) {
  nlohmann::json list = nlohmann::json::array();
  for (const PresetProblem& p : problems)
    list.push_back({{"file", p.file}, {"pointer", p.pointer}, {"rule", p.rule}});
  return list;
}

}  // namespace

int run_validate(const ValidateArgs& args) {
  // Files of any kind as named; folders and globs as bake expands them.
  std::vector<std::string> presets;
  for (const auto& path : expand_presets(args.presets)) presets.push_back(path.string());
  int status = kExitOk;
  nlohmann::json results = nlohmann::json::array();
  std::map<std::string, std::string> scene_files;  // by scene name: as bake refuses them
  for (const std::string& preset : presets) {
    try {
      const PresetCheck check = check_preset(preset);
      if (check.kind == "scene") {
        const auto [it, fresh] = scene_files.emplace(check.scene_name, preset);
        if (!fresh) throw duplicate_scene_name(preset, it->first, it->second);
      }
      nlohmann::json result = {{"preset", preset},
                               {"valid", true},
                               {"kind", check.kind},
                               {"warnings", problems_json(check.warnings)}};
      if (check.kind == "scene") result["scene"] = check.scene_name;
      if (args.strict && !check.warnings.empty()) {
        // Under --strict the warnings are this file's errors.
        const PresetError e(check.warnings);
        status = kExitFailure;
        result["valid"] = false;
        result["problems"] = result["warnings"];
        result["message"] = e.what();
        if (!args.json) std::fprintf(stderr, "skybake: error: %s\n", e.what());
      } else if (!args.json) {
        for (const PresetProblem& w : check.warnings)
          std::fprintf(stderr, "skybake: warning: %s\n", w.line().c_str());
      }
      results.push_back(result);
      if (args.quiet || args.json || !result["valid"].get<bool>()) continue;
      if (check.kind == "scene")
        std::printf("ok      %s (scene '%s', %zu outputs)\n", preset.c_str(),
                    check.scene_name.c_str(), check.outputs);
      else
        std::printf("ok      %s (%s preset)\n", preset.c_str(), check.kind.c_str());
    } catch (const PresetError& e) {
      status = kExitFailure;
      results.push_back({{"preset", preset},
                         {"valid", false},
                         {"file", e.file()},
                         {"pointer", e.pointer()},
                         {"rule", e.rule()},
                         {"problems", problems_json(e.problems())},
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
