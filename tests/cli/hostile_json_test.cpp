// Hostile JSON and hostile files where JSON is expected, through the real
// executable: presets, referenced presets and manifest.json nested far too
// deep, of the wrong types, or not regular files at all. Each must end in a
// clear one-line error or in the manifest being treated as a missing cache,
// never in a crash (exit code -1 here), a hang or an internal error (exit 5).
#include <sys/stat.h>

#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using skybake::test::fresh_dir;
using skybake::test::read_file;
using skybake::test::run_skybake;
using skybake::test::source_path;

namespace {

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

std::string nested_arrays(size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

// A scene with one small transmittance table, the atmosphere referenced by
// `atmosphere` (a path relative to the scene, or absolute).
std::string small_scene(const std::string& atmosphere) {
  return nlohmann::json{
      {"name", "hostile"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", atmosphere},
      {"outputs",
       {{{"product", "transmittance"}, {"size", {32, 16}}, {"formats", {"exr", "dds"}}}}}}
      .dump(2);
}

fs::path earth_atmosphere() {
  return source_path("presets/atmospheres/earth.json");
}

TEST(HostileJson, PresetNested20000DeepIsRefusedWithTheLimit) {
  const fs::path dir = fresh_dir("hostile_deep_preset");
  const fs::path preset = dir / "deep.json";
  write(preset, nested_arrays(20000));
  const auto v = run_skybake({"validate", preset.string()});
  EXPECT_EQ(v.exit_code, 1) << v.err;
  EXPECT_NE(v.err.find(preset.string()), std::string::npos) << v.err;
  EXPECT_NE(v.err.find("deeper than the limit of 128 levels"), std::string::npos) << v.err;
  const auto b = run_skybake({"bake", preset.string(), "-o", (dir / "out").string()});
  EXPECT_EQ(b.exit_code, 3) << b.err;
  EXPECT_NE(b.err.find("deeper than the limit of 128 levels"), std::string::npos) << b.err;
}

TEST(HostileJson, DeepObjectsInsideAValidPrefixAreRefusedToo) {
  const fs::path dir = fresh_dir("hostile_deep_objects");
  const fs::path preset = dir / "deep.json";
  std::string text = "{\"name\": \"x\", \"description\": \"[[[[ in a string is fine\", \"a\": ";
  for (int i = 0; i < 5000; ++i) text += "{\"k\": ";
  text += "1" + std::string(5000, '}') + "}";
  write(preset, text);
  const auto v = run_skybake({"validate", preset.string()});
  EXPECT_EQ(v.exit_code, 1) << v.err;
  EXPECT_NE(v.err.find("deeper than the limit of 128 levels (line 1, column"), std::string::npos)
      << v.err;
}

TEST(HostileJson, DeepReferencedPresetIsNamedAsTheFileAtFault) {
  const fs::path dir = fresh_dir("hostile_deep_reference");
  write(dir / "atmosphere.json", nested_arrays(100000));
  write(dir / "scene.json", small_scene("atmosphere.json"));
  const auto r = run_skybake({"validate", (dir / "scene.json").string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("atmosphere.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("deeper than the limit"), std::string::npos) << r.err;
}

TEST(HostileJson, ReferencedPresetThatIsADeviceOrAFifoIsRefused) {
  const fs::path dir = fresh_dir("hostile_special_reference");
  write(dir / "zero.json", small_scene("/dev/zero"));
  auto r = run_skybake({"bake", (dir / "zero.json").string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("is a character device, expected a regular file"), std::string::npos)
      << r.err;

  ASSERT_EQ(::mkfifo((dir / "fifo.json").c_str(), 0644), 0);
  write(dir / "fifo_scene.json", small_scene("fifo.json"));
  r = run_skybake({"validate", (dir / "fifo_scene.json").string()});  // must not block
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("is a FIFO, expected a regular file"), std::string::npos) << r.err;
  r = run_skybake({"bake", (dir / "fifo.json").string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("fifo.json: cannot read preset: is a FIFO"), std::string::npos) << r.err;
}

TEST(HostileJson, PresetLargerThanTheLimitIsRefusedUnread) {
  const fs::path dir = fresh_dir("hostile_large_preset");
  const fs::path preset = dir / "large.json";
  write(preset, "");
  fs::resize_file(preset, (std::uintmax_t(64) << 20) + 1);  // sparse: nothing is written
  const auto r = run_skybake({"bake", preset.string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("is 67108865 bytes, more than the limit of 67108864 bytes"),
            std::string::npos)
      << r.err;
}

// A baked scene whose manifest.json the test then replaces.
struct BakedScene {
  fs::path dir, scene, out, manifest;
};

BakedScene baked(const std::string& name) {
  BakedScene b;
  b.dir = fresh_dir(name);
  b.scene = b.dir / "scene.json";
  b.out = b.dir / "out";
  b.manifest = b.out / "hostile" / "manifest.json";
  write(b.scene, small_scene(earth_atmosphere().string()));
  const auto r = run_skybake({"bake", b.scene.string(), "-o", b.out.string(), "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return b;
}

// bake, plan and info each read the manifest; none may crash or report an
// internal error, and the bake leaves a manifest that parses.
void expect_treated_as_missing(const BakedScene& b) {
  const auto plan = run_skybake({"plan", b.scene.string(), "-o", b.out.string(), "--json"});
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const auto graph = nlohmann::json::parse(plan.out);
  EXPECT_FALSE(graph["scenes"][0]["nodes"][0]["up_to_date"].get<bool>()) << plan.out;
  // The whole file set aside, or the one entry as a damaged record.
  EXPECT_TRUE(plan.err.find("manifest.json: not a manifest skybake can read") != std::string::npos ||
              plan.err.find("manifest.json: 1 damaged record set aside") != std::string::npos)
      << plan.err;

  const auto info = run_skybake({"info", (b.out / "hostile" / "transmittance.dds").string()});
  EXPECT_EQ(info.exit_code, 0) << info.err;

  const auto bake = run_skybake({"bake", b.scene.string(), "-o", b.out.string(), "-q"});
  EXPECT_EQ(bake.exit_code, 0) << bake.err;
  const auto manifest = nlohmann::json::parse(read_file(b.manifest));
  EXPECT_EQ(manifest["outputs"][0]["name"], "transmittance");
  const auto again = run_skybake({"plan", b.scene.string(), "-o", b.out.string(), "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(nlohmann::json::parse(again.out)["scenes"][0]["nodes"][0]["up_to_date"].get<bool>());
}

TEST(HostileJson, ManifestNestedAMillionDeepIsAMissingCache) {
  const BakedScene b = baked("hostile_deep_manifest");
  write(b.manifest, nested_arrays(1000000));
  expect_treated_as_missing(b);
}

TEST(HostileJson, ManifestWithWrongTypesIsAMissingCache) {
  const BakedScene b = baked("hostile_typed_manifest");
  auto m = nlohmann::json::parse(read_file(b.manifest));
  for (const auto& [pointer, value] :
       std::vector<std::pair<std::string, nlohmann::json>>{{"/outputs/0/files", {1, 2}},
                                                            {"/outputs/0/dimensions", {1e300}},
                                                            {"/outputs/0/metadata", 7},
                                                            {"/outputs/0/metadata/x", {1, 2, 3, 4}},
                                                            {"/outputs/0/metadata/x", {1, 2.5}},
                                                            {"/outputs/0/metadata/x", {{"a", 1}}},
                                                            {"/outputs", "x"},
                                                            {"/outputs/0", 3}}) {
    auto bad = m;
    bad[nlohmann::json::json_pointer(pointer)] = value;
    write(b.manifest, bad.dump());
    SCOPED_TRACE(pointer);
    expect_treated_as_missing(b);
  }
}

TEST(HostileJson, ManifestPathThatIsADirectoryIsAFileError) {
  const BakedScene b = baked("hostile_dir_manifest");
  fs::remove(b.manifest);
  fs::create_directory(b.manifest);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bake", b.scene.string(), "-o", b.out.string(), "-q"},
        {"plan", b.scene.string(), "-o", b.out.string()},
        {"info", (b.out / "hostile" / "transmittance.dds").string()}}) {
    const auto r = run_skybake(args);
    EXPECT_EQ(r.exit_code, 4) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find(b.manifest.string() + ": cannot read manifest: is a directory"),
              std::string::npos)
        << args[0] << ": " << r.err;
  }
}

TEST(HostileJson, CatalogFolderWithADeepJsonNamesIt) {
  const fs::path dir = fresh_dir("hostile_catalog");
  fs::create_directories(dir / "catalog");
  write(dir / "catalog" / "deep.json", nested_arrays(50000));
  const auto r = run_skybake({"plan", (dir / "catalog").string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("deep.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("deeper than the limit"), std::string::npos) << r.err;
}

}  // namespace
