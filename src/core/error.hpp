// The small family of user-facing errors. Programmer invariants use assert();
// anything a user can cause (a bad preset, an unreadable file, a graph that
// cannot be built) throws one of these, is caught once in main and printed as
// `skybake: error: <message>` with the exit code of its kind.
#pragma once

#include <stdexcept>
#include <string>

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

// A preset is malformed. The message names file, JSON pointer and rule:
//   presets/x.json: /atmosphere/top_radius_km: must be greater than ... (6360 <= 6360)
class PresetError : public Error {
 public:
  PresetError(const std::string& file, const std::string& pointer, const std::string& rule)
      : Error(file + ": " + (pointer.empty() ? std::string("/") : pointer) + ": " + rule),
        file_(file), pointer_(pointer), rule_(rule) {}
  int exit_code() const override { return kExitPreset; }
  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string file_, pointer_, rule_;
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
