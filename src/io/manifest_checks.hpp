// The type rules of manifest.json (docs/formats.md, "manifest.json"): every
// field an entry holds, checked against what skybake writes before anything
// converts it. An entry that breaks a rule is a damaged record: set aside,
// and its output baked again.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace skybake {

// Why `entry` (at JSON pointer `at`, for the message) is not an entry
// skybake wrote, as "<pointer>: expected ..."; nullopt when it is one. Checks
// every field's type and the required fields.
std::optional<std::string> manifest_entry_problem(const nlohmann::json& entry,
                                                  const std::string& at);

}  // namespace skybake
