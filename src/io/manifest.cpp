#include "io/manifest.hpp"

#include <fstream>

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
          {"estimated_error", e.estimated_error}};
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
  e.estimated_error = j.value("estimated_error", nlohmann::json());
  return e;
}

Manifest read_manifest(const std::filesystem::path& file) {
  Manifest m;
  std::ifstream in(file);
  if (!in) return m;
  nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return m;
  m.scene = j.value("scene", "");
  m.preset = j.value("preset", "");
  m.tool_version = j.value("tool_version", "");
  for (const auto& e : j.value("outputs", nlohmann::json::array())) {
    if (!e.is_object()) continue;
    ManifestEntry entry = manifest_entry_from_json(e);
    m.entries[entry.name] = entry;
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
