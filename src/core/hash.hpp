// Content hashing for the incremental cache: a 64-bit FNV-1a over bytes,
// printed as 16 hex digits, for parameters and names; a word-at-a-time hash
// for large contents (files). Not cryptographic; they only have to notice
// change.
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

// Word-at-a-time mixing (a multiply-rotate round per 8 bytes, the last
// partial word zero-padded), several times faster than byte-wise FNV on
// large contents. A content given in pieces hashes as one when every piece
// but the last is a multiple of 8 bytes; hash_words_finish folds in the total
// length.
uint64_t hash_words_mix(uint64_t h, const void* data, size_t size);
uint64_t hash_words_finish(uint64_t h, uint64_t length);
// hash_words_mix of the same content from two states at once, h[0] and h[1]
// updated in place: the same two results, one pass over the memory, and the
// two chains of rounds interleaved (each round waits on the one before).
void hash_words_mix2(uint64_t h[2], const void* data, size_t size);
// hash_words_finish(hash_words_mix(seed, data, size), size).
uint64_t hash_words(const void* data, size_t size, uint64_t seed);

}  // namespace skybake
