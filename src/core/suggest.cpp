#include "core/suggest.hpp"

#include <algorithm>
#include <cctype>

namespace skybake {

namespace {

bool same_letter(char a, char b) {
  return std::toupper((unsigned char)a) == std::toupper((unsigned char)b);
}

}  // namespace

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
  const std::string* best = closest_name(word, candidates, std::max<size_t>(2, word.size() / 3));
  return best ? " (did you mean '" + *best + "'?)" : "";
}

}  // namespace skybake
