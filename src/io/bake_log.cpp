#include "io/bake_log.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/json_input.hpp"
#include "core/safe_input.hpp"
#include "io/atomic_file.hpp"

namespace skybake {

namespace {

BakeLogEntry entry_from_json(const nlohmann::json& j) {
  BakeLogEntry e;
  if (j.contains("bake_seconds") && j["bake_seconds"].is_number())
    e.bake_seconds = j["bake_seconds"].get<double>();
  if (j.contains("error_seconds") && j["error_seconds"].is_number())
    e.error_seconds = j["error_seconds"].get<double>();
  if (j.contains("mtime_ns") && j["mtime_ns"].is_object())
    for (const auto& [path, t] : j["mtime_ns"].items())
      if (t.is_number_integer()) e.mtime_ns[path] = t.get<int64_t>();
  return e;
}

}  // namespace

BakeLog read_bake_log(const std::filesystem::path& file) {
  BakeLog log;
  // Anything but a regular, small, shallow JSON file reads as an empty log.
  const FileText read = read_regular_file(file, kMaxJsonFileBytes);
  if (read.status != ReadStatus::ok) return log;
  const ParsedJson parsed = parse_json_text(read.text);
  if (!parsed.value) return log;
  const nlohmann::json& j = *parsed.value;
  if (!j.is_object() || !j.contains("outputs") || !j["outputs"].is_object()) return log;
  for (const auto& [name, e] : j["outputs"].items())
    if (e.is_object()) log.entries[name] = entry_from_json(e);
  return log;
}

void write_bake_log(const std::filesystem::path& file, const BakeLog& log) {
  nlohmann::json outputs = nlohmann::json::object();
  for (const auto& [name, e] : log.entries)
    outputs[name] = {{"bake_seconds", e.bake_seconds},
                     {"error_seconds", e.error_seconds},
                     {"mtime_ns", e.mtime_ns}};
  write_text_atomic(file, nlohmann::json{{"outputs", outputs}}.dump(2) + "\n");
}

}  // namespace skybake
