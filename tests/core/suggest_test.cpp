// "Did you mean" (core/suggest.hpp): a texture format named in the other
// API's spelling finds its counterpart, DXGI to Vulkan and back, before any
// nearer spelling; other words keep the edit-distance suggestion.
#include "core/suggest.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace skybake {
namespace {

// The names skybake accepts for dds_format and ktx2_format (schemas/scene.schema.json).
const std::vector<std::string> kDxgi = {
    "R32G32B32A32_FLOAT", "R16G16B16A16_FLOAT", "R11G11B10_FLOAT", "R8G8B8A8_UNORM",
    "R8G8_UNORM",         "R8_UNORM",           "R16_FLOAT",       "BC1_UNORM",
    "BC3_UNORM",          "BC4_UNORM",          "BC5_UNORM"};
const std::vector<std::string> kVulkan = {
    "R32G32B32A32_SFLOAT", "R32_SFLOAT",          "R16G16B16A16_SFLOAT", "R16_SFLOAT",
    "R8G8B8A8_UNORM",      "R8G8_UNORM",          "R8_UNORM",            "BC1_RGB_UNORM_BLOCK",
    "BC3_UNORM_BLOCK",     "BC4_UNORM_BLOCK",     "BC5_UNORM_BLOCK"};

TEST(Suggest, DxgiNamesFindTheirVulkanCounterparts) {
  // Microsoft Learn "DXGI_FORMAT" against the Vulkan specification "Formats".
  const std::pair<const char*, const char*> pairs[] = {
      {"BC4_UNORM", "BC4_UNORM_BLOCK"},
      {"BC1_UNORM", "BC1_RGB_UNORM_BLOCK"},
      {"BC3_UNORM", "BC3_UNORM_BLOCK"},
      {"BC5_UNORM", "BC5_UNORM_BLOCK"},
      {"R32G32B32A32_FLOAT", "R32G32B32A32_SFLOAT"},
      {"R16_FLOAT", "R16_SFLOAT"},
      {"DXGI_FORMAT_R16G16B16A16_FLOAT", "R16G16B16A16_SFLOAT"},
      {"bc4_unorm", "BC4_UNORM_BLOCK"}};
  for (const auto& [dxgi, vulkan] : pairs) {
    const std::string* got = same_format_name(dxgi, kVulkan);
    ASSERT_NE(got, nullptr) << dxgi;
    EXPECT_EQ(*got, vulkan) << dxgi;
    EXPECT_EQ(did_you_mean(dxgi, kVulkan), std::string(" (did you mean '") + vulkan + "'?)");
  }
}

TEST(Suggest, VulkanNamesFindTheirDxgiCounterparts) {
  const std::pair<const char*, const char*> pairs[] = {
      {"BC4_UNORM_BLOCK", "BC4_UNORM"},
      {"BC1_RGB_UNORM_BLOCK", "BC1_UNORM"},
      {"BC1_RGBA_UNORM_BLOCK", "BC1_UNORM"},
      {"VK_FORMAT_BC5_UNORM_BLOCK", "BC5_UNORM"},
      {"R16G16B16A16_SFLOAT", "R16G16B16A16_FLOAT"},
      {"R16_SFLOAT", "R16_FLOAT"}};
  for (const auto& [vulkan, dxgi] : pairs) {
    const std::string* got = same_format_name(vulkan, kDxgi);
    ASSERT_NE(got, nullptr) << vulkan;
    EXPECT_EQ(*got, dxgi) << vulkan;
  }
}

TEST(Suggest, FormatsWithoutACounterpartFallBackToSpelling) {
  // R32_SFLOAT has no DXGI format among skybake's; R11G11B10 no Vulkan one.
  EXPECT_EQ(same_format_name("R32_SFLOAT", kDxgi), nullptr);
  EXPECT_EQ(same_format_name("R11G11B10_FLOAT", kVulkan), nullptr);
  EXPECT_EQ(did_you_mean("R8G8B8A8_UNROM", kDxgi), " (did you mean 'R8G8B8A8_UNORM'?)");
  EXPECT_EQ(did_you_mean("transmitance", {"transmittance", "skyview"}),
            " (did you mean 'transmittance'?)");
  EXPECT_EQ(did_you_mean("zzz", {"transmittance", "skyview"}), "");
}

}  // namespace
}  // namespace skybake
