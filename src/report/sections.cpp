#include "report/sections.hpp"

#include <algorithm>

#include "report/aerial_perspective.hpp"
#include "report/bruneton.hpp"
#include "report/colour.hpp"
#include "report/gathering_sum.hpp"
#include "report/hillaire_runtime.hpp"
#include "report/irradiance.hpp"
#include "report/multiscattering.hpp"
#include "report/precision.hpp"
#include "report/preview.hpp"
#include "report/scattering.hpp"
#include "report/scattering3d.hpp"
#include "report/single_mie.hpp"
#include "report/sky_irradiance.hpp"
#include "report/sky_radiance.hpp"
#include "report/skyview.hpp"
#include "report/transmittance.hpp"

namespace skybake {

namespace {

const char* const kProduct = "/products/-";

bool covers(const ReportSection& section, const std::vector<std::string>& products) {
  return std::any_of(section.products.begin(), section.products.end(), [&](const std::string& p) {
    return std::find(products.begin(), products.end(), p) != products.end();
  });
}

}  // namespace

// The ladders in dependency order, then the sections that read their tables.
const std::vector<ReportSection>& report_sections() {
  static const std::vector<ReportSection> table = {
      make_section("transmittance", {"transmittance"}, kProduct, TransmittanceSetup::quick(),
                   TransmittanceSetup::full(), transmittance_report),
      make_section("multiscattering", {"multiscattering"}, kProduct, MultiscatteringSetup::quick(),
                   MultiscatteringSetup::full(), multiscattering_report),
      make_section("skyview", {"skyview"}, kProduct, SkyviewSetup::quick(), SkyviewSetup::full(),
                   skyview_report),
      make_section("aerial_perspective", {"aerial_perspective"}, kProduct,
                   AerialPerspectiveSetup::quick(), AerialPerspectiveSetup::full(),
                   aerial_perspective_report),
      make_section("scattering", {"scattering"}, kProduct, ScatteringSetup::quick(),
                   ScatteringSetup::full(), scattering_report),
      make_section("single_mie", {"single_mie"}, kProduct, SingleMieSetup::quick(),
                   SingleMieSetup::full(), single_mie_report),
      make_section("irradiance", {"irradiance"}, kProduct, IrradianceSetup::quick(),
                   IrradianceSetup::full(), irradiance_report),
      make_section("scattering3d", {"scattering3d"}, kProduct, Scattering3dSetup::quick(),
                   Scattering3dSetup::full(), scattering3d_report),
      make_section("gathering_sum", {"gathering_sum"}, kProduct, GatheringSumSetup::quick(),
                   GatheringSumSetup::full(), gathering_sum_report),
      // The sky as an engine renders it from either family of tables.
      make_section("sky_radiance", {"skyview", "scattering"}, "/sky_radiance",
                   SkyRadianceSetup::quick(), SkyRadianceSetup::full(), sky_radiance_report),
      // Hillaire's demo run-time reading skybake's tables in his layout.
      make_section("hillaire_runtime", {"skyview"}, "/hillaire_runtime",
                   HillaireRuntimeSetup::quick(), HillaireRuntimeSetup::full(),
                   hillaire_runtime_report),
      // Ambient light: the SH table against the path tracer's E(n).
      make_section("sky_irradiance", {"sky_irradiance"}, "/sky_irradiance",
                   SkyIrradianceReportSetup::quick(), SkyIrradianceReportSetup::full(),
                   sky_irradiance_report),
      make_section("horizon_transmittance", {"transmittance"}, "/precision/horizon_transmittance",
                   horizon_transmittance_report),
      make_section("bruneton_comparison", {}, "/bruneton_comparison", BrunetonSetup::quick(),
                   BrunetonSetup::full(), bruneton_comparison_report),
      make_section("sky_preview", {}, "/files/preview", PreviewSetup::quick(), PreviewSetup::full(),
                   sky_preview_report),
      // Three wavelengths and N against the spectral path tracer (spectral scenes).
      make_section("colour", {"skyview"}, "/colour", ColourSetup::quick(), ColourSetup::full(),
                   colour_report)};
  return table;
}

nlohmann::json level_settings(bool quick) {
  nlohmann::json settings = quick ? ReportLevel::quick() : ReportLevel::full();
  for (const ReportSection& section : report_sections())
    settings.update(quick ? section.quick : section.full);
  return settings;
}

bool is_measured(const std::string& product) {
  return std::any_of(
      report_sections().begin(), report_sections().end(),
      [&](const ReportSection& s) { return s.place == kProduct && covers(s, {product}); });
}

bool section_runs(const ReportSection& section, const std::vector<std::string>& products) {
  if (!section.products.empty()) return covers(section, products);
  return std::any_of(
      report_sections().begin(), report_sections().end(),
      [&](const ReportSection& s) { return !s.products.empty() && covers(s, products); });
}

}  // namespace skybake
