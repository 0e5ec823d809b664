// The entry points of libskybake_vdb.so (vdb_plugin.hpp): exceptions become a
// status and a message here, so none crosses the library boundary.
#include "io/vdb_plugin.hpp"

#include <exception>
#include <utility>

#include "core/error.hpp"

namespace {

template <class F>
int guarded(std::string* message, F&& body) {
  try {
    body();
    return skybake::vdb_plugin_ok;
  } catch (const skybake::IoError& e) {
    *message = e.what();
    return skybake::vdb_plugin_io_error;
  } catch (const std::exception& e) {
    *message = e.what();
    return skybake::vdb_plugin_error;
  } catch (...) {
    *message = "unknown exception in the VDB plugin";
    return skybake::vdb_plugin_error;
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int skybake_vdb_abi() {
  return skybake::kVdbPluginAbi;
}

extern "C" __attribute__((visibility("default"))) int skybake_vdb_write(
    const char* path, const skybake::Texture* tex, const skybake::VdbWriteOptions* options,
    std::string* message) {
  return guarded(message, [&] { skybake::write_vdb_file(path, *tex, *options); });
}

extern "C" __attribute__((visibility("default"))) int skybake_vdb_read(const char* path,
                                                                       uint64_t budget,
                                                                       skybake::Texture* out,
                                                                       std::string* message) {
  return guarded(message, [&] { *out = skybake::read_vdb_file(path, budget); });
}
