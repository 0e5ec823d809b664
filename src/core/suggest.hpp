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

// " (did you mean 'x'?)" for the closest candidate within a small distance, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace skybake
