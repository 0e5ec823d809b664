#include "io/manifest_checks.hpp"

#include <limits>

#include <fmt/format.h>

#include "core/hash.hpp"
#include "core/metadata_json.hpp"

namespace skybake {

namespace {

using nlohmann::json;
using Problem = std::optional<std::string>;

bool is_int(const json& v) {
  if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<int>::max());
  if (v.is_number_integer())
    return v.get<int64_t>() >= std::numeric_limits<int>::min() &&
           v.get<int64_t>() <= std::numeric_limits<int>::max();
  return false;
}

Problem expected(const std::string& at, const char* what) {
  return fmt::format("{}: expected {}", at, what);
}

// Keys that must be present and hold non-empty strings, then keys that may
// be present and hold strings.
Problem string_fields(const json& j, const std::string& at,
                      std::initializer_list<const char*> required,
                      std::initializer_list<const char*> optional) {
  for (const char* key : required) {
    if (!j.contains(key)) return fmt::format("{}: missing required key '{}'", at, key);
    if (!j[key].is_string() || j[key].get_ref<const std::string&>().empty())
      return expected(at + "/" + key, "a non-empty string");
  }
  for (const char* key : optional)
    if (j.contains(key) && !j[key].is_string()) return expected(at + "/" + key, "a string");
  return std::nullopt;
}

Problem files_problem(const json& files, const std::string& at) {
  if (!files.is_array()) return expected(at, "an array");
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string fat = fmt::format("{}/{}", at, i);
    if (!files[i].is_object()) return expected(fat, "an object");
    if (auto bad = string_fields(files[i], fat, {"path"}, {"format", "encoding", "hash"}))
      return bad;
    if (files[i].contains("size") && !files[i]["size"].is_number_unsigned())
      return expected(fat + "/size", "a non-negative integer");
  }
  return std::nullopt;
}

// [{code, message, ...numbers}] as pipeline/warnings.hpp writes them.
Problem warnings_problem(const json& warnings, const std::string& at) {
  if (!warnings.is_array()) return expected(at, "an array");
  for (size_t i = 0; i < warnings.size(); ++i) {
    const std::string wat = fmt::format("{}/{}", at, i);
    const json& w = warnings[i];
    if (!w.is_object()) return expected(wat, "an object");
    if (auto bad = string_fields(w, wat, {"code"}, {})) return bad;
    if (!w.contains("message") || !w["message"].is_string())
      return expected(wat + "/message", "a string");
    for (const auto& [key, value] : w.items())
      if (key != "code" && key != "message" && !value.is_number() && !value.is_null())
        return expected(wat + "/" + key, "a number");
  }
  return std::nullopt;
}

Problem list_problem(const json& j, const std::string& at, bool ints) {
  if (!j.is_array()) return expected(at, "an array");
  for (const json& v : j)
    if (ints ? !is_int(v) : !v.is_string()) return expected(at, ints ? "integers" : "strings");
  return std::nullopt;
}

Problem metadata_problem(const json& meta, const std::string& at) {
  if (!meta.is_object()) return expected(at, "an object");
  std::string why;
  for (const auto& [key, value] : meta.items())
    if (!meta_from_json(value, &why)) return fmt::format("{}/{}: {}", at, key, why);
  return std::nullopt;
}

// Every field but the hash.
Problem field_problem(const json& e, const std::string& at) {
  if (auto bad = string_fields(e, at, {"product", "name", "input_hash", "entry_hash"}, {}))
    return bad;
  if (!e.contains("files")) return fmt::format("{}: missing required key 'files'", at);
  if (auto bad = files_problem(e["files"], at + "/files")) return bad;
  if (e.contains("dimensions"))
    if (auto bad = list_problem(e["dimensions"], at + "/dimensions", true)) return bad;
  if (e.contains("channels"))
    if (auto bad = list_problem(e["channels"], at + "/channels", false)) return bad;
  if (e.contains("layers") && !is_int(e["layers"])) return expected(at + "/layers", "an integer");
  if (e.contains("metadata"))
    if (auto bad = metadata_problem(e["metadata"], at + "/metadata")) return bad;
  if (e.contains("warnings"))
    if (auto bad = warnings_problem(e["warnings"], at + "/warnings")) return bad;
  for (const char* key : {"error", "tiling"})
    if (e.contains(key) && !e[key].is_null() && !e[key].is_object())
      return expected(at + "/" + key, "an object or null");
  return std::nullopt;
}

}  // namespace

std::string manifest_entry_hash(const json& entry) {
  const auto text = [](const json& j) {
    return j.dump(-1, ' ', false, json::error_handler_t::replace);
  };
  if (!entry.is_object() || !entry.contains("entry_hash")) return hash_hex(text(entry));
  json without = entry;
  without.erase("entry_hash");
  return hash_hex(text(without));
}

std::optional<std::string> manifest_entry_problem(const json& entry, const std::string& at) {
  if (!entry.is_object()) return expected(at, "an object");
  if (auto bad = field_problem(entry, at)) return bad;
  if (entry["entry_hash"].get_ref<const std::string&>() != manifest_entry_hash(entry))
    return fmt::format("{}: the entry does not match its entry_hash (edited since it was written)",
                       at);
  return std::nullopt;
}

}  // namespace skybake
