// The DDS reader on arbitrary bytes: header parsing and validation, then
// decoding whatever the validated header announces.
#include "fuzz_support.hpp"
#include "io/dds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "input.dds");
  skybake::fuzz::expect_no_internal_error([&] { skybake::read_dds(path); });
  return 0;
}
