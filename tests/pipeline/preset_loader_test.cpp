// Preset loading: the shipped presets, SI conversion, defaults, the reference
// and inline forms, and the bad-input corpus of tests/bad_presets/ (each file
// must fail with the pointer and rule listed in its EXPECTED.json).
#include "pipeline/preset_loader.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "pipeline/schema_validator.hpp"

namespace skybake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kRoot = SKYBAKE_SOURCE_DIR;
const fs::path kPresets = kRoot / "presets";
const fs::path kBad = kRoot / "tests" / "bad_presets";

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

// A scratch folder per test, emptied first.
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(SKYBAKE_TEST_TMP) / "preset_loader" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p;
}

// Earth with the atmosphere inline: the same values as presets/earth.json.
json inline_earth() {
  json scene = read_json(kPresets / "earth.json");
  json atmosphere = read_json(kPresets / "atmospheres" / "earth.json");
  atmosphere.erase("$schema");
  scene["atmosphere"] = atmosphere;
  scene.erase("$schema");
  return scene;
}

const MediumComponent* component(const Atmosphere& a, const std::string& name) {
  for (const MediumComponent& c : a.components)
    if (c.name == name) return &c;
  return nullptr;
}

// The rule of the PresetError that loading `file` throws ("" if none).
PresetError load_error(const fs::path& file) {
  try {
    load_scene(file);
  } catch (const PresetError& e) {
    return e;
  }
  ADD_FAILURE() << file << " loaded without error";
  return PresetError("", "", "");
}

TEST(PresetLoader, ShippedPresetsLoad) {
  for (const char* name : {"earth", "mars", "tiny_planet"}) {
    SCOPED_TRACE(name);
    const Scene scene = load_scene(kPresets / (std::string(name) + ".json"));
    EXPECT_EQ(scene.name, name);
    ASSERT_FALSE(scene.outputs.empty());
    EXPECT_EQ(scene.outputs[0].product, "transmittance");
    EXPECT_EQ(scene.outputs[0].pointer, "/outputs/0");
    EXPECT_GT(scene.atmosphere.top_radius_m, scene.atmosphere.bottom_radius_m);
    EXPECT_FALSE(scene.resolved.contains("$schema"));
  }
}

TEST(PresetLoader, ShippedPresetSchemaPathsExistForEditors) {
  for (const fs::path& p :
       {kPresets / "earth.json", kPresets / "mars.json", kPresets / "tiny_planet.json",
        kPresets / "atmospheres" / "earth.json"}) {
    const json doc = read_json(p);
    ASSERT_TRUE(doc.contains("$schema")) << p;
    EXPECT_TRUE(fs::exists(p.parent_path() / doc["$schema"].get<std::string>())) << p;
  }
}

TEST(PresetLoader, EarthInSiUnits) {
  const Scene scene = load_scene(kPresets / "earth.json");
  const Atmosphere& a = scene.atmosphere;
  EXPECT_DOUBLE_EQ(a.bottom_radius_m, 6.36e6);
  EXPECT_DOUBLE_EQ(a.top_radius_m, 6.46e6);
  EXPECT_EQ(a.ground_albedo, glm::dvec3(0.3));
  EXPECT_DOUBLE_EQ(a.sun_angular_radius_rad, 0.004675);
  ASSERT_EQ(a.components.size(), 3u);

  const MediumComponent* rayleigh = component(a, "rayleigh");
  ASSERT_NE(rayleigh, nullptr);
  EXPECT_EQ(rayleigh->phase, PhaseKind::rayleigh);
  EXPECT_EQ(rayleigh->scattering_per_m, glm::dvec3(5.802e-6, 13.558e-6, 33.1e-6));
  EXPECT_EQ(rayleigh->absorption_per_m, glm::dvec3(0.0));
  ASSERT_EQ(rayleigh->density.layers.size(), 1u);
  EXPECT_DOUBLE_EQ(rayleigh->density.layers[0].exp_term, 1.0);
  EXPECT_DOUBLE_EQ(rayleigh->density.layers[0].exp_scale_per_m, -1.0 / 8000.0);
  EXPECT_NEAR(density_at(rayleigh->density, 8000.0), std::exp(-1.0), 1e-15);

  const MediumComponent* mie = component(a, "mie");
  ASSERT_NE(mie, nullptr);
  EXPECT_EQ(mie->phase, PhaseKind::cornette_shanks);
  EXPECT_DOUBLE_EQ(mie->g, 0.8);
  EXPECT_EQ(mie->absorption_per_m, glm::dvec3(0.444e-6));
  EXPECT_DOUBLE_EQ(mie->density.layers[0].exp_scale_per_m, -1.0 / 1200.0);

  const MediumComponent* ozone = component(a, "ozone");
  ASSERT_NE(ozone, nullptr);
  EXPECT_EQ(ozone->phase, PhaseKind::none);
  EXPECT_EQ(ozone->scattering_per_m, glm::dvec3(0.0));
  EXPECT_DOUBLE_EQ(density_at(ozone->density, 25e3), 1.0);
  EXPECT_NEAR(density_at(ozone->density, 10e3), 0.0, 1e-12);
  EXPECT_NEAR(density_at(ozone->density, 17.5e3), 0.5, 1e-12);
  EXPECT_NEAR(density_at(ozone->density, 32.5e3), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(density_at(ozone->density, 45e3), 0.0);
}

TEST(PresetLoader, ReferenceAndInlineFormsAreTheSame) {
  const fs::path dir = scratch("inline");
  const Scene referenced = load_scene(kPresets / "earth.json");
  const Scene inlined = load_scene(write(dir / "earth.json", inline_earth().dump(2)));
  const Atmosphere& a = referenced.atmosphere;
  const Atmosphere& b = inlined.atmosphere;
  EXPECT_EQ(a.bottom_radius_m, b.bottom_radius_m);
  EXPECT_EQ(a.top_radius_m, b.top_radius_m);
  EXPECT_EQ(a.sun_illuminance, b.sun_illuminance);
  ASSERT_EQ(a.components.size(), b.components.size());
  for (size_t i = 0; i < a.components.size(); ++i) {
    EXPECT_EQ(a.components[i].name, b.components[i].name);
    EXPECT_EQ(a.components[i].scattering_per_m, b.components[i].scattering_per_m);
    EXPECT_EQ(a.components[i].absorption_per_m, b.components[i].absorption_per_m);
    EXPECT_EQ(a.components[i].g, b.components[i].g);
    ASSERT_EQ(a.components[i].density.layers.size(), b.components[i].density.layers.size());
    for (size_t l = 0; l < a.components[i].density.layers.size(); ++l) {
      EXPECT_EQ(a.components[i].density.layers[l].width_m,
                b.components[i].density.layers[l].width_m);
      EXPECT_EQ(a.components[i].density.layers[l].linear_term_per_m,
                b.components[i].density.layers[l].linear_term_per_m);
    }
  }
  // Same hash input: the cache does not care which form the preset uses.
  EXPECT_EQ(referenced.resolved.dump(), inlined.resolved.dump());
}

TEST(PresetLoader, PlanetReferenceIsResolvedRelativeToTheScene) {
  const fs::path dir = scratch("planet_ref");
  write(dir / "planets" / "rock.json",
        R"({"$schema": "x/planet.schema.json", "radius_km": 100, "description": "a rock"})");
  json scene = inline_earth();
  scene["planet"] = "planets/rock.json";
  scene["atmosphere"]["top_radius_km"] = 120;
  const Scene s = load_scene(write(dir / "scene.json", scene.dump()));
  EXPECT_DOUBLE_EQ(s.atmosphere.bottom_radius_m, 1e5);
  EXPECT_EQ(s.atmosphere.ground_albedo, glm::dvec3(0.3));  // planet schema default
  EXPECT_EQ(s.resolved["planet"], json({{"radius_km", 100}, {"ground_albedo", {0.3, 0.3, 0.3}}}));
}

TEST(PresetLoader, DefaultsAreFilledIn) {
  const fs::path dir = scratch("defaults");
  json scene = {
      {"name", "d"},
      {"planet", {{"radius_km", 10}}},
      {"atmosphere",
       {{"top_radius_km", 20},
        {"mie",
         {{"scattering_per_m", {1e-5, 1e-5, 1e-5}}, {"density", {{"uniform", {{"top_km", 3}}}}}}}}},
      {"outputs", json::array({{{"product", "transmittance"}}})}};
  const Scene s = load_scene(write(dir / "d.json", scene.dump()));
  const Atmosphere& a = s.atmosphere;
  EXPECT_EQ(a.ground_albedo, glm::dvec3(0.3));
  EXPECT_EQ(a.sun_illuminance, glm::dvec3(1.0));
  EXPECT_DOUBLE_EQ(a.sun_angular_radius_rad, 0.004675);
  ASSERT_EQ(a.components.size(), 1u);
  EXPECT_EQ(a.components[0].phase, PhaseKind::cornette_shanks);
  EXPECT_DOUBLE_EQ(a.components[0].g, 0.8);
  EXPECT_EQ(a.components[0].absorption_per_m, glm::dvec3(0.0));
  EXPECT_DOUBLE_EQ(density_at(a.components[0].density, 2e3), 1.0);
  EXPECT_DOUBLE_EQ(density_at(a.components[0].density, 4e3), 0.0);

  ASSERT_EQ(s.outputs.size(), 1u);
  const OutputSpec& out = s.outputs[0];
  EXPECT_EQ(out.name, "transmittance");
  EXPECT_EQ(out.size, (std::vector<int>{256, 64}));
  EXPECT_EQ(out.formats, (std::vector<std::string>{"exr", "dds"}));
  EXPECT_EQ(out.precision, "float");
  EXPECT_EQ(out.options.value("steps", 0), 6);
  EXPECT_EQ(out.options, s.resolved["outputs"][0]);
  EXPECT_EQ(s.resolved["atmosphere"]["sun"]["angular_radius_rad"], 0.004675);
  EXPECT_EQ(s.resolved["atmosphere"]["mie"]["phase"], "cornette_shanks");
}

TEST(PresetLoader, ZeroComponentsAreDroppedAndVacuumIsValid) {
  const fs::path dir = scratch("zero");
  json scene = inline_earth();
  scene["atmosphere"]["rayleigh"]["scattering_per_m"] = {0, 0, 0};
  scene["atmosphere"]["mie"]["scattering_per_m"] = {0, 0, 0};
  scene["atmosphere"]["mie"]["absorption_per_m"] = {0, 0, 0};
  const Scene s = load_scene(write(dir / "zero.json", scene.dump()));
  ASSERT_EQ(s.atmosphere.components.size(), 1u);
  EXPECT_EQ(s.atmosphere.components[0].name, "ozone");

  scene["atmosphere"] = {{"top_radius_km", 6460}};
  const Scene vacuum = load_scene(write(dir / "vacuum.json", scene.dump()));
  EXPECT_TRUE(vacuum.atmosphere.components.empty());
}

TEST(PresetLoader, GeneralLayersAndExtraComponents) {
  const fs::path dir = scratch("layers");
  json scene = inline_earth();
  scene["atmosphere"]["extra"] = json::array(
      {{{"name", "dust"},
        {"scattering_per_m", {2e-6, 2e-6, 2e-6}},
        {"phase", "henyey_greenstein"},
        {"g", 0.5},
        {"density",
         {{"layers", json::array({{{"width_km", 10}, {"linear_term_per_km", 0.1}},
                                  {{"exp_term", 1}, {"exp_scale_per_km", -0.125}}})}}}}});
  const Scene s = load_scene(write(dir / "layers.json", scene.dump()));
  const MediumComponent* dust = component(s.atmosphere, "dust");
  ASSERT_NE(dust, nullptr);
  EXPECT_EQ(dust->phase, PhaseKind::henyey_greenstein);
  ASSERT_EQ(dust->density.layers.size(), 2u);
  EXPECT_DOUBLE_EQ(dust->density.layers[0].width_m, 1e4);
  EXPECT_DOUBLE_EQ(dust->density.layers[0].linear_term_per_m, 1e-4);
  EXPECT_DOUBLE_EQ(dust->density.layers[1].exp_scale_per_m, -1.25e-4);
  EXPECT_NEAR(density_at(dust->density, 5e3), 0.5, 1e-12);
}

TEST(PresetLoader, ResolvedIgnoresFormattingKeyOrderAndDescriptions) {
  const fs::path dir = scratch("canonical");
  json scene = inline_earth();
  const Scene a = load_scene(write(dir / "a.json", scene.dump(2)));
  scene["description"] = "changed words";
  scene["atmosphere"]["description"] = "more words";
  // nlohmann writes sorted keys; reverse them by hand so the file order differs.
  std::string text = "{\"outputs\": " + scene["outputs"].dump() + ", \"name\": \"earth\", " +
                     "\"atmosphere\": " + scene["atmosphere"].dump() +
                     ", \"planet\": " + scene["planet"].dump() + "}";
  const Scene b = load_scene(write(dir / "b.json", text));
  EXPECT_EQ(a.resolved.dump(), b.resolved.dump());
  scene["planet"]["radius_km"] = 6361;
  const Scene c = load_scene(write(dir / "c.json", scene.dump()));
  EXPECT_NE(a.resolved.dump(), c.resolved.dump());
}

TEST(PresetLoader, MisspelledKeyGetsDidYouMean) {
  const fs::path dir = scratch("misspelled");
  json scene = inline_earth();
  scene["planet"]["ground_albdo"] = scene["planet"]["ground_albedo"];
  scene["planet"].erase("ground_albedo");
  const fs::path file = write(dir / "typo.json", scene.dump(2));
  const PresetError e = load_error(file);
  EXPECT_EQ(e.file(), file.string());
  EXPECT_EQ(e.pointer(), "/planet/ground_albdo");
  EXPECT_EQ(e.rule(), "unknown key 'ground_albdo' (did you mean 'ground_albedo'?)");
  EXPECT_EQ(std::string(e.what()), file.string() +
                                       ": /planet/ground_albdo: unknown key 'ground_albdo' (did "
                                       "you mean 'ground_albedo'?)");
  EXPECT_EQ(e.exit_code(), kExitPreset);
}

TEST(PresetLoader, MissingPresetIsAnIoError) {
  EXPECT_THROW(load_scene(kPresets / "no_such_scene.json"), IoError);
}

// Every file of tests/bad_presets/ fails with the pointer and rule fragment
// listed in EXPECTED.json; the error names the file holding the mistake.
TEST(PresetLoader, BadPresetCorpus) {
  const json expected = read_json(kBad / "EXPECTED.json");
  std::set<std::string> listed;
  for (auto& [name, want] : expected.items()) {
    SCOPED_TRACE(name);
    listed.insert(name);
    const fs::path file = kBad / name;
    ASSERT_TRUE(fs::exists(file));
    const PresetError e = load_error(file);
    const std::string error_file = (kBad / want.value("file", name)).lexically_normal().string();
    EXPECT_EQ(fs::path(e.file()).lexically_normal().string(), error_file);
    EXPECT_EQ(e.pointer(), want["pointer"].get<std::string>());
    EXPECT_NE(e.rule().find(want["rule"].get<std::string>()), std::string::npos)
        << "rule: " << e.rule();
    const std::string what = e.what();
    EXPECT_NE(what.find(e.file()), std::string::npos);
    EXPECT_NE(what.find(want["pointer"].get<std::string>()), std::string::npos) << what;
  }
  // No unlisted files (a file without an expectation tests nothing).
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kBad)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name == "EXPECTED.json") continue;
    ++files;
    EXPECT_TRUE(listed.count(name)) << name << " is not in EXPECTED.json";
  }
  EXPECT_EQ(files, listed.size());
  EXPECT_GE(files, 30u);
}

TEST(PresetLoader, OutputSizeBudgetIsCheckedBeforeAllocation) {
  ProductInfo volume;
  volume.name = "volume";
  volume.axes = {"x", "y", "z"};
  volume.max_size = {4096, 4096, 4096};
  EXPECT_EQ(output_bytes({256, 64}), 256u * 64u * 16u);
  EXPECT_NO_THROW(check_output_size(volume, {256, 256, 256}, "f.json", "/outputs/0/size"));
  try {
    check_output_size(volume, {2048, 2048, 2048}, "f.json", "/outputs/0/size");
    FAIL() << "a 128 GiB volume was accepted";
  } catch (const PresetError& e) {
    EXPECT_EQ(e.pointer(), "/outputs/0/size");
    EXPECT_NE(e.rule().find("over the 2 GiB budget"), std::string::npos) << e.rule();
  }
  EXPECT_THROW(check_output_size(volume, {64, 64}, "f.json", "/p"), PresetError);
  EXPECT_THROW(check_output_size(volume, {64, 64, 5000}, "f.json", "/p"), PresetError);
  EXPECT_EQ(output_bytes({1 << 20, 1 << 20, 1 << 20, 1 << 20}), UINT64_MAX);  // saturates
}

TEST(PresetLoader, MaxErrorOnlyWhereTheBakeMeasuresAnError) {
  const fs::path dir = scratch("max_error");
  json scene = inline_earth();
  scene["outputs"] = json::array({{{"product", "transmittance"}, {"max_error", 0.05}}});
  const Scene loaded = load_scene(write(dir / "lut.json", scene.dump()));
  EXPECT_DOUBLE_EQ(loaded.outputs.at(0).options.at("max_error").get<double>(), 0.05);

  scene["outputs"][0]["max_error"] = 0;
  EXPECT_EQ(load_error(write(dir / "zero.json", scene.dump())).pointer(), "/outputs/0/max_error");

  // On a product whose error is not measured it changes nothing: a warning,
  // as every key with no effect (docs/presets.md "Keys that have no effect").
  const json noise = {{"name", "noise"},
                      {"outputs", json::array({{{"product", "noise_detail"}, {"max_error", 0.1}}})}};
  const Scene warned = load_scene(write(dir / "noise.json", noise.dump()));
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(warned.warnings[0].pointer, "/outputs/0/max_error");
  EXPECT_NE(warned.warnings[0].rule.find("measures no error of noise_detail"), std::string::npos)
      << warned.warnings[0].rule;
}

// twilight_source chooses between the converged sources; with the
// multiscattering table's march it changes nothing.
TEST(PresetLoader, TwilightSourceOnlyWithTheConvergedField) {
  const fs::path dir = scratch("twilight_source");
  json scene = inline_earth();
  scene["outputs"] = json::array({{{"product", "sky_irradiance"},
                                   {"twilight_source", "converged_field"}}});
  EXPECT_TRUE(load_scene(write(dir / "field.json", scene.dump())).warnings.empty());
  scene["outputs"][0]["radiance_source"] = "multiscattering_table";
  const Scene warned = load_scene(write(dir / "table.json", scene.dump()));
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(warned.warnings[0].pointer, "/outputs/0/twilight_source");
  scene["outputs"][0]["twilight_source"] = "hillaire";
  EXPECT_EQ(load_error(write(dir / "bad.json", scene.dump())).pointer(),
            "/outputs/0/twilight_source");
}

TEST(PresetLoader, SpectrumWithoutSpectralHasNoEffect) {
  const fs::path dir = scratch("spectrum_rgb");
  // The shipped spectral Earth, its atmosphere file referenced from elsewhere.
  json scene = read_json(kPresets / "earth_spectral.json");
  scene["atmosphere"] = (kPresets / "atmospheres" / "earth_spectral.json").string();
  scene["$schema"] = (kRoot / "schemas" / "scene.schema.json").string();
  EXPECT_TRUE(load_scene(write(dir / "spectral.json", scene.dump())).warnings.empty());

  scene.erase("spectral");
  const Scene rgb = load_scene(write(dir / "rgb.json", scene.dump()));
  ASSERT_EQ(rgb.warnings.size(), 1u);
  EXPECT_EQ(fs::path(rgb.warnings[0].file).filename(), "earth_spectral.json");
  EXPECT_NE(fs::path(rgb.warnings[0].file).parent_path(), dir);  // the atmosphere's file
  EXPECT_EQ(rgb.warnings[0].pointer, "/spectrum");
  EXPECT_NE(rgb.warnings[0].rule.find("has no effect"), std::string::npos) << rgb.warnings[0].rule;
}

TEST(PresetLoader, SchemaDirCanBeOverriddenAtRunTime) {
  const fs::path dir = scratch("schema_dir");
  fs::copy(kRoot / "schemas", dir / "schemas", fs::copy_options::recursive);
  json product = read_json(dir / "schemas" / "products" / "transmittance.schema.json");
  product["properties"]["steps"]["default"] = 41;
  write(dir / "schemas" / "products" / "transmittance.schema.json", product.dump());
  const fs::path file = write(dir / "earth.json", inline_earth().dump());

  ::setenv("SKYBAKE_SCHEMA_DIR", (dir / "schemas").c_str(), 1);
  const Scene overridden = load_scene(file);
  ::setenv("SKYBAKE_SCHEMA_DIR", (dir / "missing").c_str(), 1);
  EXPECT_THROW(load_scene(file), IoError);
  ::unsetenv("SKYBAKE_SCHEMA_DIR");
  EXPECT_EQ(overridden.outputs[0].options.value("steps", 0), 41);
  EXPECT_EQ(load_scene(file).outputs[0].options.value("steps", 0), 6);
}

// Editors show help from "description"s: every property of every schema has one.
void expect_described(const json& node, const std::string& where) {
  if (node.is_object()) {
    if (node.contains("properties")) {
      for (auto& [key, prop] : node["properties"].items())
        EXPECT_TRUE(prop.contains("description") || prop.contains("$ref")) << where << " " << key;
    }
    for (auto& [key, child] : node.items()) expect_described(child, where + "/" + key);
  } else if (node.is_array()) {
    for (const json& child : node) expect_described(child, where);
  }
}

TEST(PresetLoader, SchemasDescribeEveryProperty) {
  for (const auto& entry : fs::recursive_directory_iterator(kRoot / "schemas")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const json schema = read_json(entry.path());
    EXPECT_TRUE(schema.contains("$id"));
    EXPECT_TRUE(schema.contains("title"));
    EXPECT_TRUE(schema.contains("description"));
    expect_described(schema, entry.path().filename().string());
  }
}

}  // namespace
}  // namespace skybake
