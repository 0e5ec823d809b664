#include "core/hash.hpp"

#include <cstring>

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

namespace {

constexpr uint64_t kMul1 = 0x9E3779B97F4A7C15ull;
constexpr uint64_t kMul2 = 0xC2B2AE3D27D4EB4Full;

uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

}  // namespace

uint64_t hash_words_mix(uint64_t h, const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = rotl(h ^ (w * kMul1), 29) * kMul2;
  }
  uint64_t tail = 0;
  std::memcpy(&tail, p + i, size - i);
  if (size > i) h = rotl(h ^ (tail * kMul1), 29) * kMul2;
  return h;
}

void hash_words_mix2(uint64_t h[2], const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t a = h[0], b = h[1];
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    const uint64_t m = w * kMul1;
    a = rotl(a ^ m, 29) * kMul2;
    b = rotl(b ^ m, 29) * kMul2;
  }
  h[0] = hash_words_mix(a, p + i, size - i);
  h[1] = hash_words_mix(b, p + i, size - i);
}

uint64_t hash_words_finish(uint64_t h, uint64_t length) {
  h ^= length * kMul2;
  h ^= h >> 33;
  h *= kMul1;
  h ^= h >> 29;
  return h;
}

uint64_t hash_words(const void* data, size_t size, uint64_t seed) {
  return hash_words_finish(hash_words_mix(seed, data, size), size);
}

}  // namespace skybake
