// JSON that comes from outside the process (a manifest, a bake log, a farm
// catalog entry, a KTX2 key/value entry): parsed only after its nesting is
// bounded (core/safe_input.hpp), and quoted back in messages only as a short
// excerpt. nlohmann's parser keeps its own stack, but dump(), comparison and
// every recursive walk of a parsed tree recurse once per level: a value
// nested 100,000 deep overflows the stack in any of them (docs/formats.md,
// "Reading files skybake did not write").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/safe_input.hpp"

namespace skybake {

struct ParsedJson {
  std::optional<nlohmann::json> value;  // set when the text is JSON within the limit
  std::string why;  // else the rule: "invalid JSON" or the nesting rule of safe_input.hpp
};

// `text` parsed as JSON when it nests no deeper than `max_depth`; never throws.
ParsedJson parse_json_text(std::string_view text, int max_depth = kMaxJsonDepth);

// A one-line excerpt of `j` for a message: at most `max_chars` characters
// (then "..."), and arrays and objects past 8 levels shown as "[...]" and
// "{...}". Safe on any value, however deep or large.
std::string json_excerpt(const nlohmann::json& j, size_t max_chars = 80);

}  // namespace skybake
