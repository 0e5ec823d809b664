// The KTX2 format table (ktx2_format.hpp).
#include "io/ktx2_format.hpp"

#include <numeric>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/suggest.hpp"

namespace skybake {

namespace {

const std::vector<Ktx2FormatInfo> kFormats = {
    {Ktx2Format::R8_UNORM, "R8_UNORM", 1, 1, 1, 1, 1, Ktx2Encoding::unorm8},
    {Ktx2Format::R8G8_UNORM, "R8G8_UNORM", 2, 2, 1, 1, 1, Ktx2Encoding::unorm8},
    {Ktx2Format::R8G8B8A8_UNORM, "R8G8B8A8_UNORM", 4, 4, 1, 1, 1, Ktx2Encoding::unorm8},
    {Ktx2Format::R16_SFLOAT, "R16_SFLOAT", 1, 2, 1, 1, 2, Ktx2Encoding::half},
    {Ktx2Format::R16G16B16A16_SFLOAT, "R16G16B16A16_SFLOAT", 4, 8, 1, 1, 2, Ktx2Encoding::half},
    {Ktx2Format::R32_SFLOAT, "R32_SFLOAT", 1, 4, 1, 1, 4, Ktx2Encoding::float32},
    {Ktx2Format::R32G32B32A32_SFLOAT, "R32G32B32A32_SFLOAT", 4, 16, 1, 1, 4, Ktx2Encoding::float32},
    // BC1 without alpha: our encoder stores RGB and its blocks decode alpha as 1.
    {Ktx2Format::BC1_RGB_UNORM_BLOCK, "BC1_RGB_UNORM_BLOCK", 3, 8, 4, 4, 1, Ktx2Encoding::bc,
     BcFormat::bc1},
    {Ktx2Format::BC3_UNORM_BLOCK, "BC3_UNORM_BLOCK", 4, 16, 4, 4, 1, Ktx2Encoding::bc,
     BcFormat::bc3},
    {Ktx2Format::BC4_UNORM_BLOCK, "BC4_UNORM_BLOCK", 1, 8, 4, 4, 1, Ktx2Encoding::bc,
     BcFormat::bc4},
    {Ktx2Format::BC5_UNORM_BLOCK, "BC5_UNORM_BLOCK", 2, 16, 4, 4, 1, Ktx2Encoding::bc,
     BcFormat::bc5},
};

}  // namespace

const std::vector<Ktx2FormatInfo>& ktx2_formats() {
  return kFormats;
}

const Ktx2FormatInfo* find_ktx2_format(uint32_t vk_format) {
  for (const Ktx2FormatInfo& f : kFormats)
    if (uint32_t(f.format) == vk_format) return &f;
  return nullptr;
}

const Ktx2FormatInfo& ktx2_format_info(Ktx2Format format) {
  const Ktx2FormatInfo* f = find_ktx2_format(uint32_t(format));
  if (!f) throw Error(fmt::format("unknown Ktx2Format value {}", uint32_t(format)));
  return *f;
}

const char* ktx2_format_name(Ktx2Format format) {
  return ktx2_format_info(format).name;
}

std::string ktx2_format_list(bool with_codes) {
  std::string s;
  for (const Ktx2FormatInfo& f : kFormats) {
    if (!s.empty()) s += ", ";
    s += with_codes ? fmt::format("{} ({})", f.name, uint32_t(f.format)) : f.name;
  }
  return s;
}

Ktx2Format ktx2_format_from_name(const std::string& name, const std::string& context) {
  const std::string prefix = "VK_FORMAT_";
  const std::string bare =
      name.compare(0, prefix.size(), prefix) == 0 ? name.substr(prefix.size()) : name;
  std::vector<std::string> names;
  for (const Ktx2FormatInfo& f : kFormats) {
    if (bare == f.name) return f.format;
    names.push_back(f.name);
  }
  const std::string* best = same_format_name(bare, names);
  if (!best) best = closest_name(bare, names, 2);
  throw IoError(fmt::format("{}: expected one of {}, got \"{}\"{}", context,
                            ktx2_format_list(false), name,
                            best ? fmt::format(" (did you mean \"{}\"?)", *best) : ""));
}

uint64_t ktx2_level_bytes(const Ktx2FormatInfo& f, uint64_t width, uint64_t height, uint64_t depth,
                          uint64_t layers) {
  const uint64_t bx = (width + uint64_t(f.block_width) - 1) / uint64_t(f.block_width);
  const uint64_t by = (height + uint64_t(f.block_height) - 1) / uint64_t(f.block_height);
  return bx * by * depth * layers * uint64_t(f.block_bytes);
}

uint32_t ktx2_level_alignment(const Ktx2FormatInfo& f) {
  return uint32_t(std::lcm(f.block_bytes, 4));
}

}  // namespace skybake
