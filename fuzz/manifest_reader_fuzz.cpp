// The manifest reader on arbitrary bytes: the nesting limit, nlohmann's
// parser, the type checks and the conversion to entries; then the entries
// are written back and read again (what a bake does under its lock).
#include "fuzz_support.hpp"
#include "io/manifest.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "manifest.json");
  skybake::fuzz::expect_no_internal_error([&] {
    const skybake::Manifest m = skybake::read_manifest(path);
    skybake::write_manifest(path, m);
    const skybake::Manifest again = skybake::read_manifest(path);
    if (again.entries.size() != m.entries.size()) std::abort();
  });
  return 0;
}
