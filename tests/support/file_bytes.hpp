// Test support: a file's bytes, and little-endian fields inside them, for the
// tests that check a format's layout byte by byte (DDS, KTX2) or forge files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace skybake::test {

// The whole file; empty if it cannot be opened.
std::vector<uint8_t> read_bytes(const std::filesystem::path& path);

// Replaces the file with exactly these bytes.
void write_bytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes);

// Little-endian fields, as DDS and KTX2 store them; reads are bounds-checked,
// so a field past the end fails the test with std::out_of_range.
uint32_t u32_at(const std::vector<uint8_t>& bytes, size_t offset);
uint64_t u64_at(const std::vector<uint8_t>& bytes, size_t offset);
void put_u32_at(std::vector<uint8_t>& bytes, size_t offset, uint32_t value);

}  // namespace skybake::test
