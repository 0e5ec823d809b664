// Writes small genuine files for the fuzzers' seed corpora, through the
// project's own writers: `fuzz_seeds DIR` fills DIR/dds, DIR/exr, DIR/vdb,
// DIR/ktx2 and DIR/manifest (each file a few hundred bytes to a few KiB). The preset
// seeds are the shipped presets, copied by scripts/fuzz.sh.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/dds.hpp"
#include "io/exr.hpp"
#include "io/ktx2.hpp"
#include "io/manifest.hpp"
#include "io/vdb.hpp"

namespace fs = std::filesystem;
using namespace skybake;

namespace {

Texture filled(int w, int h, int d, int layers, int channels) {
  static const std::vector<std::string> rgba = {"R", "G", "B", "A"};
  Texture t(w, h, d, layers, {rgba.begin(), rgba.begin() + channels});
  for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i % 17) / 16.0f;
  set_meta(t.metadata, "product", "seed");
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIR\n");
    return 2;
  }
  const fs::path dir = argv[1];
  for (const char* sub : {"dds", "exr", "vdb", "ktx2", "manifest", "ktx2_key_value", "manifest_entry"})
    fs::create_directories(dir / sub);

  const std::vector<Texture> shapes = {filled(4, 2, 1, 1, 4), filled(3, 3, 1, 2, 1),
                                       filled(2, 2, 4, 1, 3)};
  int n = 0;
  for (const Texture& t : shapes) {
    for (ExrPrecision p : {ExrPrecision::half, ExrPrecision::float32})
      for (ExrVolumeLayout l : {ExrVolumeLayout::atlas, ExrVolumeLayout::multipart})
        write_exr((dir / "exr" / ("seed" + std::to_string(n++) + ".exr")).string(), t, p, l);
    for (DdsFormat f : dds_formats()) {
      if (t.channel_count() > dds_component_count(f)) continue;
      write_dds((dir / "dds" / ("seed" + std::to_string(n++) + ".dds")).string(), {t}, f);
    }
    for (const Ktx2FormatInfo& f : ktx2_formats()) {
      if (t.channel_count() > f.components) continue;
      write_ktx2((dir / "ktx2" / ("seed" + std::to_string(n++) + ".ktx2")).string(), {t},
                 f.format);
    }
    if (!t.is_array())
      write_vdb((dir / "vdb" / ("seed" + std::to_string(n++) + ".vdb")).string(), t, 0.5);
  }
  // A chain of mips in DDS.
  const Texture top = filled(4, 4, 1, 1, 4);
  write_dds((dir / "dds" / "mips.dds").string(), {top, filled(2, 2, 1, 1, 4), filled(1, 1, 1, 1, 4)},
            DdsFormat::R16G16B16A16_FLOAT);

  write_ktx2((dir / "ktx2" / "mips.ktx2").string(),
             {top, filled(2, 2, 1, 1, 4), filled(1, 1, 1, 1, 4)}, Ktx2Format::R16G16B16A16_SFLOAT);

  Manifest m;
  m.scene = "seed";
  m.preset = "presets/seed.json";
  m.tool_version = "0";
  ManifestEntry e;
  e.product = "transmittance";
  e.name = "transmittance";
  e.files = {{"transmittance.exr", "exr", "float", 1234, "0123456789abcdef"},
             {"transmittance.dds", "dds", "R32G32B32A32_FLOAT", 148, "fedcba9876543210"}};
  e.dimensions = {256, 64};
  e.channels = {"R", "G", "B"};
  e.metadata = {{"parameterization", "bruneton"}, {"mu_min", -0.2}};
  e.input_hash = "d5358e9113d6403a";
  e.error = {{"rms_rel", 0.0004}, {"max_rel", 0.001}, {"queries", 512}, {"reference", "quadrature"}};
  m.entries[e.name] = e;
  write_manifest(dir / "manifest" / "manifest.json", m);

  // One entry as JSON (manifest_entry_fuzz stamps its hash), with a warning.
  e.warnings = nlohmann::json::array({{{"code", "error_above_limit"}, {"message", "seed"},
                                       {"max_rel", 0.5}}});
  nlohmann::json entry = to_json(e);
  entry.erase("entry_hash");
  std::ofstream(dir / "manifest_entry" / "entry.json") << entry.dump(1);
  // A key/value value: the first byte picks skybake.channels, a metadata key
  // or an unknown key (ktx2_key_value_fuzz).
  const std::vector<std::string> values = {std::string("\0[\"R\", \"G\"]", 11), "\1\"seed\"",
                                           "\1[1.0, 2.5, 3.0]", "\2[[[[1]]]]", "\2{\"a\": 1}"};
  for (size_t i = 0; i < values.size(); ++i)
    std::ofstream(dir / "ktx2_key_value" / ("value" + std::to_string(i)), std::ios::binary)
        << values[i];
  return 0;
}
