#include "support/file_bytes.hpp"

#include <fstream>
#include <iterator>

namespace skybake::test {

std::vector<uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

uint32_t u32_at(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | bytes.at(offset + size_t(i));
  return v;
}

uint64_t u64_at(const std::vector<uint8_t>& bytes, size_t offset) {
  return uint64_t(u32_at(bytes, offset + 4)) << 32 | u32_at(bytes, offset);
}

void put_u32_at(std::vector<uint8_t>& bytes, size_t offset, uint32_t value) {
  for (size_t i = 0; i < 4; ++i) bytes.at(offset + i) = uint8_t(value >> (8 * i));
}

}  // namespace skybake::test
