// Content hashing for the incremental cache: a 64-bit FNV-1a over bytes,
// printed as 16 hex digits. Not cryptographic; it only has to notice change.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace skybake {

class Hasher {
 public:
  Hasher& add(std::string_view bytes);
  Hasher& add(const void* data, size_t size);
  uint64_t value() const { return h_; }
  std::string hex() const;

 private:
  uint64_t h_ = 1469598103934665603ull;
};

std::string hash_hex(std::string_view bytes);

}  // namespace skybake
