// The EXR reader on arbitrary bytes: OpenImageIO/OpenEXR parse the file (they
// are not instrumented, but their allocations go through ASan), then our
// checks of header sizes and skybake:* attributes and the copy into a
// texture.
#include "fuzz_support.hpp"
#include "io/exr.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "input.exr");
  skybake::fuzz::expect_no_internal_error([&] { skybake::read_exr(path); });
  return 0;
}
