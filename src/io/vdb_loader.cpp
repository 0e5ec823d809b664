// write_vdb and read_vdb (vdb.hpp): forwarded to the VDB plugin, opened with
// dlopen on first use (vdb_plugin.hpp says why and where it is looked for).
#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/vdb.hpp"
#include "io/vdb_plugin.hpp"

namespace skybake {

namespace {

struct VdbPlugin {
  SkybakeVdbWriteFn* write = nullptr;
  SkybakeVdbReadFn* read = nullptr;
  std::string problem;  // why it could not be loaded, with every path tried
};

std::string executable_dir() {
  char buffer[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n <= 0) return "";
  const std::string exe(buffer, size_t(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? "" : exe.substr(0, slash);
}

std::vector<std::string> candidates() {
  if (const char* env = std::getenv("SKYBAKE_VDB_PLUGIN"); env && *env) return {env};
  std::vector<std::string> paths;
  if (const std::string dir = executable_dir(); !dir.empty())
    paths.push_back(dir + "/" + kVdbPluginName);
#ifdef SKYBAKE_PLUGIN_BUILD_DIR
  const std::string built = std::string(SKYBAKE_PLUGIN_BUILD_DIR) + "/" + kVdbPluginName;
  if (paths.empty() || paths.front() != built) paths.push_back(built);
#endif
  return paths;
}

VdbPlugin load() {
  VdbPlugin plugin;
  std::vector<std::string> tried;
  for (const std::string& path : candidates()) {
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      tried.push_back(fmt::format("{} ({})", path, why ? why : "cannot open"));
      continue;
    }
    auto* abi = reinterpret_cast<SkybakeVdbAbiFn*>(::dlsym(handle, "skybake_vdb_abi"));
    plugin.write = reinterpret_cast<SkybakeVdbWriteFn*>(::dlsym(handle, "skybake_vdb_write"));
    plugin.read = reinterpret_cast<SkybakeVdbReadFn*>(::dlsym(handle, "skybake_vdb_read"));
    if (abi && abi() == kVdbPluginAbi && plugin.write && plugin.read) return plugin;
    tried.push_back(fmt::format("{} (not a skybake {} VDB plugin of interface {})", path,
                                SKYBAKE_VERSION, kVdbPluginAbi));
    plugin.write = nullptr;
    plugin.read = nullptr;
    ::dlclose(handle);
  }
  std::string list;
  for (const std::string& t : tried) list += (list.empty() ? "" : "; ") + t;
  plugin.problem = fmt::format("the VDB plugin {} could not be loaded; tried {}", kVdbPluginName,
                               list.empty() ? std::string("no path") : list);
  return plugin;
}

const VdbPlugin& plugin_for(const std::string& path, const char* what) {
  static const VdbPlugin plugin = load();
  if (!plugin.problem.empty())
    throw IoError(fmt::format("{}: cannot {} VDB: {}", path, what, plugin.problem));
  return plugin;
}

void rethrow(int status, const std::string& message) {
  if (status == vdb_plugin_io_error) throw IoError(message);
  if (status != vdb_plugin_ok) throw Error(message);
}

}  // namespace

void write_vdb(const std::string& path, const Texture& tex, const VdbWriteOptions& options) {
  const VdbPlugin& plugin = plugin_for(path, "write");
  std::string message;
  rethrow(plugin.write(path.c_str(), &tex, &options, &message), message);
}

void write_vdb(const std::string& path, const Texture& tex, double voxel_size) {
  VdbWriteOptions options;
  options.voxel_size = voxel_size;
  write_vdb(path, tex, options);
}

Texture read_vdb(const std::string& path) {
  const VdbPlugin& plugin = plugin_for(path, "read");
  Texture tex;
  std::string message;
  rethrow(plugin.read(path.c_str(), &tex, &message), message);
  return tex;
}

}  // namespace skybake
