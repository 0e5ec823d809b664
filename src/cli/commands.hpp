// The subcommands of the skybake executable, one function each, free of
// CLI11 so they stay small and testable; main.cpp parses the command line
// (the only translation unit that includes CLI11) and calls them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/read_budget.hpp"

namespace skybake::cli {

struct BakeArgs {
  std::vector<std::string> presets;
  std::string out_dir = "out";
  std::vector<std::string> only;
  int threads = 0;  // 0 = all cores
  bool force = false;
  bool verify = false;  // hash every recorded file (pipeline/freshness.hpp)
  bool quiet = false;
  bool verbose = false;  // log reasons, reads, threads and timings on stderr
  bool json = false;
  bool strict = false;  // any warning exits 1, after the files are written and recorded
  bool emit_shader_constants = false;  // <output>.glsl and .hlsl beside each output
};
int run_bake(const BakeArgs& args);

struct ValidateArgs {
  std::vector<std::string> presets;
  bool strict = false;  // keys that have no effect are errors (exit 1), not warnings
  bool quiet = false;
  bool json = false;
};
int run_validate(const ValidateArgs& args);

struct PlanArgs {
  std::vector<std::string> catalog;  // preset files, folders, globs
  std::string out_dir = "out";       // read for the state, never written
  std::vector<std::string> only;
  bool json = false;
  std::string emit;         // "", "ninja" or "slurm"
  std::string emit_file;    // file for --emit (default stdout)
  std::string launcher;     // ninja: command prefix for each edge
  int threads = 1;          // --threads of each emitted task
  std::string edges = "scene";  // ninja: one edge per "scene" (chunk of scenes) or "product"
  int chunk = 1;            // presets per slurm array task or ninja scene edge
  int max_parallel = 0;     // slurm: array throttle
  bool strict = false;      // emitted tasks run `bake --strict`
  std::string self;         // path of this executable
};
int run_plan(const PlanArgs& args);

struct InfoArgs {
  std::vector<std::string> files;
  bool json = false;
  uint64_t max_memory = kDefaultReadBudget;  // io/read_budget.hpp
};
int run_info(const InfoArgs& args);

struct CheckTilingArgs {
  std::vector<std::string> files;
  double tolerance = 0.25;  // values margin of the seam over the median face (core/tiling.hpp)
  bool quiet = false;
  bool json = false;
  uint64_t max_memory = kDefaultReadBudget;  // io/read_budget.hpp
};
int run_check_tiling(const CheckTilingArgs& args);

struct ReportArgs {
  std::vector<std::string> presets;   // files, folders, globs
  std::string out_dir = "out";
  std::vector<std::string> only;      // empty: every product the scene requests
  int threads = 0;                    // 0 = all cores
  bool quick = false;                 // fewer ladder points, queries and paths
  int paths = 0;                      // > 0: path tracer paths per view (every order)
  bool quiet = false;
  bool json = false;
};
int run_report(const ReportArgs& args);

}  // namespace skybake::cli
