#include "io/plugin_library.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>

namespace skybake {

namespace {

std::string executable_dir() {
  char buffer[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return "";
  const std::string exe(buffer, size_t(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? "" : exe.substr(0, slash);
}

std::vector<std::string> candidates(const char* env_var, const char* file_name) {
  if (const char* env = std::getenv(env_var); env && *env) return {env};
  std::vector<std::string> paths;
  if (const std::string dir = executable_dir(); !dir.empty())
    paths.push_back(dir + "/" + file_name);
#ifdef SKYBAKE_PLUGIN_BUILD_DIR
  const std::string built = std::string(SKYBAKE_PLUGIN_BUILD_DIR) + "/" + file_name;
  if (paths.empty() || paths.front() != built) paths.push_back(built);
#endif
  return paths;
}

}  // namespace

PluginLibrary open_plugin_library(const char* env_var, const char* file_name,
                                  const std::function<bool(void* handle)>& accept,
                                  const std::string& rejected) {
  std::vector<std::string> tried;
  for (const std::string& path : candidates(env_var, file_name)) {
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      tried.push_back(fmt::format("{} ({})", path, why ? why : "cannot open"));
      continue;
    }
    if (accept(handle)) return {handle, ""};
    tried.push_back(fmt::format("{} ({})", path, rejected));
    ::dlclose(handle);
  }
  std::string list;
  for (const std::string& t : tried) list += (list.empty() ? "" : "; ") + t;
  return {nullptr, list.empty() ? std::string("tried no path") : "tried " + list};
}

}  // namespace skybake
