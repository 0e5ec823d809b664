// write_vdb and read_vdb (vdb.hpp): forwarded to the VDB plugin, opened with
// dlopen on first use (vdb_plugin.hpp says why and where it is looked for).
#include <dlfcn.h>

#include <string>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/vdb.hpp"
#include "io/plugin_library.hpp"
#include "io/vdb_plugin.hpp"

namespace skybake {

namespace {

struct VdbPlugin {
  SkybakeVdbWriteFn* write = nullptr;
  SkybakeVdbReadFn* read = nullptr;
  std::string problem;  // why it could not be loaded, with every path tried
};

VdbPlugin load() {
  VdbPlugin plugin;
  const PluginLibrary lib = open_plugin_library(
      "SKYBAKE_VDB_PLUGIN", kVdbPluginName,
      [&](void* handle) {
        auto* abi = reinterpret_cast<SkybakeVdbAbiFn*>(::dlsym(handle, "skybake_vdb_abi"));
        plugin.write = reinterpret_cast<SkybakeVdbWriteFn*>(::dlsym(handle, "skybake_vdb_write"));
        plugin.read = reinterpret_cast<SkybakeVdbReadFn*>(::dlsym(handle, "skybake_vdb_read"));
        return abi && abi() == kVdbPluginAbi && plugin.write && plugin.read;
      },
      fmt::format("not a skybake {} VDB plugin of interface {}", SKYBAKE_VERSION, kVdbPluginAbi));
  if (!lib.handle)
    plugin.problem =
        fmt::format("the VDB plugin {} could not be loaded; {}", kVdbPluginName, lib.problem);
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

VdbCompression vdb_compression_from_name(const std::string& name) {
  if (name == "blosc") return VdbCompression::blosc;
  if (name == "zip") return VdbCompression::zip;
  if (name == "none") return VdbCompression::none;
  throw Error(fmt::format("expected a VDB compression of blosc, zip or none, got '{}'", name));
}

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

Texture read_vdb(const std::string& path, uint64_t budget) {
  const VdbPlugin& plugin = plugin_for(path, "read");
  Texture tex;
  std::string message;
  rethrow(plugin.read(path.c_str(), budget, &tex, &message), message);
  return tex;
}

}  // namespace skybake
