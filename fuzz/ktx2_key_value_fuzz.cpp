// The JSON of a KTX2's skybake.* key/value entries on arbitrary bytes: a
// small genuine file (made once with the project's writer) gets the input
// as the value of one key, chosen by the input's first byte among
// skybake.channels, a metadata key and a key the writer never writes; the
// rest, with a NUL appended, is the value. Exercises the nesting limit, the
// parser, the channel and metadata conversions and the messages' excerpts.
#include <vector>

#include "fuzz_support.hpp"
#include "io/ktx2.hpp"
#include "support/file_bytes.hpp"
#include "support/ktx2_edit.hpp"

namespace {

const std::vector<uint8_t>& genuine() {
  static const std::vector<uint8_t> bytes = [] {
    skybake::Texture tex(4, 4, 1, 1, {"R", "G"});
    tex.metadata["product"] = std::string("seed");
    const std::string path = (skybake::fuzz::work_dir() / "genuine.ktx2").string();
    skybake::write_ktx2(path, {tex}, skybake::Ktx2Format::R16G16B16A16_SFLOAT);
    return skybake::test::read_bytes(path);
  }();
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* keys[] = {"skybake.channels", "skybake.product", "skybake.zz"};
  const std::string value(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::vector<uint8_t> bytes =
      skybake::test::with_ktx2_key_value(genuine(), keys[data[0] % 3], value + '\0');
  const std::string path = skybake::fuzz::write_input(bytes.data(), bytes.size(), "kv.ktx2");
  skybake::fuzz::expect_no_internal_error([&] { skybake::read_ktx2(path); });
  return 0;
}
