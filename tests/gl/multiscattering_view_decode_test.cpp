// runtime/glsl/multiscattering_view.glsl and its HLSL twin on llvmpipe
// against the C++ read (lookup_multiscattering with nu and mu_v,
// atmosphere/multiscattering_lut.hpp) of the same baked volume, read back
// from its DDS file: the converged model's source by view
// (docs/reference.md "Psi_ms by view"), with unequal slice counts so that a
// mix-up of the two terms' slices shows.
#include <gtest/gtest.h>

#include "atmosphere/multiscattering_lut.hpp"
#include "gl/decode_case.hpp"
#include "support/run.hpp"
#include "verify/query_points.hpp"

namespace skybake::gltest {
namespace {

const BakedScene& view_source_scene() {
  static const BakedScene scene = bake_scene("gl_view_source", R"({
  "$schema": "../schemas/scene.schema.json",
  "name": "gl_view_source",
  "planet": { "radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3] },
  "atmosphere": ")" + test::source_path("presets/atmospheres/earth.json").string() + R"(",
  "outputs": [
    { "product": "transmittance", "size": [64, 16], "formats": ["dds"] },
    { "product": "multiscattering", "size": [16, 16], "formats": ["dds"], "model": "converged",
      "scattering_shape": [8, 32, 8, 4], "tolerance": 0.01, "angular": "nu_zenith",
      "nu_slices": 6, "zenith_slices": 5 }
  ]
})");
  return scene;
}

TEST(MultiscatteringViewDecode, LookupMultiscatteringView) {
  const BakedScene& s = view_source_scene();
  const Atmosphere& atm = s.atmosphere;
  const Texture lut = s.texture("multiscattering");
  ASSERT_EQ(lut.depth, 1 + 6 + 5);
  MultiscatteringMapping mapping = s.multiscattering_mapping("multiscattering");
  mapping.nu_slices = int(s.meta_number("multiscattering", "nu_slices"));
  mapping.zenith_slices = int(s.meta_number("multiscattering", "zenith_slices"));
  ASSERT_EQ(mapping.nu_slices, 6);
  ASSERT_EQ(mapping.zenith_slices, 5);
  const GlTexture tex =
      upload_dds(s.dds_path("multiscattering"), s.sampler("multiscattering", kClamp));
  const Comparison c = run_case(
      {"lookup_multiscattering_view (6 nu x 5 zenith slices)",
       {"multiscattering.glsl", "multiscattering_view.glsl"},
       "layout(binding = 0) uniform sampler3D lut;\nuniform MultiscatteringMapping mapping;",
       "vec4(lookup_multiscattering_view(lut, mapping, atm, 6, 5, q0.x, q0.y, q0.z, q0.w), 0.0)",
       {&tex}, 3,
       "Texture3D<float4> lut : register(t0);\nSamplerState lut_sampler : register(s0);\n" +
           hlsl_load_mapping(),
       "float4(lookup_multiscattering_view(lut, lut_sampler, load_mapping(), atm, 6, 5, q0.x, "
       "q0.y, q0.z, q0.w), 0.0)",
       {mapping_extra(mapping)}},
      s.parameters("multiscattering"),
      [&](size_t i, glm::vec4& q0, glm::vec4&) {
        const RadiusCosine p = multiscattering_query(atm, i);
        const double nu = 2.0 * unit(i, 93) - 1.0, mu_v = 2.0 * unit(i, 94) - 1.0;
        q0 = glm::vec4(float(p.r), float(p.mu), float(nu), float(mu_v));
        return rgb(lookup_multiscattering(lut, mapping, atm, q0.x, q0.y, q0.z, q0.w));
      },
      [&](const ComputeProgram& p) { set_mapping_uniform(p, "mapping", mapping); });
  expect_within(c, kCoordinateBar);
}

}  // namespace
}  // namespace skybake::gltest
