// The loader's bookkeeping shared by its files (preset_loader.cpp,
// atmosphere_preset.cpp, output_preset.cpp): where a JSON subtree came from,
// and the list of problems one run reports. Internal to pipeline/.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace skybake::preset {

// Schema violations looked for in one document before giving up.
constexpr size_t kMaxSchemaViolations = 100;

// Where a JSON subtree came from: the file and the subtree's pointer in it.
struct Source {
  std::string file;
  std::string prefix;

  [[noreturn]] void fail(const std::string& pointer, const std::string& rule) const {
    throw PresetError(file, prefix + pointer, rule);
  }
};

// The problems of one preset and of the files it references, collected so
// that one run reports all of them (PresetError lists the first
// kMaxListedProblems and counts the rest).
class Problems {
 public:
  void add(const Source& src, const std::string& pointer, const std::string& rule) {
    list_.push_back({src.file, src.prefix + pointer, rule});
  }
  // Runs `check`; the problems of a PresetError it throws are kept instead,
  // and false is returned.
  template <typename Check>
  bool collect(Check&& check) {
    try {
      check();
      return true;
    } catch (const PresetError& e) {
      list_.insert(list_.end(), e.problems().begin(), e.problems().end());
      return false;
    }
  }
  bool empty() const { return list_.empty(); }
  size_t size() const { return list_.size(); }
  void throw_if_any() const {
    if (!list_.empty()) throw PresetError(list_);
  }

 private:
  std::vector<PresetProblem> list_;
};

inline std::string token(const std::string& key) {
  return (nlohmann::json::json_pointer() / key).to_string();
}
inline std::string token(size_t index) {
  return "/" + std::to_string(index);
}


}  // namespace skybake::preset
