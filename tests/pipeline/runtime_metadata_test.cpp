// What a runtime shader needs, end to end: a small scene is baked and the
// values are read back typed from each file kind with that format's own
// typed API (OpenEXR's findTypedAttribute, OpenVDB's metaValue<T>) and from
// manifest.json (docs/formats.md "Metadata").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <ImfDoubleAttribute.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>
#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>

#include "atmosphere/scattering_lut.hpp"
#include "support/run.hpp"
#include "support/test_atmospheres.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

const glm::dvec3 kSun(1.5, 1.25, 0.75);
constexpr double kMieG = 0.7;

// Earth with another sun and a Henyey-Greenstein Mie phase, so that every
// value checked below differs from a default.
fs::path baked() {
  static const fs::path out = [] {
    const fs::path dir = test::fresh_dir("runtime_metadata");
    json atm = json::parse(test::read_file(test::source_path("presets/atmospheres/earth.json")));
    atm.erase("$schema");
    atm["sun"]["illuminance"] = {kSun.x, kSun.y, kSun.z};
    atm["mie"]["phase"] = "henyey_greenstein";
    atm["mie"]["g"] = kMieG;
    std::ofstream(dir / "atm.json") << atm.dump(2);
    const json scene = {
        {"name", "rt"},
        {"planet", {{"radius_km", 6360}}},
        {"atmosphere", (dir / "atm.json").string()},
        {"outputs",
         {{{"product", "transmittance"}, {"size", {64, 16}}, {"formats", {"exr", "dds"}}},
          {{"product", "multiscattering"}, {"size", {16, 16}}, {"formats", {"exr"}}},
          {{"product", "skyview"}, {"size", {32, 16}}, {"formats", {"exr"}}},
          {{"product", "aerial_perspective"}, {"size", {8, 8, 8}}, {"formats", {"vdb"}}},
          {{"product", "scattering"},
           {"size", {8, 16, 8, 4}},
           {"orders", 3},
           {"formats", {"exr", "dds"}}},
          {{"product", "irradiance"}, {"size", {16, 4}}, {"formats", {"exr"}}},
          {{"product", "noise_detail"}, {"size", {32, 32, 32}}, {"formats", {"vdb", "exr"}}}}}};
    std::ofstream(dir / "rt.json") << scene.dump(2);
    const auto r = test::run_skybake({"bake", (dir / "rt.json").string(), "-o", dir.string(), "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir / "rt";
  }();
  return out;
}

Imf::Header exr_header(const std::string& file) {
  Imf::MultiPartInputFile in((baked() / file).c_str());
  return in.header(0);
}

template <class A>
auto exr_value(const Imf::Header& h, const std::string& key) {
  const A* a = h.findTypedAttribute<A>("skybake:" + key);
  EXPECT_NE(a, nullptr) << key << " is not a " << A::staticTypeName();
  return a ? a->value() : std::decay_t<decltype(a->value())>{};
}

json manifest_metadata(const std::string& product) {
  const json m = json::parse(test::read_file(baked() / "manifest.json"));
  for (const json& o : m["outputs"])
    if (o["product"] == product) return o["metadata"];
  ADD_FAILURE() << product << " not in the manifest";
  return json::object();
}

void expect_double3(const json& j, glm::dvec3 v) {
  ASSERT_TRUE(j.is_array() && j.size() == 3) << j;
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(j[c].is_number_float()) << j;
    EXPECT_EQ(j[c].get<double>(), v[c]);
  }
}

TEST(RuntimeMetadata, EveryExrTableRecordsTheSunAndItsSampler) {
  for (const std::string file :
       {"transmittance.exr", "multiscattering.exr", "skyview.exr", "scattering.exr",
        "irradiance.exr"}) {
    SCOPED_TRACE(file);
    const Imf::Header h = exr_header(file);
    EXPECT_EQ(exr_value<Imf::V3dAttribute>(h, "solar_irradiance"),
              Imath::V3d(kSun.x, kSun.y, kSun.z));
    EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "filter"), "linear");
    EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "wrap_u"),
              file == "skyview.exr" ? "repeat" : "clamp");
    EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "wrap_v"), "clamp");
    const bool volume = file == "scattering.exr";
    EXPECT_EQ(h.find("skybake:wrap_w") != h.end(), volume);
    if (volume) {
      EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "wrap_w"), "clamp");
    }
    // Transmittance and the isotropic multiple-scattering transfer do not
    // depend on the Mie phase; the others record it.
    const bool mie = file != "transmittance.exr" && file != "multiscattering.exr";
    EXPECT_EQ(h.find("skybake:mie_phase") != h.end(), mie);
    if (mie) {
      EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "mie_phase"), "henyey_greenstein");
      EXPECT_EQ(exr_value<Imf::DoubleAttribute>(h, "mie_g"), kMieG);
    }
  }
}

TEST(RuntimeMetadata, ScatteringRecordsTheNuOfTheRayleighDivisor) {
  const Imf::Header h = exr_header("scattering.exr");
  EXPECT_EQ(exr_value<Imf::V2dAttribute>(h, "rayleigh_divisor_nu_range"), Imath::V2d(-1.0, 1.0));
  EXPECT_EQ(exr_value<Imf::IntAttribute>(h, "rayleigh_divisor_nu_clamped"), 0);
  EXPECT_EQ(exr_value<Imf::IntAttribute>(h, "nu_size"), 4);
  EXPECT_EQ(exr_value<Imf::IntAttribute>(h, "mie_in_alpha"), 1);
  // What the record says is what the divisor reads: the unclamped nu of
  // each slice, evenly spaced from -1 to 1 (scattering_orders.cpp texel_phases).
  const ScatteringShape shape{8, 16, 8, 4, kBrunetonMuSMin};
  const ScatteringTexelGrid grid = scattering_texel_grid(fixtures::earth_atmosphere(), shape);
  ASSERT_EQ(grid.nu.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(grid.nu[k], -1.0 + 2.0 * k / 3.0, 1e-15) << k;
  const json m = manifest_metadata("scattering");
  EXPECT_EQ(m["rayleigh_divisor_nu_range"], json::parse("[-1.0, 1.0]"));
  EXPECT_TRUE(m["rayleigh_divisor_nu_range"][0].is_number_float());
  EXPECT_EQ(m["rayleigh_divisor_nu_clamped"], 0);
  expect_double3(m["solar_irradiance"], kSun);
  EXPECT_EQ(m["wrap_w"], "clamp");
}

TEST(RuntimeMetadata, IrradianceRecordsTheSkyOrdersItHolds) {
  const Imf::Header h = exr_header("irradiance.exr");
  // 3 orders, indirect only: the sky's orders 1..3.
  EXPECT_EQ(exr_value<Imf::V2iAttribute>(h, "irradiance_orders"), Imath::V2i(1, 3));
  EXPECT_EQ(exr_value<Imf::IntAttribute>(h, "orders"), 3);
  EXPECT_EQ(exr_value<Imf::IntAttribute>(h, "includes_direct"), 0);
  EXPECT_NE(exr_value<Imf::StringAttribute>(h, "irradiance_orders_note").find("Init(4)"),
            std::string::npos);
  const json m = manifest_metadata("irradiance");
  EXPECT_EQ(m["irradiance_orders"], json::parse("[1, 3]"));
  EXPECT_TRUE(m["irradiance_orders"][0].is_number_integer());
}

TEST(RuntimeMetadata, DdsConsumersReadTheSameValuesFromTheManifest) {
  const json t = manifest_metadata("transmittance");
  expect_double3(t["solar_irradiance"], kSun);
  EXPECT_EQ(t["filter"], "linear");
  EXPECT_EQ(t["wrap_u"], "clamp");
  EXPECT_FALSE(t.contains("mie_phase"));
  const json s = manifest_metadata("scattering");
  EXPECT_EQ(s["mie_phase"], "henyey_greenstein");
  EXPECT_TRUE(s["mie_g"].is_number_float());
  EXPECT_EQ(s["mie_g"].get<double>(), kMieG);
  EXPECT_EQ(s["orders"], 3);
}

TEST(RuntimeMetadata, VdbGridsCarryTypedValues) {
  openvdb::initialize();
  {
    openvdb::io::File file((baked() / "aerial_perspective.vdb").string());
    file.open();
    const openvdb::GridPtrVecPtr grids = file.getGrids();
    ASSERT_FALSE(grids->empty());
    for (const openvdb::GridBase::Ptr& g : *grids) {
      EXPECT_EQ(g->metaValue<openvdb::Vec3d>("skybake:solar_irradiance"),
                openvdb::Vec3d(kSun.x, kSun.y, kSun.z));
      EXPECT_EQ(g->metaValue<std::string>("skybake:mie_phase"), "henyey_greenstein");
      EXPECT_EQ(g->metaValue<double>("skybake:mie_g"), kMieG);
      for (const char* axis : {"skybake:wrap_u", "skybake:wrap_v", "skybake:wrap_w"})
        EXPECT_EQ(g->metaValue<std::string>(axis), "clamp") << axis;
      EXPECT_EQ(g->metaValue<std::string>("skybake:filter"), "linear");
    }
  }
  openvdb::io::File file((baked() / "noise_detail.vdb").string());
  file.open();
  const openvdb::GridPtrVecPtr grids = file.getGrids();
  ASSERT_FALSE(grids->empty());
  for (const openvdb::GridBase::Ptr& g : *grids) {
    for (const char* axis : {"skybake:wrap_u", "skybake:wrap_v", "skybake:wrap_w"})
      EXPECT_EQ(g->metaValue<std::string>(axis), "repeat") << axis;
    const int period = manifest_metadata("noise_detail")["period.R"].get<int>();
    EXPECT_EQ(g->metaValue<int32_t>("skybake:period.R"), period);
    EXPECT_EQ((*g)["skybake:solar_irradiance"], nullptr) << "a noise is no atmosphere table";
  }
  const json n = manifest_metadata("noise_detail");
  EXPECT_EQ(n["wrap_w"], "repeat");
  const Imf::Header h = exr_header("noise_detail.exr");
  EXPECT_EQ(exr_value<Imf::StringAttribute>(h, "wrap_w"), "repeat");
}

}  // namespace
}  // namespace skybake
