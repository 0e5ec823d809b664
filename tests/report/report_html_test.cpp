// report_html (report/html.hpp) on a report.json written here: the
// sky_irradiance section shows each texel's three errors apart, its target
// and its setup in prose, and says when it was not run.
#include "report/html.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace skybake {
namespace {

using nlohmann::json;

json report_with(const json& sky_irradiance, const std::string& level) {
  return {{"scene", "earth"},       {"preset", "earth.json"},    {"tool", "skybake"},
          {"level", level},         {"seconds", 1.0},            {"products", json::array()},
          {"sky_radiance", nullptr}, {"hillaire_runtime", nullptr}, {"precision", {{"horizon_transmittance", nullptr}, {"half", json::array()}}},
          {"bruneton_comparison", nullptr}, {"files", json::object()},
          {"sky_irradiance", sky_irradiance}};
}

json measured_sky_irradiance(const std::string& status) {
  json texel = {{"altitude_m", 250.0},
                {"sun_zenith_deg", 45.0},
                {"decode", {{"rms", 0.0123}, {"max", 0.0456}}},
                {"l2_limit", {{"rms", 0.0031}, {"max", 0.0095}}},
                {"interpolation", {{"rms", 0.0211}, {"max", 0.0777}}}};
  return {{"product", "sky_irradiance"},
          {"radiance_source", "field"},
          {"size", {32, 16}},
          {"bake_seconds", 0.93},
          {"path_tracer",
           {{"rays_below", 4}, {"rays_above", 8}, {"azimuths", 12}, {"samples", 32},
            {"normals", 64}}},
          {"texels", json::array({texel})},
          {"target", {{"what", "daylight decode"}, {"worst_rms", 0.0123}, {"status", status}}}};
}

TEST(ReportHtml, SkyIrradianceShowsTheThreeErrorsApart) {
  const std::string html = report_html(report_with(measured_sky_irradiance("met"), "full"));
  EXPECT_NE(html.find("<h2 id=\"sky_irradiance\">"), std::string::npos);
  EXPECT_NE(html.find("Table 32 x 16"), std::string::npos);
  EXPECT_NE(html.find("64 normals per texel"), std::string::npos);
  for (const char* cell : {"<td>1.23 %</td><td>4.56 %</td>", "<td>0.31 %</td><td>0.95 %</td>",
                           "<td>2.11 %</td><td>7.77 %</td>"})
    EXPECT_NE(html.find(cell), std::string::npos) << cell;
  EXPECT_NE(html.find("<span class=\"met\">met</span>"), std::string::npos);
}

TEST(ReportHtml, SkyIrradianceMissIsJudgedOnlyByAFullRun) {
  EXPECT_NE(report_html(report_with(measured_sky_irradiance("missed"), "full"))
                .find("<span class=\"notmet\">missed</span>"),
            std::string::npos);
  EXPECT_NE(report_html(report_with(measured_sky_irradiance("missed"), "quick"))
                .find("not judged by a quick run"),
            std::string::npos);
}

TEST(ReportHtml, SkyIrradianceShowsTwilightTexelsAgainstTheirOwnTarget) {
  json si = measured_sky_irradiance("met");
  si["twilight_path_tracer_samples"] = 256;
  si["twilight_texels"] = json::array({{{"altitude_m", 0.0},
                                        {"sun_zenith_deg", 101.0},
                                        {"decode", {{"rms", 0.3585}, {"max", 0.95}}},
                                        {"l2_limit", {{"rms", 0.0401}, {"max", 0.1422}}},
                                        {"interpolation", {{"rms", 0.02}, {"max", 0.05}}}}});
  si["twilight_target"] = {{"what", "twilight decode"}, {"worst_excess", 0.81}, {"status", "missed"}};
  const std::string html = report_html(report_with(si, "full"));
  EXPECT_NE(html.find("Twilight, 256 paths"), std::string::npos);
  EXPECT_NE(html.find("<td>35.9 %</td><td>95 %</td>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"notmet\">missed</span> (worst excess over it 81 %)"),
            std::string::npos);
  EXPECT_NE(html.find("<span class=\"met\">met</span>"), std::string::npos);  // daylight's
}

TEST(ReportHtml, SkyIrradianceNotSelectedSaysSo) {
  EXPECT_NE(report_html(report_with(nullptr, "full")).find("Not run (sky_irradiance was not"),
            std::string::npos);
}

}  // namespace
}  // namespace skybake
