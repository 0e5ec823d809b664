// The small family of user-facing errors. Programmer invariants use assert();
// anything a user can cause (a bad preset, an unreadable file, a graph that
// cannot be built) throws one of these, is caught once in main and printed as
// `skybake: error: <message>` with the exit code of its kind.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace skybake {

// Exit codes of the skybake executable (README "Exit codes").
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,     // a check failed (validate, check-tiling)
  kExitUsage = 2,       // bad command line
  kExitPreset = 3,      // a preset is invalid
  kExitIo = 4,          // a file could not be read or written
  kExitInternal = 5,    // a bug: an invariant broke
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  virtual int exit_code() const { return kExitInternal; }
};

// One problem of a preset: the file that holds it, the JSON pointer, the rule.
struct PresetProblem {
  std::string file, pointer, rule;
  // "presets/x.json: /atmosphere/top_radius_km: must be ..." ("/" for the root).
  std::string line() const {
    return file + ": " + (pointer.empty() ? std::string("/") : pointer) + ": " + rule;
  }
};

// An error lists at most this many problems of one preset; the rest are counted.
constexpr size_t kMaxListedProblems = 20;

// A preset is malformed. The message names file, JSON pointer and rule:
//   presets/x.json: /atmosphere/top_radius_km: must be greater than ... (6360 <= 6360)
// With several problems the first is file() / pointer() / rule() and the
// message's first line; each further problem adds a line "  <file>: <pointer>:
// <rule>", up to kMaxListedProblems, then "  and N more".
class PresetError : public Error {
 public:
  PresetError(const std::string& file, const std::string& pointer, const std::string& rule)
      : PresetError(std::vector<PresetProblem>{{file, pointer, rule}}) {}
  // `problems` is not empty.
  explicit PresetError(std::vector<PresetProblem> problems)
      : Error(message(problems)), problems_(std::move(problems)) {}
  int exit_code() const override { return kExitPreset; }
  const std::string& file() const { return problems_.front().file; }
  const std::string& pointer() const { return problems_.front().pointer; }
  const std::string& rule() const { return problems_.front().rule; }
  // Every problem found, the first included (also those past the listed ones).
  const std::vector<PresetProblem>& problems() const { return problems_; }

 private:
  static std::string message(const std::vector<PresetProblem>& problems) {
    std::string m = problems.at(0).line();
    for (size_t i = 1; i < problems.size() && i < kMaxListedProblems; ++i)
      m += "\n  " + problems[i].line();
    if (problems.size() > kMaxListedProblems)
      m += "\n  and " + std::to_string(problems.size() - kMaxListedProblems) + " more";
    return m;
  }
  std::vector<PresetProblem> problems_;
};

class IoError : public Error {
 public:
  explicit IoError(const std::string& what) : Error(what) {}
  int exit_code() const override { return kExitIo; }
};

class UsageError : public Error {
 public:
  explicit UsageError(const std::string& what) : Error(what) {}
  int exit_code() const override { return kExitUsage; }
};

}  // namespace skybake
