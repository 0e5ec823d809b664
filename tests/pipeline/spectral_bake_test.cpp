// Spectral bakes (pipeline/spectral_bake.hpp) against closed forms: one
// wavelength through a pure Rayleigh slab, the sun at zero air mass, the
// group sum of a grey sky, and the shipped spectral presets' RGB values
// against their own spectra. Small tables, real files read back.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <nlohmann/json.hpp>

#include "atmosphere/sky_preview.hpp"
#include "atmosphere/spectral_medium.hpp"
#include "core/colour.hpp"
#include "core/spectral_data.hpp"
#include "io/texture_file.hpp"
#include "pipeline/bake.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/spectral_bake.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

constexpr double kSlabKm = 10.0;
constexpr double kSigma550 = 1e-5;

// A planet with a uniform Rayleigh slab kSlabKm thick.
json slab_scene(const json& spectral, const json& spectrum, const json& outputs) {
  json atm = {{"top_radius_km", 6360 + kSlabKm},
              {"rayleigh",
               {{"scattering_per_m", {kSigma550, kSigma550, kSigma550}},
                {"density", {{"uniform", {{"top_km", kSlabKm}}}}}}},
              {"spectrum", spectrum}};
  json scene = {{"name", "slab"},
                {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.0, 0.0, 0.0}}}},
                {"atmosphere", atm},
                {"outputs", outputs}};
  if (!spectral.is_null()) scene["spectral"] = spectral;
  return scene;
}

// Bakes `scene` into a fresh folder; the file `<name>.exr` read back.
fs::path bake_json(const json& scene) {
  const fs::path dir = test::test_dir("spectral");
  std::ofstream(dir / "scene.json") << scene.dump(2);
  BakeOptions o;
  o.out_dir = dir / "out";
  bake_scene(load_scene(dir / "scene.json"), o);
  return o.out_dir / scene["name"].get<std::string>();
}

Texture read_exr(const fs::path& dir, const std::string& name) {
  return read_texture_file((dir / (name + ".exr")).string()).texture;
}

// The transmittance table of a Rayleigh slab under a sun that shines only
// between sun_from_nm and sun_to_nm (a trapezoid 1 nm wide at each end).
Texture slab_transmittance_in_sunlight(const json& spectral, double sun_from_nm, double sun_to_nm) {
  const json sun = {{"table",
                     {{"wavelengths_nm", {sun_from_nm - 1, sun_from_nm, sun_to_nm, sun_to_nm + 1}},
                      {"values", {0, 1, 1, 0}}}}};
  const json spectrum = {
      {"sun", sun},
      {"rayleigh", {{"power_law", {{"scattering_per_m", kSigma550}, {"reference_nm", 550}}}}}};
  const json outputs = {{{"product", "transmittance"}, {"size", {32, 8}}, {"formats", {"exr"}}}};
  return read_exr(bake_json(slab_scene(spectral, spectrum, outputs)), "transmittance");
}

// Texel (0, 0), the ground looking at the zenith: exp(-sigma(nm) H) in every channel.
void expect_slab_transmittance_at(const Texture& t, double nm) {
  const double expected = std::exp(-kSigma550 * std::pow(nm / 550.0, -4.0) * kSlabKm * 1e3);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.at(0, 0, 0, 0, c) / expected, 1.0, 2e-5) << c;
}

TEST(SpectralBake, OneWavelengthThroughARayleighSlab) {
  // The sun shines only inside the bin of 505 nm (N = 15: bins of 20 nm
  // from 395 nm, the sixth centred on 395 + 5.5 * 20 = 505 nm): every channel
  // of the sun-weighted transmittance is T(505 nm).
  expect_slab_transmittance_at(slab_transmittance_in_sunlight({{"wavelengths", 15}}, 497, 513),
                               395.0 + 5.5 * 20.0);
}

TEST(SpectralBake, UniformSamplingIsBrunetonsBins) {
  // "uniform": bins of 470/15 nm from 360 nm, the fifth centred on 501 nm.
  const Texture t =
      slab_transmittance_in_sunlight({{"wavelengths", 15}, {"sampling", "uniform"}}, 491, 511);
  EXPECT_EQ(std::get<std::string>(t.metadata.at("spectral_sampling")), "uniform");
  expect_slab_transmittance_at(t, 360.0 + 4.5 * 470.0 / 15.0);
}

TEST(SpectralBake, SunAtZeroAirMassIsTheSolarSpectrumsXyz) {
  // At the top, looking up, the transmittance is 1 at every wavelength: the
  // sun's colour recorded with the table is the ASTM G-173 spectrum's XYZ in
  // the table's colour space and units (radiometric: CIE-weighted W/m^2).
  const json outputs = {{{"product", "transmittance"}, {"size", {32, 8}}, {"formats", {"exr"}}}};
  for (const char* space : {"rec709", "acescg"}) {
    const json spectral = {{"wavelengths", 15}, {"units", "radiometric"}, {"colour_space", space}};
    const fs::path dir = bake_json(slab_scene(spectral, json::object(), outputs));
    const Texture t = read_exr(dir, "transmittance");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.at(0, t.height - 1, 0, 0, c), 1.0, 1e-6);
    const glm::dvec3 sun = std::get<glm::dvec3>(t.metadata.at("solar_irradiance"));
    const ColourSpace cs =
        std::string(space) == "acescg" ? ColourSpace::acescg : ColourSpace::rec709;
    const glm::dvec3 xyz = xyz_from_rgb(chromaticities_of(cs)) * sun;
    const glm::dvec3 fine = spectrum_xyz(astm_g173_solar_irradiance, 0.25);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(xyz[i] / fine[i], 1.0, 1e-4) << space << i;
    // The file carries its colour space as OpenEXR's standard attribute.
    Imf::InputFile file((dir / "transmittance.exr").c_str());
    ASSERT_TRUE(Imf::hasChromaticities(file.header()));
    const Chromaticities want = chromaticities_of(cs);
    EXPECT_NEAR(Imf::chromaticities(file.header()).red.x, want.red.x, 1e-6);
    EXPECT_NEAR(Imf::chromaticities(file.header()).white.y, want.white.y, 1e-6);
  }
}

TEST(SpectralBake, LuminanceScaleOfEachUnitSystem) {
  // cd/m^2 per table unit: 1 photometric, 683 lm/W radiometric, and for
  // relative tables (the sun's luminance 1) the sun's illuminance in lux,
  // about 1.28e5 at the top of Earth's atmosphere.
  const json outputs = {{{"product", "transmittance"}, {"size", {32, 8}}, {"formats", {"exr"}}}};
  std::map<std::string, double> scale;
  for (const char* units : {"relative", "radiometric", "photometric"}) {
    const json spectral = {{"wavelengths", 15}, {"units", units}};
    const Texture t =
        read_exr(bake_json(slab_scene(spectral, json::object(), outputs)), "transmittance");
    scale[units] = std::get<double>(t.metadata.at("luminance_scale_cd_m2"));
    const glm::dvec3 sun = std::get<glm::dvec3>(t.metadata.at("solar_irradiance"));
    const double y = (xyz_from_rgb(chromaticities_of(ColourSpace::rec709)) * sun).y;
    EXPECT_GT(y * scale[units], 1.20e5) << units;  // the sun in lux
    EXPECT_LT(y * scale[units], 1.35e5) << units;
  }
  EXPECT_NEAR(scale["photometric"], 1.0, 1e-12);
  EXPECT_NEAR(scale["radiometric"], kMaxLuminousEfficacy, 1e-9);
  EXPECT_NEAR(scale["relative"], 683.0 * spectrum_xyz(astm_g173_solar_irradiance, 0.25).y, 1.0);
}

// A sun of spectral irradiance 1 at every wavelength.
json flat_sun() {
  return {{"sun", {{"constant", {{"irradiance_w_m2_nm", 1.0}}}}}};
}

// Hillaire's set at small sizes, a sky-view layer 500 m up under a sun 20
// degrees high.
json small_hillaire_set() {
  return {
      {{"product", "transmittance"}, {"size", {32, 8}}, {"formats", {"exr"}}},
      {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}}, {"directions", 16}},
      {{"product", "skyview"},
       {"size", {16, 8}},
       {"formats", {"exr"}},
       {"views", {{{"altitude_km", 0.5}, {"sun_zenith_deg", 70}}}}}};
}

TEST(SpectralBake, GreySkyIsTheRgbSkyTimesTheSunsColour) {
  // Coefficients flat in wavelength and a flat sun: every group bakes the
  // same grey sky-view as the RGB bake, and the groups add up to it times
  // the sun's colour (relative units: the sun's luminance is 1).
  const json spectrum = flat_sun();
  const json outputs = small_hillaire_set();
  const Texture rgb = read_exr(bake_json(slab_scene(nullptr, spectrum, outputs)), "skyview");
  const Texture sp =
      read_exr(bake_json(slab_scene({{"wavelengths", 6}}, spectrum, outputs)), "skyview");
  const glm::dvec3 sun = std::get<glm::dvec3>(sp.metadata.at("solar_irradiance"));
  const glm::dvec3 e = rgb_from_xyz(chromaticities_of(ColourSpace::rec709)) * glm::dvec3(1.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sun[c], e[c], 1e-3 * e[c]);  // illuminant E, Y = 1
  ASSERT_EQ(rgb.data.size(), sp.data.size());
  for (size_t t = 0; t < rgb.texel_count(); ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(sp.data[t * 3 + c], rgb.data[t * 3] * sun[c], 2e-5 * rgb.data[t * 3] + 1e-9);
}

// The error records of a bake of `scene`, by product.
std::map<std::string, json> error_records(const json& scene) {
  const fs::path dir = test::test_dir("spectral_errors");
  std::ofstream(dir / "scene.json") << scene.dump(2);
  BakeOptions o;
  o.out_dir = dir / "out";
  std::map<std::string, json> out;
  for (const OutputRecord& r : bake_scene(load_scene(dir / "scene.json"), o).outputs)
    out[r.product] = r.entry.error;
  return out;
}

TEST(SpectralBake, GreySkyRecordsTheRgbBakesErrorPerGroup) {
  // Every group of a grey sky bakes the RGB bake's tables against the same
  // references: each spectral record is the RGB one, with its groups named.
  const json spectrum = flat_sun();
  const json outputs = small_hillaire_set();
  const auto rgb = error_records(slab_scene(nullptr, spectrum, outputs));
  const auto sp = error_records(slab_scene({{"wavelengths", 6}}, spectrum, outputs));
  for (const char* product : {"transmittance", "multiscattering", "skyview"}) {
    SCOPED_TRACE(product);
    ASSERT_TRUE(rgb.at(product).is_object());
    ASSERT_TRUE(sp.at(product).is_object());
    EXPECT_NEAR(sp.at(product)["max_rel"].get<double>(), rgb.at(product)["max_rel"].get<double>(),
                1e-6 * rgb.at(product)["max_rel"].get<double>() + 1e-12);
    EXPECT_EQ(sp.at(product)["queries"], rgb.at(product)["queries"]);
    EXPECT_EQ(sp.at(product)["wavelength_groups"], 2);
    ASSERT_EQ(sp.at(product)["worst_group_nm"].size(), 3u);
    for (double nm : sp.at(product)["worst_group_nm"]) EXPECT_TRUE(nm > 360.0 && nm < 830.0);
    EXPECT_FALSE(rgb.at(product).contains("wavelength_groups"));
  }
}

TEST(SpectralBake, GreySkyPreviewIsTheRgbRadianceInTheSunsColourToneMapped) {
  // The preview's radiance adds up over groups; the picture is its sum
  // exposed and tone mapped once.
  const json spectrum = flat_sun();
  const json outputs = {
      {{"product", "transmittance"}, {"size", {64, 16}}, {"formats", {"exr"}}},
      {{"product", "multiscattering"}, {"size", {8, 8}}, {"formats", {"exr"}}, {"directions", 16}},
      {{"product", "sky_preview"}, {"size", {32, 18}}, {"formats", {"exr"}}}};
  const fs::path rgb_dir = bake_json(slab_scene(nullptr, spectrum, outputs));
  const Texture rgb_t = read_exr(rgb_dir, "transmittance");
  const Texture rgb_ms = read_exr(rgb_dir, "multiscattering");
  const fs::path sp_dir = bake_json(slab_scene({{"wavelengths", 6}}, spectrum, outputs));
  const Texture sp = read_exr(sp_dir, "sky_preview");
  const glm::dvec3 sun =
      std::get<glm::dvec3>(read_exr(sp_dir, "transmittance").metadata.at("solar_irradiance"));

  // The slab under a white sun of 1, as each group sees it.
  Atmosphere white = load_scene(sp_dir.parent_path().parent_path() / "scene.json").atmosphere;
  white.sun_illuminance = glm::dvec3(1.0);
  SkyPreviewSpec spec;
  spec.width = 32, spec.height = 18;
  Texture radiance = render_sky_preview_radiance(white, rgb_t, rgb_ms, spec, {});
  for (size_t t = 0; t < radiance.texel_count(); ++t)
    for (int c = 0; c < 3; ++c) radiance.data[t * 3 + c] *= float(sun[c]);
  const Texture expected = tone_map_sky_preview(radiance, white, spec);
  ASSERT_EQ(sp.data.size(), expected.data.size());
  double worst = 0.0;
  for (size_t i = 0; i < sp.data.size(); ++i)
    worst = std::max(worst, std::abs(double(sp.data[i]) - expected.data[i]));
  EXPECT_LT(worst, 2e-4);
  for (int p = 0; p < 5; ++p)
    EXPECT_NEAR(std::get<double>(sp.metadata.at(fmt::format("exposure_{}", p))),
                std::get<double>(expected.metadata.at(fmt::format("exposure_{}", p))),
                1e-4 * std::get<double>(expected.metadata.at(fmt::format("exposure_{}", p))));
}

TEST(SpectralBake, GreyFourAndThreeDTablesAreTheRgbTimesTheSunsColour) {
  // As above for the 4D and 3D tables, whose alpha is the single Mie's red:
  // with a flat medium every channel, alpha included, is the RGB bake's
  // times the sun's colour (alpha: its red).
  json spectrum = flat_sun();
  const json outputs = {
      {{"product", "transmittance"}, {"size", {32, 8}}, {"formats", {"exr"}}},
      {{"product", "scattering"}, {"size", {4, 16, 8, 4}}, {"orders", 2}, {"formats", {"exr"}}},
      {{"product", "scattering3d"}, {"size", {4, 16, 8}}, {"orders", 2}, {"formats", {"exr"}}}};
  json rgb_scene = slab_scene(nullptr, spectrum, outputs);
  rgb_scene["atmosphere"]["mie"] = {{"scattering_per_m", {2e-6, 2e-6, 2e-6}},
                                    {"density", {{"exponential", {{"scale_height_km", 1.2}}}}}};
  json sp_scene = rgb_scene;
  sp_scene["spectral"] = {{"wavelengths", 6}};
  const fs::path rgb_dir = bake_json(rgb_scene);
  std::map<std::string, Texture> rgb;
  for (const char* name : {"scattering", "scattering3d"}) rgb[name] = read_exr(rgb_dir, name);
  const fs::path sp_dir = bake_json(sp_scene);
  for (const char* name : {"scattering", "scattering3d"}) {
    const Texture sp = read_exr(sp_dir, name);
    const glm::dvec3 sun = std::get<glm::dvec3>(sp.metadata.at("solar_irradiance"));
    ASSERT_EQ(sp.channels.size(), 4u) << name;
    ASSERT_EQ(rgb[name].data.size(), sp.data.size()) << name;
    for (size_t t = 0; t < sp.texel_count(); ++t) {
      const float* a = &rgb[name].data[t * 4];
      const float* b = &sp.data[t * 4];
      for (int c = 0; c < 4; ++c) {
        // Grey: the RGB bake's channels are equal, the sky's colour is the sun's.
        const double want = c == 3 ? a[3] * sun[0] : a[0] * sun[c];
        ASSERT_NEAR(b[c], want, 2e-5 * std::abs(want) + 1e-12)
            << name << " texel " << t << " " << c;
      }
    }
  }
}

TEST(SpectralBake, RunningSumsSpilledBetweenGroupsAreTheSameBytes) {
  // The pipeline keeps each output's running sum on disk between groups
  // (io/texel_spill.hpp); in memory the sums are the same, bit for bit.
  const json outputs = {{{"product", "transmittance"}, {"size", {32, 8}}},
                        {{"product", "multiscattering"}, {"size", {8, 8}}},
                        {{"product", "skyview"}, {"size", {24, 16}}}};
  const fs::path dir = test::test_dir("spectral_spill");
  std::ofstream(dir / "scene.json") << slab_scene({{"wavelengths", 9}}, json::object(), outputs);
  const Scene scene = load_scene(dir / "scene.json");
  const ProductGraph g = build_product_graph(scene, {});
  const std::vector<char> all(g.nodes.size(), 1), none(g.nodes.size(), 0);
  const SpectralTables held = bake_spectral_graph(scene, g, all, none, {});
  const SpectralTables spilled = bake_spectral_graph(scene, g, all, none, {}, dir);
  ASSERT_EQ(held.textures.size(), 3u);
  ASSERT_EQ(spilled.textures.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(held.textures[i] && spilled.textures[i]);
    EXPECT_FALSE(held.textures[i]->data.empty());
    EXPECT_EQ(held.textures[i]->data, spilled.textures[i]->data) << g.nodes[i].info->name;
  }
}

TEST(SpectralBake, ShippedRgbCoefficientsAreTheirSpectraAtRgbWavelengths) {
  for (const char* preset : {"presets/earth_spectral.json", "presets/mars_spectral.json"}) {
    const Scene scene = load_scene(test::source_path(preset));
    ASSERT_TRUE(scene.spectral) << preset;
    const Atmosphere at = atmosphere_at_wavelengths(scene.atmosphere, scene.spectral->medium,
                                                    glm::dvec3(kRedNm, kGreenNm, kBlueNm));
    for (size_t i = 0; i < at.components.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const MediumComponent& want = at.components[i];
        const MediumComponent& got = scene.atmosphere.components[i];
        EXPECT_NEAR(got.scattering_per_m[c], want.scattering_per_m[c],
                    1e-4 * want.scattering_per_m[c])
            << preset << " " << got.name << c;
        EXPECT_NEAR(got.absorption_per_m[c], want.absorption_per_m[c],
                    1e-4 * want.absorption_per_m[c])
            << preset << " " << got.name << c;
      }
  }
}

TEST(SpectralPreset, MolecularRayleighIsAirs) {
  // Sea-level air scatters about 1.15e-5 /m at 550 nm (Bucholtz 1995), and
  // its wavelength exponent is a little above 4 (about 4.08 over the
  // visible, from the refractive index's dispersion).
  const fs::path dir = test::test_dir("spectral");
  const json spectrum = {{"rayleigh", {{"molecular", json::object()}}}};
  std::ofstream(dir / "air.json")
      << slab_scene({{"wavelengths", 15}}, spectrum, {{{"product", "transmittance"}}}).dump();
  const Scene scene = load_scene(dir / "air.json");
  const SpectrumFn& s = scene.spectral->medium.components.at("rayleigh").scattering_per_m;
  EXPECT_NEAR(s(550.0), 1.15e-5, 0.03e-5);
  const double exponent = std::log(s(440.0) / s(680.0)) / std::log(680.0 / 440.0);
  EXPECT_GT(exponent, 4.0);
  EXPECT_LT(exponent, 4.2);
}

TEST(SpectralPreset, ProblemsNameFilePointerAndRule) {
  const fs::path dir = test::test_dir("spectral");
  const json spectrum = {
      {"rayleigh", {{"table", {{"wavelengths_nm", {500, 400}}, {"values", {1e-5, 2e-5}}}}}},
      {"ozone", {{"column", {{"dobson", 300}}}}},
      {"ground_albedo",
       {{"table",
         {{"wavelengths_nm", {400, 700}}, {"values", {0.2, 1.5}}, {"absorption", {0, 0}}}}}}};
  json scene = slab_scene({{"units", "photometric"}}, spectrum,
                          {{{"product", "transmittance"}, {"precision", "half"}}});
  std::ofstream(dir / "bad.json") << scene.dump(2);
  try {
    load_scene(dir / "bad.json");
    FAIL() << "loaded";
  } catch (const PresetError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/atmosphere/spectrum/rayleigh/table/wavelengths_nm/1"), std::string::npos)
        << what;
    EXPECT_NE(what.find("/atmosphere/spectrum/ozone"), std::string::npos) << what;
    EXPECT_NE(what.find("needs the atmosphere's 'ozone' component"), std::string::npos) << what;
    EXPECT_NE(what.find("/outputs/0/precision"), std::string::npos) << what;
    EXPECT_NE(what.find("/atmosphere/spectrum/ground_albedo/table/absorption"), std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace skybake
