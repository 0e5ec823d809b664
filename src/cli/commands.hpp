// The subcommands of the skybake executable, one function each, free of
// CLI11 so they stay small and testable; main.cpp parses the command line
// (the only translation unit that includes CLI11) and calls them.
#pragma once

#include <string>
#include <vector>

namespace skybake::cli {

struct BakeArgs {
  std::vector<std::string> presets;
  std::string out_dir = "out";
  std::vector<std::string> only;
  int threads = 0;  // 0 = all cores
  bool force = false;
  bool quiet = false;
  bool json = false;
};
int run_bake(const BakeArgs& args);

struct ValidateArgs {
  std::vector<std::string> presets;
  bool quiet = false;
  bool json = false;
};
int run_validate(const ValidateArgs& args);

struct PlanArgs {
  std::vector<std::string> presets;
  std::string out_dir = "out";
  std::vector<std::string> only;
  bool json = false;
};
int run_plan(const PlanArgs& args);

struct InfoArgs {
  std::vector<std::string> files;
  bool json = false;
};
int run_info(const InfoArgs& args);

}  // namespace skybake::cli
