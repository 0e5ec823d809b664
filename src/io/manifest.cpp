#include "io/manifest.hpp"

#include <cstdio>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/json_input.hpp"
#include "core/safe_input.hpp"
#include "io/atomic_file.hpp"
#include "io/manifest_checks.hpp"

namespace skybake {

nlohmann::json to_json(const ManifestEntry& e) {
  nlohmann::json files = nlohmann::json::array();
  for (const ManifestFile& f : e.files)
    files.push_back({{"path", f.path},
                     {"format", f.format},
                     {"encoding", f.encoding},
                     {"size", f.size},
                     {"hash", f.hash}});
  nlohmann::json j = {{"product", e.product},   {"name", e.name},
                      {"files", files},         {"dimensions", e.dimensions},
                      {"layers", e.layers},     {"channels", e.channels},
                      {"metadata", e.metadata}, {"input_hash", e.input_hash},
                      {"error", e.error},       {"tiling", e.tiling},
                      {"warnings", e.warnings}};
  j["entry_hash"] = manifest_entry_hash(j);
  return j;
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

// Why `text` is not a manifest skybake can read at all, or nullopt with `m`
// filled: every entry that breaks a rule of io/manifest_checks.hpp goes to
// m.damaged instead of m.entries, and so does a second entry of one name.
std::optional<std::string> parse_manifest(const std::string& text, Manifest& m) {
  const ParsedJson parsed = parse_json_text(text);
  if (!parsed.value) return parsed.why;
  const json& j = *parsed.value;
  if (!j.is_object()) return std::string("expected an object");
  for (const char* key : {"scene", "preset", "tool_version"})
    if (j.contains(key) && !j[key].is_string()) return fmt::format("/{}: expected a string", key);
  if (j.contains("outputs") && !j["outputs"].is_array())
    return std::string("/outputs: expected an array");
  m.scene = j.value("scene", "");
  m.preset = j.value("preset", "");
  m.tool_version = j.value("tool_version", "");
  if (!j.contains("outputs")) return std::nullopt;
  const json& outputs = j["outputs"];
  for (size_t i = 0; i < outputs.size(); ++i) {
    const std::string at = fmt::format("/outputs/{}", i);
    if (auto bad = manifest_entry_problem(outputs[i], at)) {
      m.damaged.push_back(*bad);
      continue;
    }
    ManifestEntry entry = manifest_entry_from_json(outputs[i]);
    if (m.entries.count(entry.name)) {
      m.damaged.push_back(fmt::format("{}: a second entry named '{}'", at, entry.name));
      continue;
    }
    m.entries[entry.name] = std::move(entry);
  }
  return std::nullopt;
}

// Says once per process and file that a manifest, or records in it, were
// set aside.
void note_once(const std::filesystem::path& file, const std::string& note) {
  static std::mutex mutex;
  static std::set<std::string> noted;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!noted.insert(file.string()).second) return;
  std::fprintf(stderr, "skybake: note: %s: %s\n", file.c_str(), note.c_str());
}

std::string damaged_note(const std::vector<std::string>& damaged) {
  const size_t n = damaged.size();
  return fmt::format("{} damaged record{} set aside ({}{}); {} output{} count{} as not baked, "
                     "and the next bake rewrites the manifest",
                     n, n == 1 ? "" : "s", damaged.front(),
                     n > 1 ? fmt::format("; and {} more", n - 1) : "", n == 1 ? "its" : "their",
                     n == 1 ? "" : "s", n == 1 ? "s" : "");
}

}  // namespace

Manifest read_manifest(const std::filesystem::path& file) {
  const FileText read = read_regular_file(file, kMaxJsonFileBytes);
  if (read.status == ReadStatus::missing) return {};
  if (read.status == ReadStatus::refused)
    throw IoError(fmt::format("{}: cannot read manifest: {}; remove it and bake again (the "
                              "manifest is a cache the bake rebuilds; docs/farm.md, \"Repairing "
                              "an output folder\")",
                              file.string(), read.why));
  Manifest m;
  if (auto bad = parse_manifest(read.text, m)) {
    note_once(file, fmt::format("not a manifest skybake can read ({}); read as empty, so its "
                                "outputs count as not baked",
                                *bad));
    Manifest empty;
    empty.damaged.push_back(*bad);
    return empty;
  }
  if (!m.damaged.empty()) note_once(file, damaged_note(m.damaged));
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
