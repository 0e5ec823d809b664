// The VDB reader on arbitrary bytes: the layout walk, then OpenVDB on what
// the walk accepted (OpenVDB is not instrumented, but its allocations go
// through ASan's limits), then the dense copy.
#include "fuzz_support.hpp"
#include "io/vdb.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = skybake::fuzz::write_input(data, size, "input.vdb");
  skybake::fuzz::expect_no_internal_error([&] { skybake::read_vdb(path); });
  return 0;
}
