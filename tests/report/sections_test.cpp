// The report's table of sections: every row names real products, no two
// setups share a level_settings key (a section reads its own keys out of the
// merged settings), each setup round-trips through that JSON, and which
// sections run follows from the products the report covers.
#include "report/sections.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "pipeline/product.hpp"

namespace skybake {
namespace {

using nlohmann::json;

std::vector<std::string> running(const std::vector<std::string>& products) {
  std::vector<std::string> names;
  for (const ReportSection& s : report_sections())
    if (section_runs(s, products)) names.push_back(s.name);
  return names;
}

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

TEST(ReportSections, NamesAreUniqueAndProductsAreRegistered) {
  std::set<std::string> names;
  for (const ReportSection& s : report_sections()) {
    EXPECT_TRUE(names.insert(s.name).second) << "two sections named " << s.name;
    EXPECT_TRUE(s.run) << s.name;
    EXPECT_FALSE(s.place.empty()) << s.name;
    EXPECT_EQ(s.place[0], '/') << s.name << ": place must be a JSON pointer";
    for (const std::string& p : s.products)
      EXPECT_NE(find_product(p), nullptr) << s.name << ": " << p;
  }
}

TEST(ReportSections, SetupKeysAreOwnedByOneSectionAndEqualAtBothLevels) {
  std::map<std::string, std::string> owner;
  const json shared = ReportLevel::full();
  for (const auto& [key, value] : shared.items()) owner[key] = "ReportLevel";
  for (const ReportSection& s : report_sections()) {
    ASSERT_TRUE(s.quick.is_object()) << s.name;
    std::set<std::string> quick_keys, full_keys;
    for (const auto& [key, value] : s.quick.items()) quick_keys.insert(key);
    for (const auto& [key, value] : s.full.items()) full_keys.insert(key);
    EXPECT_EQ(quick_keys, full_keys) << s.name;
    for (const std::string& key : full_keys) {
      const auto [it, fresh] = owner.emplace(key, s.name);
      EXPECT_TRUE(fresh) << key << " is a setting of both " << it->second << " and " << s.name;
    }
  }
  // The merged settings hold every key once, with each section's own value.
  for (bool quick : {true, false}) {
    const json settings = level_settings(quick);
    EXPECT_EQ(settings.size(), owner.size());
    EXPECT_EQ(settings["name"], quick ? "quick" : "full");
    for (const ReportSection& s : report_sections())
      for (const auto& [key, value] : (quick ? s.quick : s.full).items())
        EXPECT_EQ(settings.at(key), value) << s.name << " " << key;
  }
}

TEST(ReportSections, QuickIsNoLargerThanFull) {
  // Quick exists to be fast: no count of a quick setup exceeds the full one's.
  const json quick = level_settings(true), full = level_settings(false);
  int counts = 0;
  for (const auto& [key, value] : full.items()) {
    if (!value.is_number_integer()) continue;
    EXPECT_LE(quick[key].get<long>(), value.get<long>()) << key;
    ++counts;
  }
  EXPECT_GT(counts, 10);
}

TEST(ReportSections, LaddersMeasureTheirProductsAndOnlyThose) {
  for (const ReportSection& s : report_sections()) {
    if (s.place != "/products/-") continue;
    for (const std::string& p : s.products) EXPECT_TRUE(is_measured(p)) << p;
  }
  for (const char* p : {"sky_preview", "curl", "weather", "noise_shape"})
    EXPECT_FALSE(is_measured(p)) << p;
}

TEST(ReportSections, WhichSectionsRunFollowsTheProducts) {
  // Nothing the atmosphere tables measure: no section.
  EXPECT_TRUE(running({}).empty());
  EXPECT_TRUE(running({"sky_preview"}).empty());

  const std::vector<std::string> t = running({"transmittance"});
  EXPECT_TRUE(contains(t, "transmittance"));
  EXPECT_TRUE(contains(t, "horizon_transmittance"));
  EXPECT_FALSE(contains(t, "sky_radiance"));
  EXPECT_FALSE(contains(t, "skyview"));
  // Sections without products of their own follow any section that runs.
  for (const ReportSection& s : report_sections()) {
    if (s.products.empty()) {
      EXPECT_TRUE(contains(t, s.name)) << s.name;
    }
  }

  const std::vector<std::string> sky = running({"scattering"});
  EXPECT_TRUE(contains(sky, "scattering"));
  EXPECT_TRUE(contains(sky, "sky_radiance"));
  EXPECT_FALSE(contains(sky, "transmittance"));
}

TEST(ReportSections, BrunetonComparisonRunsAfterTheSkyRadianceItReads) {
  const auto& table = report_sections();
  const auto at = [&](const std::string& name) {
    return std::find_if(table.begin(), table.end(),
                        [&](const ReportSection& s) { return s.name == name; }) -
           table.begin();
  };
  ASSERT_LT(at("sky_radiance"), long(table.size()));
  ASSERT_LT(at("bruneton_comparison"), long(table.size()));
  EXPECT_LT(at("sky_radiance"), at("bruneton_comparison"));
}

}  // namespace
}  // namespace skybake
