#include "support/ktx2_edit.hpp"

#include <map>
#include <stdexcept>

#include "support/file_bytes.hpp"

namespace skybake::test {

namespace {

// KTX 2.0 section 3.1: the index after the 48-byte header.
constexpr size_t kKvdOffsetAt = 56, kKvdLengthAt = 60, kLevelIndexAt = 80, kLevelCountAt = 40;

void put_u64_at(std::vector<uint8_t>& bytes, size_t offset, uint64_t value) {
  put_u32_at(bytes, offset, uint32_t(value));
  put_u32_at(bytes, offset + 4, uint32_t(value >> 32));
}

std::map<std::string, std::string> key_values(const std::vector<uint8_t>& b, size_t at,
                                              size_t end) {
  std::map<std::string, std::string> kv;
  while (at < end) {
    const uint32_t n = u32_at(b, at);
    const std::string entry(b.begin() + long(at + 4), b.begin() + long(at + 4 + n));
    const size_t nul = entry.find('\0');
    if (nul == std::string::npos) throw std::runtime_error("key without NUL");
    kv[entry.substr(0, nul)] = entry.substr(nul + 1);
    at = (at + 4 + n + 3) / 4 * 4;
  }
  return kv;
}

std::vector<uint8_t> encode(const std::map<std::string, std::string>& kv) {
  std::vector<uint8_t> out;
  for (const auto& [key, value] : kv) {
    const std::string entry = key + '\0' + value;
    const size_t at = out.size();
    out.resize(at + 4);
    put_u32_at(out, at, uint32_t(entry.size()));
    out.insert(out.end(), entry.begin(), entry.end());
    out.resize((out.size() + 3) / 4 * 4, 0);
  }
  return out;
}

}  // namespace

std::vector<uint8_t> with_ktx2_key_value(const std::vector<uint8_t>& bytes,
                                         const std::string& key, std::string value) {
  const size_t kvd_at = u32_at(bytes, kKvdOffsetAt), kvd_length = u32_at(bytes, kKvdLengthAt);
  std::map<std::string, std::string> kv = key_values(bytes, kvd_at, kvd_at + kvd_length);
  std::vector<uint8_t> kvd;
  for (;;) {
    kv[key] = value;
    kvd = encode(kv);
    if ((kvd.size() - kvd_length) % 16 == 0) break;
    value.insert(value.empty() ? value.end() : value.end() - 1, ' ');
  }
  const uint64_t grown = kvd.size() - kvd_length;
  std::vector<uint8_t> out(bytes.begin(), bytes.begin() + long(kvd_at));
  out.insert(out.end(), kvd.begin(), kvd.end());
  out.insert(out.end(), bytes.begin() + long(kvd_at + kvd_length), bytes.end());
  put_u32_at(out, kKvdLengthAt, uint32_t(kvd.size()));
  const uint32_t levels = u32_at(bytes, kLevelCountAt) ? u32_at(bytes, kLevelCountAt) : 1;
  for (uint32_t i = 0; i < levels; ++i) {
    const size_t at = kLevelIndexAt + 24 * i;
    put_u64_at(out, at, u64_at(bytes, at) + grown);
  }
  return out;
}

}  // namespace skybake::test
