#include "io/manifest.hpp"

#include <cstdio>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/metadata_json.hpp"
#include "core/safe_input.hpp"
#include "io/atomic_file.hpp"

namespace skybake {

nlohmann::json to_json(const ManifestEntry& e) {
  nlohmann::json files = nlohmann::json::array();
  for (const ManifestFile& f : e.files)
    files.push_back({{"path", f.path},
                     {"format", f.format},
                     {"encoding", f.encoding},
                     {"size", f.size},
                     {"hash", f.hash}});
  return {{"product", e.product},       {"name", e.name},
          {"files", files},             {"dimensions", e.dimensions},
          {"layers", e.layers},         {"channels", e.channels},
          {"metadata", e.metadata},     {"input_hash", e.input_hash},
          {"error", e.error},           {"tiling", e.tiling},
          {"warnings", e.warnings}};
}

ManifestEntry manifest_entry_from_json(const nlohmann::json& j) {
  ManifestEntry e;
  e.product = j.value("product", "");
  e.name = j.value("name", "");
  for (const auto& f : j.value("files", nlohmann::json::array()))
    e.files.push_back({f.value("path", ""), f.value("format", ""), f.value("encoding", ""),
                       f.value("size", uint64_t(0)), f.value("hash", "")});
  e.dimensions = j.value("dimensions", std::vector<int>{});
  e.layers = j.value("layers", 1);
  e.channels = j.value("channels", std::vector<std::string>{});
  e.metadata = j.value("metadata", nlohmann::json::object());
  e.input_hash = j.value("input_hash", "");
  e.error = j.value("error", nlohmann::json());
  e.tiling = j.value("tiling", nlohmann::json());
  e.warnings = j.value("warnings", nlohmann::json::array());
  return e;
}

namespace {

using nlohmann::json;

// The first key of `j` (an object) whose value has a type the reader cannot
// take, as "/key: expected ..."; absent keys are fine (defaults apply).
std::optional<std::string> field_type_problem(const json& j, const std::string& at,
                                              const std::set<std::string>& strings) {
  for (const std::string& key : strings)
    if (j.contains(key) && !j[key].is_string())
      return fmt::format("{}/{}: expected a string", at, key);
  return std::nullopt;
}

bool is_int(const json& v) {
  if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<int>::max());
  if (v.is_number_integer())
    return v.get<int64_t>() >= std::numeric_limits<int>::min() &&
           v.get<int64_t>() <= std::numeric_limits<int>::max();
  return false;
}

// Checks every field manifest_entry_from_json reads against the type it
// converts to, so that the conversion cannot throw or overflow.
std::optional<std::string> entry_problem(const json& e, const std::string& at) {
  if (!e.is_object()) return fmt::format("{}: expected an object", at);
  if (auto bad = field_type_problem(e, at, {"product", "name", "input_hash"})) return bad;
  if (e.contains("files")) {
    const json& files = e["files"];
    if (!files.is_array()) return fmt::format("{}/files: expected an array", at);
    for (size_t i = 0; i < files.size(); ++i) {
      const std::string fat = fmt::format("{}/files/{}", at, i);
      if (!files[i].is_object()) return fmt::format("{}: expected an object", fat);
      if (auto bad = field_type_problem(files[i], fat, {"path", "format", "encoding", "hash"}))
        return bad;
      if (files[i].contains("size") && !files[i]["size"].is_number_unsigned())
        return fmt::format("{}/size: expected a non-negative integer", fat);
    }
  }
  if (e.contains("dimensions")) {
    const json& d = e["dimensions"];
    if (!d.is_array()) return fmt::format("{}/dimensions: expected an array", at);
    for (const json& v : d)
      if (!is_int(v)) return fmt::format("{}/dimensions: expected integers", at);
  }
  if (e.contains("layers") && !is_int(e["layers"]))
    return fmt::format("{}/layers: expected an integer", at);
  if (e.contains("channels")) {
    const json& c = e["channels"];
    if (!c.is_array()) return fmt::format("{}/channels: expected an array", at);
    for (const json& v : c)
      if (!v.is_string()) return fmt::format("{}/channels: expected strings", at);
  }
  if (e.contains("metadata")) {
    if (!e["metadata"].is_object()) return fmt::format("{}/metadata: expected an object", at);
    std::string why;
    for (const auto& [key, value] : e["metadata"].items())
      if (!meta_from_json(value, &why)) return fmt::format("{}/metadata/{}: {}", at, key, why);
  }
  if (e.contains("warnings") && !e["warnings"].is_array())
    return fmt::format("{}/warnings: expected an array", at);
  if (e.contains("bake_seconds") && !e["bake_seconds"].is_number())
    return fmt::format("{}/bake_seconds: expected a number", at);
  return std::nullopt;
}

// Why `text` is not a manifest skybake can read, or nullopt (with `m` filled).
std::optional<std::string> parse_manifest(const std::string& text, Manifest& m) {
  if (auto deep = json_nesting_problem(text)) return *deep;
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::string("invalid JSON");
  if (!j.is_object()) return std::string("expected an object");
  if (auto bad = field_type_problem(j, "", {"scene", "preset", "tool_version"})) return bad;
  if (j.contains("outputs") && !j["outputs"].is_array())
    return std::string("/outputs: expected an array");
  m.scene = j.value("scene", "");
  m.preset = j.value("preset", "");
  m.tool_version = j.value("tool_version", "");
  if (!j.contains("outputs")) return std::nullopt;
  const json& outputs = j["outputs"];
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (auto bad = entry_problem(outputs[i], fmt::format("/outputs/{}", i))) return bad;
    ManifestEntry entry = manifest_entry_from_json(outputs[i]);
    m.entries[entry.name] = entry;
  }
  return std::nullopt;
}

// Says once per process and file that a manifest was set aside.
void note_ignored(const std::filesystem::path& file, const std::string& why) {
  static std::mutex mutex;
  static std::set<std::string> noted;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!noted.insert(file.string()).second) return;
  std::fprintf(stderr,
               "skybake: note: %s: not a manifest skybake can read (%s); read as empty, so "
               "its outputs count as not baked\n",
               file.c_str(), why.c_str());
}

}  // namespace

Manifest read_manifest(const std::filesystem::path& file) {
  const FileText read = read_regular_file(file, kMaxJsonFileBytes);
  if (read.status == ReadStatus::missing) return {};
  if (read.status == ReadStatus::refused)
    throw IoError(fmt::format("{}: cannot read manifest: {}", file.string(), read.why));
  Manifest m;
  if (auto bad = parse_manifest(read.text, m)) {
    note_ignored(file, *bad);
    return {};
  }
  return m;
}

void write_manifest(const std::filesystem::path& file, const Manifest& m) {
  nlohmann::json outputs = nlohmann::json::array();
  for (const auto& [name, e] : m.entries) outputs.push_back(to_json(e));
  const nlohmann::json j = {{"scene", m.scene},
                            {"preset", m.preset},
                            {"tool", "skybake"},
                            {"tool_version", m.tool_version},
                            {"outputs", outputs}};
  write_text_atomic(file, j.dump(2) + "\n");
}

}  // namespace skybake
