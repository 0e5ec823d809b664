#include "core/json_input.hpp"

namespace skybake {

namespace {

// How deep json_excerpt descends before writing "[...]" or "{...}".
constexpr int kExcerptDepth = 8;

std::string scalar_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A string as JSON, cut to `limit` bytes first (the excerpt is cut anyway).
std::string quoted(const std::string& s, size_t limit) {
  return scalar_text(nlohmann::json(s.size() > limit ? s.substr(0, limit) : s));
}

// Appends `j` to `out` until `out` holds `limit` characters.
void append_excerpt(const nlohmann::json& j, std::string& out, size_t limit, int depth) {
  if (out.size() >= limit) return;
  if (j.is_array() || j.is_object()) {
    const bool array = j.is_array();
    if (depth >= kExcerptDepth && !j.empty()) {
      out += array ? "[...]" : "{...}";
      return;
    }
    out += array ? '[' : '{';
    bool first = true;
    for (auto it = j.begin(); it != j.end() && out.size() < limit; ++it) {
      if (!first) out += ", ";
      first = false;
      if (!array) out += quoted(it.key(), limit) + ": ";
      append_excerpt(*it, out, limit, depth + 1);
    }
    out += array ? ']' : '}';
    return;
  }
  out += j.is_string() ? quoted(j.get_ref<const std::string&>(), limit) : scalar_text(j);
}

}  // namespace

ParsedJson parse_json_text(std::string_view text, int max_depth) {
  ParsedJson r;
  if (auto deep = json_nesting_problem(text, max_depth)) {
    r.why = *deep;
    return r;
  }
  nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr,
                                           /*allow_exceptions=*/false);
  if (j.is_discarded()) {
    r.why = "invalid JSON";
    return r;
  }
  r.value = std::move(j);
  return r;
}

std::string json_excerpt(const nlohmann::json& j, size_t max_chars) {
  std::string out;
  append_excerpt(j, out, max_chars + 1, 0);
  if (out.size() > max_chars) {
    out.resize(max_chars);
    out += "...";
  }
  return out;
}

}  // namespace skybake
