// A shipped preset's manifest errors against `skybake report --quick`'s
// operating points (bake_error_test.cpp, bake_error_accuracy_test.cpp): the
// report's ladder sections run directly, as `report --quick` runs them.
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "report/sections.hpp"
#include "support/run.hpp"

namespace skybake::bake_error {

namespace fs = std::filesystem;
using nlohmann::json;

// A shipped preset baked once, its manifest's error per output.
struct BakedPreset {
  Scene scene;
  std::map<std::string, json> error;  // by product
};

inline BakedPreset bake(const std::string& preset) {
  const fs::path out = test::fresh_dir("bake_error_" + preset);
  const fs::path file = test::source_path("presets/" + preset + ".json");
  const auto run = test::run_skybake({"bake", file.string(), "-o", out.string(), "-q"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  BakedPreset b{load_scene(file), {}};
  const json m = json::parse(test::read_file(out / b.scene.name / "manifest.json"));
  for (const json& o : m["outputs"]) b.error[o["product"]] = o["error"];
  return b;
}

// The report's --quick operating point of `product` (its ladder section, as
// run_report runs it: the operating-point tables baked at the preset's
// settings and the level's fine transmittance).
inline json report_operating_point(const Scene& scene, const std::string& product) {
  const json settings = level_settings(true);
  const ReportLevel level = settings.get<ReportLevel>();
  const Atmosphere& atm = scene.atmosphere;
  const Texture t = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  const Texture ms = bake_multiscattering_lut(
      atm, t, multiscattering_spec(operating_spec(scene, "multiscattering")), BakeContext{});
  TransmittanceLutSpec fine;
  fine.width = level.reference_transmittance_size.at(0);
  fine.height = level.reference_transmittance_size.at(1);
  fine.steps = level.reference_transmittance_steps;
  const Texture reference = bake_transmittance_lut(atm, fine, BakeContext{});
  const json report = json::object();
  const ReportInputs in{
      scene, level, t, ms, reference, report, test::fresh_dir("bake_error_report_" + product), {}};
  for (const ReportSection& s : report_sections())
    if (s.place == "/products/-" &&
        std::find(s.products.begin(), s.products.end(), product) != s.products.end()) {
      const json j = s.run(in, settings);
      return j["ladder"][j["operating_point"].get<size_t>()];
    }
  ADD_FAILURE() << "no ladder for " << product;
  return json();
}

inline void expect_within_2x(const BakedPreset& b, const std::vector<std::string>& products) {
  for (const std::string& product : products) {
    ASSERT_TRUE(b.error.count(product)) << product;
    const json& manifest = b.error.at(product);
    ASSERT_TRUE(manifest.is_object()) << product;
    const json report = report_operating_point(b.scene, product);
    for (const char* key : {"max_rel", "rms_rel"}) {
      const double ours = manifest[key], theirs = report[key];
      EXPECT_GE(ours, 0.5 * theirs) << b.scene.name << "/" << product << " " << key;
      EXPECT_LE(ours, 2.0 * theirs) << b.scene.name << "/" << product << " " << key;
    }
  }
}

}  // namespace skybake::bake_error
