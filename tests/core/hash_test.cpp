// hash_words: a content given in pieces (all but the last a multiple of 8
// bytes) hashes as one; every byte, the length and the seed count.
#include <gtest/gtest.h>

#include <string>

#include "core/hash.hpp"

namespace skybake {
namespace {

std::string content(size_t n) {
  std::string s(n, '\0');
  for (size_t i = 0; i < n; ++i) s[i] = char((i * 131 + 7) % 251);
  return s;
}

TEST(HashWords, PiecesOfWholeWordsHashAsOneContent) {
  const std::string s = content(1000);
  for (size_t cut : {0u, 8u, 64u, 992u}) {
    uint64_t h = hash_words_mix(7, s.data(), cut);
    h = hash_words_mix(h, s.data() + cut, s.size() - cut);
    EXPECT_EQ(hash_words_finish(h, s.size()), hash_words(s.data(), s.size(), 7)) << cut;
  }
}

TEST(HashWords, TwoStatesAtOnceAreTwoSeparateMixes) {
  const std::string s = content(1003);
  for (size_t n : {0u, 5u, 8u, 13u, 1000u, 1003u}) {
    uint64_t h[2] = {7, 0xfedcba9876543210ull};
    hash_words_mix2(h, s.data(), n);
    EXPECT_EQ(h[0], hash_words_mix(7, s.data(), n)) << n;
    EXPECT_EQ(h[1], hash_words_mix(0xfedcba9876543210ull, s.data(), n)) << n;
  }
}

TEST(HashWords, EveryByteTheLengthAndTheSeedChangeTheHash) {
  const std::string s = content(37);  // 4 words and a 5-byte tail
  const uint64_t h = hash_words(s.data(), s.size(), 1);
  for (size_t i = 0; i < s.size(); ++i) {
    std::string t = s;
    t[i] = char(t[i] ^ 1);
    EXPECT_NE(hash_words(t.data(), t.size(), 1), h) << "byte " << i;
  }
  // A zero byte more: the padded tail word is the same, the length is not.
  const std::string longer = s + std::string(1, '\0');
  EXPECT_NE(hash_words(longer.data(), longer.size(), 1), h);
  EXPECT_NE(hash_words(s.data(), s.size(), 2), h);
}

}  // namespace
}  // namespace skybake
