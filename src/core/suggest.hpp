// "did you mean" for misspelled names (after ninja's SpellcheckString).
#pragma once

#include <string>
#include <vector>

namespace skybake {

// Levenshtein distance, ignoring letter case.
size_t edit_distance(const std::string& a, const std::string& b);

// The candidate nearest to `word` within `max_distance` edits, or nullptr.
const std::string* closest_name(const std::string& word, const std::vector<std::string>& candidates,
                                size_t max_distance);

// The candidate that names the same texture format as `word` in the other
// API's spelling, nullptr when none does: DXGI names ("BC4_UNORM",
// "R16_FLOAT", prefix "DXGI_FORMAT_") against Vulkan names
// ("BC4_UNORM_BLOCK", "BC1_RGB_UNORM_BLOCK", "R16_SFLOAT", prefix
// "VK_FORMAT_"), both ways (Microsoft Learn "DXGI_FORMAT", Vulkan
// specification "Formats"). Spelling near misses are closest_name's.
const std::string* same_format_name(const std::string& word,
                                    const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" for the candidate naming the same texture format
// (same_format_name), else the closest within a small distance, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace skybake
