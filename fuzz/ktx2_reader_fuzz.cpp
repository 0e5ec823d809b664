// The KTX2 reader on arbitrary bytes: header, index and level index
// validation, the descriptor, the key/value data, then decoding whatever the
// validated header announces.
#include "fuzz_support.hpp"
#include "io/ktx2.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "input.ktx2");
  skybake::fuzz::expect_no_internal_error([&] { skybake::read_ktx2(path); });
  return 0;
}
