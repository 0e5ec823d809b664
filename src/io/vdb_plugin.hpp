// The VDB plugin: OpenVDB costs tens of milliseconds of dynamic loading and
// static initialisation, so the VDB writer and reader (vdb.cpp, vdb_leaves.cpp,
// vdb_layout.cpp)
// live in a shared library of their own, libskybake_vdb.so, that write_vdb and
// read_vdb (vdb_loader.cpp, in skybake_io) open with dlopen the first time a
// VDB is written or read. Nothing else links OpenVDB, so no other command
// pays for it.
//
// Where the plugin is looked for, in order: $SKYBAKE_VDB_PLUGIN when set (and
// then only there); beside the running executable (the installed layout and
// build/skybake); the build folder the library was compiled for (tests and
// fuzzers live in its subfolders).
//
// The entry points are extern "C" (found by name with dlsym) and never let an
// exception cross the library boundary: they return a status and a message,
// and the loader throws the matching IoError or Error. Textures cross it by
// reference: the plugin is built from the same sources and compiler.
#pragma once

#include <string>

#include "core/texture.hpp"
#include "io/vdb.hpp"

namespace skybake {

// The implementations inside the plugin (vdb.cpp); contracts as write_vdb and
// read_vdb in vdb.hpp.
void write_vdb_file(const std::string& path, const Texture& tex, const VdbWriteOptions& options);
Texture read_vdb_file(const std::string& path, uint64_t budget);

enum VdbPluginStatus : int { vdb_plugin_ok = 0, vdb_plugin_io_error = 1, vdb_plugin_error = 2 };

// Bumped whenever an entry point's signature or Texture's layout changes.
constexpr int kVdbPluginAbi = 7;
constexpr const char* kVdbPluginName = "libskybake_vdb.so";

}  // namespace skybake

extern "C" {
using SkybakeVdbAbiFn = int();
using SkybakeVdbWriteFn = int(const char* path, const skybake::Texture* tex,
                              const skybake::VdbWriteOptions* options, std::string* message);
using SkybakeVdbReadFn = int(const char* path, uint64_t budget, skybake::Texture* out,
                             std::string* message);
}
