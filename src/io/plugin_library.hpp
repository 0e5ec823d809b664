// Opening a plugin library of ours (the VDB and block-compression writers
// live in shared libraries opened with dlopen on first use, so a process
// that does not write those formats never loads OpenVDB or libsquish;
// docs/architecture.md "Build"). Where a plugin is looked for, in order:
// the path in an environment variable when it is set (and then only there),
// the executable's folder, and the build folder the tool was built in.
#pragma once

#include <functional>
#include <string>

namespace skybake {

struct PluginLibrary {
  void* handle = nullptr;  // from dlopen; never closed (the process keeps the plugin)
  std::string problem;     // why none could be opened, with every path tried; "" when opened
};

// Opens the first candidate for `file_name` whose `accept(handle)` holds
// (it checks the interface version and looks its functions up); a library
// that is not accepted is closed and named in `problem` with `rejected`,
// e.g. "not a skybake VDB plugin of interface 2".
PluginLibrary open_plugin_library(const char* env_var, const char* file_name,
                                  const std::function<bool(void* handle)>& accept,
                                  const std::string& rejected);

}  // namespace skybake
