// One manifest entry on arbitrary bytes, its entry_hash made to match: the
// entry hash no longer stops the input at the door, so the typed reader
// (io/manifest_checks.hpp) and everything that reads an entry it accepts
// (the warnings' summary lines, the metadata conversion, the writer) see
// every shape of JSON. A manifest written back from what was read must read
// back the same.
#include <string>

#include "core/json_input.hpp"
#include "core/metadata_json.hpp"
#include "fuzz_support.hpp"
#include "io/atomic_file.hpp"
#include "io/manifest.hpp"
#include "io/manifest_checks.hpp"
#include "pipeline/warnings.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const skybake::ParsedJson parsed =
      skybake::parse_json_text(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!parsed.value || !parsed.value->is_object()) return 0;
  nlohmann::json entry = *parsed.value;
  entry["entry_hash"] = skybake::manifest_entry_hash(entry);
  const nlohmann::json manifest = {{"scene", "fuzz"}, {"outputs", {entry}}};
  const std::string path = (skybake::fuzz::work_dir() / "manifest.json").string();
  skybake::fuzz::expect_no_internal_error([&] {
    skybake::write_text_atomic(path, manifest.dump(-1, ' ', false,
                                                   nlohmann::json::error_handler_t::replace));
    const skybake::Manifest m = skybake::read_manifest(path);
    for (const auto& [name, e] : m.entries) {
      for (const nlohmann::json& w : e.warnings) (void)skybake::warning_line(w);
      (void)skybake::metadata_from_json(e.metadata);
    }
    skybake::write_manifest(path, m);
    const skybake::Manifest again = skybake::read_manifest(path);
    if (again.entries.size() != m.entries.size() || !again.damaged.empty()) std::abort();
  });
  return 0;
}
