#include "core/hash.hpp"

#include <fmt/format.h>

namespace skybake {

Hasher& Hasher::add(const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h_ ^= p[i];
    h_ *= 1099511628211ull;
  }
  return *this;
}

Hasher& Hasher::add(std::string_view bytes) {
  add(bytes.data(), bytes.size());
  // A separator so ("ab","c") and ("a","bc") differ.
  const unsigned char sep = 0xff;
  return add(&sep, 1);
}

std::string Hasher::hex() const { return fmt::format("{:016x}", h_); }

std::string hash_hex(std::string_view bytes) { return Hasher().add(bytes).hex(); }

}  // namespace skybake
