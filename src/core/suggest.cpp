#include "core/suggest.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace skybake {

namespace {

bool same_letter(char a, char b) {
  return std::toupper((unsigned char)a) == std::toupper((unsigned char)b);
}

// A format name with what differs between DXGI and Vulkan spellings
// removed: upper case, no API prefix, no "_BLOCK" suffix, BC1's "_RGB" or
// "_RGBA" dropped, SFLOAT as FLOAT.
std::string format_key(const std::string& name) {
  std::string s;
  for (char c : name) s += char(std::toupper((unsigned char)c));
  for (const std::string prefix : {"DXGI_FORMAT_", "VK_FORMAT_"})
    if (s.rfind(prefix, 0) == 0) s = s.substr(prefix.size());
  const std::string block = "_BLOCK";
  if (s.size() > block.size() && s.compare(s.size() - block.size(), block.size(), block) == 0)
    s.resize(s.size() - block.size());
  for (const std::string rgb : {"BC1_RGBA_", "BC1_RGB_"})
    if (s.rfind(rgb, 0) == 0) s = "BC1_" + s.substr(rgb.size());
  const size_t sfloat = s.find("_SFLOAT");
  if (sfloat != std::string::npos) s.replace(sfloat, 7, "_FLOAT");
  return s;
}

}  // namespace

const std::string* same_format_name(const std::string& word,
                                    const std::vector<std::string>& candidates) {
  const std::string key = format_key(word);
  for (const std::string& c : candidates)
    if (format_key(c) == key) return &c;
  return nullptr;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + !same_letter(a[i - 1], b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

const std::string* closest_name(const std::string& word, const std::vector<std::string>& candidates,
                                size_t max_distance) {
  size_t best = max_distance + 1;
  const std::string* best_name = nullptr;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best) {
      best = d;
      best_name = &c;
    }
  }
  return best_name;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string* best = same_format_name(word, candidates);
  if (!best) best = closest_name(word, candidates, std::max<size_t>(2, word.size() / 3));
  return best ? " (did you mean '" + *best + "'?)" : "";
}

}  // namespace skybake
