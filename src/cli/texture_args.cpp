#include "cli/texture_args.hpp"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/texture_file.hpp"

namespace fs = std::filesystem;

namespace skybake::cli {

namespace {

bool is_texture_file(const fs::path& p) {
  if (!fs::is_regular_file(p)) return false;
  std::string ext = p.extension().string();
  if (ext.empty()) return false;
  ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::vector<std::string>& formats = texture_file_formats();
  return std::find(formats.begin(), formats.end(), ext) != formats.end();
}

// The texture files below `folder`, sorted.
std::vector<std::string> folder_files(const fs::path& folder) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (is_texture_file(e.path())) out.push_back(e.path().lexically_normal().string());
  std::sort(out.begin(), out.end());
  if (out.empty())
    throw UsageError(fmt::format("{}: a folder with no {} file", folder.string(),
                                 fmt::join(texture_file_formats(), ", ")));
  return out;
}

std::vector<std::string> pattern_files(const std::string& pattern) {
  std::vector<std::string> out;
  glob_t g{};
  if (::glob(pattern.c_str(), 0, nullptr, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; ++i) {
      const fs::path p = g.gl_pathv[i];
      if (fs::is_directory(p)) {
        const std::vector<std::string> inside = folder_files(p);
        out.insert(out.end(), inside.begin(), inside.end());
      } else {
        out.push_back(p.lexically_normal().string());
      }
    }
  }
  globfree(&g);
  if (out.empty())
    throw UsageError(fmt::format("{}: no such file, folder or matching pattern", pattern));
  return out;
}

}  // namespace

std::vector<std::string> expand_texture_files(const std::vector<std::string>& entries) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const std::string& entry : entries) {
    std::vector<std::string> files;
    if (fs::is_directory(entry))
      files = folder_files(entry);
    else if (fs::exists(entry))
      files = {entry};
    else if (entry.find_first_of("*?[") != std::string::npos)
      files = pattern_files(entry);
    else
      throw IoError(entry + ": no such file");
    for (const std::string& f : files)
      if (seen.insert(f).second) out.push_back(f);
  }
  return out;
}

}  // namespace skybake::cli
