// Test support: a KTX2 file's key/value data rewritten in place, the level
// index moved along with it, so that a forged value reaches the reader's
// key/value checks instead of its layout checks (KTX 2.0 specification,
// sections 3.5 and 3.6).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace skybake::test {

// `bytes` with the value of `key` replaced by `value` (the stored value's
// bytes: a text value ends in its NUL); the key is added, in sorted order,
// if absent. Spaces are appended before the NUL so that the key/value data
// grows by a multiple of 16 bytes and every level keeps its alignment.
std::vector<uint8_t> with_ktx2_key_value(const std::vector<uint8_t>& bytes,
                                         const std::string& key, std::string value);

}  // namespace skybake::test
