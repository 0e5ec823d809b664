#include "farm/catalog.hpp"

#include <glob.h>

#include <algorithm>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/json_input.hpp"
#include "core/safe_input.hpp"

namespace fs = std::filesystem;

namespace skybake {

namespace {

// A file too large or too deeply nested to tell counts as a scene, so that
// loading it names the limit instead of the folder silently skipping it.
bool looks_like_scene(const fs::path& file) {
  const FileText read = read_regular_file(file, kMaxJsonFileBytes);
  if (read.status == ReadStatus::missing) return false;
  if (read.status == ReadStatus::refused || json_nesting_problem(read.text)) return true;
  const ParsedJson parsed = parse_json_text(read.text);
  return parsed.value && parsed.value->is_object() && parsed.value->contains("outputs");
}

void add_folder(const fs::path& dir, std::vector<fs::path>& out) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".json" && looks_like_scene(e.path()))
      out.push_back(e.path().lexically_normal());
  }
}

}  // namespace

std::vector<fs::path> expand_catalog(const std::vector<std::string>& entries) {
  std::vector<fs::path> out;
  for (const std::string& entry : entries) {
    if (fs::is_directory(entry)) {
      add_folder(entry, out);
      continue;
    }
    if (fs::exists(entry)) {
      out.push_back(fs::path(entry).lexically_normal());
      continue;
    }
    glob_t g{};
    const int rc = ::glob(entry.c_str(), 0, nullptr, &g);
    size_t matched = 0;
    if (rc == 0) {
      for (size_t i = 0; i < g.gl_pathc; ++i) {
        const fs::path p = g.gl_pathv[i];
        if (fs::is_directory(p)) {
          add_folder(p, out);
        } else if (p.extension() == ".json") {
          out.push_back(p.lexically_normal());
        }
        ++matched;
      }
    }
    globfree(&g);
    if (matched == 0)
      throw UsageError(fmt::format("{}: no such preset file, folder or matching pattern", entry));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace skybake
