// validate_against_schema_all: every violation of a document is found, each
// with the rule and pointer validate_against_schema gives for it alone; the
// patched document passes the schema; a misspelled required key counts
// once; stand-ins never invent a duplicate; the cap is kept.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pipeline/schema_validator.hpp"

namespace skybake {
namespace {

using nlohmann::json;

json scene_with_problems() {
  return json::parse(R"({
    "name": "Bad Name",
    "planet": {"radius_km": 6360, "ground_albedo": [0.3, 1.5, 0.3]},
    "atmosphere": {"top_radius_km": 6460,
                   "mie": {"g": 1, "density": {"exponential": {"scale_heigt_km": 1.2}}}},
    "outputs": [{"product": "transmittance", "formats": ["exr", "tiff"], "size": [0, 64]}]
  })");
}

TEST(SchemaProblems, EveryViolationIsFoundAndThePatchedDocumentPasses) {
  json patched;
  const auto all =
      validate_against_schema_all(scene_with_problems(), "scene.schema.json", 100, &patched);
  std::vector<std::string> pointers;
  for (const SchemaViolation& v : all) pointers.push_back(v.pointer);
  EXPECT_EQ(pointers, (std::vector<std::string>{
                          "/atmosphere/mie/density/exponential/scale_heigt_km",
                          "/atmosphere/mie/g",
                          "/atmosphere/mie",  // no scattering_per_m
                          "/name",
                          "/outputs/0/formats/1",
                          "/outputs/0/size/0",
                          "/planet/ground_albedo/1",
                      }));
  // The first is what the first-error validator reports.
  const auto first = validate_against_schema(scene_with_problems(), "scene.schema.json");
  ASSERT_TRUE(first);
  EXPECT_EQ(all.front().pointer, first->pointer);
  EXPECT_EQ(all.front().rule, first->rule);
  EXPECT_EQ(all[1].rule, "must be <= 0.999999, got 1");
  ASSERT_FALSE(patched.is_null());
  EXPECT_FALSE(validate_against_schema(patched, "scene.schema.json"));
  // The misspelled required key is read as the key it meant.
  EXPECT_EQ(patched["atmosphere"]["mie"]["density"]["exponential"]["scale_height_km"], 1.2);
  // The unknown format stands in by one the array does not hold yet.
  EXPECT_EQ(patched["outputs"][0]["formats"], json({"exr", "dds"}));
}

TEST(SchemaProblems, ARepeatedItemIsOneProblem) {
  const json doc = json::parse(
      R"({"name": "a", "outputs": [{"product": "transmittance", "formats": ["exr", "exr", "dds"]}]})");
  json patched;
  const auto all = validate_against_schema_all(doc, "scene.schema.json", 100, &patched);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].keyword, "uniqueItems");
  EXPECT_EQ(patched["outputs"][0]["formats"], json({"exr", "dds"}));
}

TEST(SchemaProblems, MissingRequiredKeysGetStandIns) {
  const json doc = json::parse(R"({"planet": {"ground_albedo": [0.3, 0.3, 0.3]}})");
  json patched;
  const auto all = validate_against_schema_all(doc, "scene.schema.json", 100, &patched);
  ASSERT_FALSE(all.empty());
  ASSERT_FALSE(patched.is_null());
  EXPECT_TRUE(patched.contains("name"));
  EXPECT_TRUE(patched["planet"].contains("radius_km"));
  EXPECT_GE(patched["outputs"].size(), 1u);
}

TEST(SchemaProblems, TheCapIsKeptAndLeavesNoPatchedDocument) {
  json outputs = json::array();
  for (int i = 0; i < 10; ++i) outputs.push_back({{"product", "transmittance"}, {"size", {0, 0}}});
  json patched = json::object();
  const auto all = validate_against_schema_all({{"name", "a"}, {"outputs", outputs}},
                                               "scene.schema.json", 5, &patched);
  EXPECT_EQ(all.size(), 5u);
  EXPECT_TRUE(patched.is_null());
  EXPECT_TRUE(validate_against_schema_all({{"name", "a"}, {"outputs", {{{"product", "x"}}}}},
                                          "scene.schema.json", 5)
                  .empty());
}

}  // namespace
}  // namespace skybake
