// The type rules of manifest.json (docs/formats.md, "manifest.json"): every
// field an entry holds, checked against what skybake writes before anything
// converts it, and the entry hash that tells an entry skybake wrote from one
// edited, truncated or made up since. An entry that breaks a rule is a
// damaged record: set aside, and its output baked again.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace skybake {

// The hash recorded in an entry's "entry_hash": of the entry's compact JSON
// without that key. A parsed entry dumps to the bytes it was written from
// (object keys sorted, numbers in their shortest round-trip form), so the
// reader recomputes it from what it parsed.
std::string manifest_entry_hash(const nlohmann::json& entry);

// Why `entry` (at JSON pointer `at`, for the message) is not an entry
// skybake wrote, as "<pointer>: expected ..."; nullopt when it is one. Checks
// every field's type, the required fields, and the entry hash last.
std::optional<std::string> manifest_entry_problem(const nlohmann::json& entry,
                                                  const std::string& at);

}  // namespace skybake
