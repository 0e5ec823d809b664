// For each measured (row, column) texel of the table baked at the preset's
// settings: the path tracer's E at the texel's (altitude, sun zenith) for
// Fibonacci normals (reference/sky_irradiance_reference.hpp), and
//   decode         the texel decoded (sh_l2_irradiance) against it;
//   l2_limit       the reference's own L2 projection against it;
//   interpolation  the bilinear read in the middle of the cell after the
//                  texel against the coefficients computed there from the
//                  same source (no path tracer).
// Errors relative to the mean reference E over the normals, per channel.
// The daylight target (sun zenith <= 90 degrees): 3% RMS, and 8% max or
// L2's own max + 1% where that is above 8%. The twilight target (columns
// past 90 degrees, read from the twilight source,
// docs/decisions/sky-irradiance-source.md): L2's own RMS and max + 1%.
#include "report/sky_irradiance.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/sky_irradiance.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "reference/sky_irradiance_reference.hpp"
#include "report/stats.hpp"

namespace skybake {

namespace {

nlohmann::json errors_json(const IrradianceErrors& e) { return {{"rms", e.rms}, {"max", e.max}}; }

ShRadiance texel_sh(const Texture& table, int x, int y) {
  std::array<glm::dvec3, kShSymmetricCount> stored;
  for (int j = 0; j < kShSymmetricCount; ++j)
    for (int c = 0; c < 3; ++c) stored[j][c] = table.at(x, y, 0, j, c);
  return decode_sky_radiance_sh(stored);
}

// The bilinear read in the middle of cell (x, y) against the source there.
IrradianceErrors interpolation_errors(const Atmosphere& atm, const SkyRadianceSource& source,
                                      const SkyIrradianceSpec& spec, const Texture& table, int x,
                                      int y, int normals) {
  const int x1 = std::min(x + 1, spec.width - 1), y1 = std::min(y + 1, spec.height - 1);
  const double h = 0.5 * (sky_irradiance_altitude(atm, spec, y) +
                          sky_irradiance_altitude(atm, spec, y1));
  const double zenith = 0.5 * (sky_irradiance_sun_zenith(spec, x) +
                               sky_irradiance_sun_zenith(spec, x1));
  const ShRadiance at = compute_sky_radiance_sh(atm, source, spec, h, zenith);
  IrradianceReference direct;
  direct.normals = fibonacci_normals(normals);
  for (const glm::dvec3& n : direct.normals) direct.irradiance.push_back(sh_l2_irradiance(at, n));
  const ShRadiance read = lookup_sky_radiance_sh(table, h, zenith);
  return irradiance_errors(direct, [&](glm::dvec3 n) { return sh_l2_irradiance(read, n); });
}

// One texel against the path tracer: the decode, L2's limit and the read
// between texels, and their JSON row.
struct MeasuredTexel {
  IrradianceErrors decode, limit;
  nlohmann::json json;
};

struct TexelMeasure {
  const ReportInputs& in;
  const Atmosphere& atm;
  const SkyRadianceSource& source;
  const SkyIrradianceSpec& spec;
  const Texture& table;
  int normals;

  MeasuredTexel operator()(int x, int y, const IrradianceReferenceRule& rule) const {
    const double h = sky_irradiance_altitude(atm, spec, y);
    const double zenith = sky_irradiance_sun_zenith(spec, x);
    in.stage("sky_irradiance path tracer");
    const IrradianceReference ref = reference_sky_irradiance(atm, h, zenith, rule, normals);
    const ShRadiance sh = texel_sh(table, x, y);
    MeasuredTexel t;
    t.decode = irradiance_errors(ref, [&](glm::dvec3 n) { return sh_l2_irradiance(sh, n); });
    t.limit =
        irradiance_errors(ref, [&](glm::dvec3 n) { return sh_l2_irradiance(ref.projection, n); });
    const IrradianceErrors interp =
        interpolation_errors(atm, source, spec, table, x, y, normals);
    t.json = {{"altitude_m", h},
              {"sun_zenith_deg", zenith / kDeg},
              {"decode", errors_json(t.decode)},
              {"l2_limit", errors_json(t.limit)},
              {"interpolation", errors_json(interp)}};
    return t;
  }
};

}  // namespace

SkyIrradianceReportSetup SkyIrradianceReportSetup::full() {
  SkyIrradianceReportSetup s;
  s.sky_irradiance_rows = {0, 4};
  s.sky_irradiance_columns = {0, 13, 23, 25};
  s.sky_irradiance_twilight_columns = {27, 29, 31};
  s.sky_irradiance_normals = 64;
  s.sky_irradiance_rays_below = 8;
  s.sky_irradiance_rays_above = 16;
  s.sky_irradiance_azimuths = 24;
  s.sky_irradiance_samples = 96;
  return s;
}

SkyIrradianceReportSetup SkyIrradianceReportSetup::quick() {
  SkyIrradianceReportSetup s = full();
  s.sky_irradiance_rows = {0};
  s.sky_irradiance_columns = {0, 23};
  s.sky_irradiance_twilight_columns = {};
  s.sky_irradiance_rays_below = 4;
  s.sky_irradiance_rays_above = 8;
  s.sky_irradiance_azimuths = 12;
  s.sky_irradiance_samples = 32;
  return s;
}

nlohmann::json sky_irradiance_report(const ReportInputs& in,
                                     const SkyIrradianceReportSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const OutputSpec spec = operating_spec(in.scene, "sky_irradiance");
  const SkyIrradianceSpec s = sky_irradiance_spec(spec);
  in.stage("sky_irradiance bake");
  // The product's own source (sky_light_products.cpp), remade on each timed bake.
  SkyLightHeld held;
  Texture table;
  const double seconds = time_bake(
      [&] {
        make_sky_light_held(held, atm, spec, in.transmittance, in.multiscattering, s,
                            s.max_sun_zenith_rad, {});
        return bake_sky_irradiance(atm, held.source(), s, {});
      },
      table, in.level.min_timing_seconds, 1);
  const SkyRadianceSource& source = held.source();
  IrradianceReferenceRule rule;
  rule.below = setup.sky_irradiance_rays_below;
  rule.above = setup.sky_irradiance_rays_above;
  rule.azimuths = setup.sky_irradiance_azimuths;
  rule.samples = setup.sky_irradiance_samples;
  const TexelMeasure measure{in, atm, source, s, table, setup.sky_irradiance_normals};
  nlohmann::json texels = nlohmann::json::array();
  double worst_rms = 0.0, worst_excess = -1.0, twilight_excess = -1.0;
  for (int y : setup.sky_irradiance_rows) {
    for (int x : setup.sky_irradiance_columns) {
      if (x >= s.width || y >= s.height || sun_below_horizon(sky_irradiance_sun_zenith(s, x)))
        continue;
      const MeasuredTexel t = measure(x, y, rule);
      worst_rms = std::max(worst_rms, t.decode.rms);
      worst_excess = std::max(worst_excess, t.decode.max - std::max(0.08, t.limit.max + 0.01));
      texels.push_back(t.json);
    }
  }
  IrradianceReferenceRule twilight_rule = rule;
  twilight_rule.samples = setup.sky_irradiance_twilight_samples;
  nlohmann::json twilight = nlohmann::json::array();
  for (int y : setup.sky_irradiance_rows)
    for (int x : setup.sky_irradiance_twilight_columns) {
      if (x >= s.width || y >= s.height || !sun_below_horizon(sky_irradiance_sun_zenith(s, x)))
        continue;
      const MeasuredTexel t = measure(x, y, twilight_rule);
      twilight_excess = std::max({twilight_excess, t.decode.rms - (t.limit.rms + 0.01),
                                  t.decode.max - (t.limit.max + 0.01)});
      twilight.push_back(t.json);
    }
  const bool met = worst_rms < 0.03 && worst_excess < 0.0;
  return {{"product", "sky_irradiance"},
          {"radiance_source", radiance_source_name(source)},
          {"size", {s.width, s.height}},
          {"bake_seconds", seconds},
          {"path_tracer", {{"rays_below", rule.below}, {"rays_above", rule.above},
                           {"azimuths", rule.azimuths}, {"samples", rule.samples},
                           {"normals", setup.sky_irradiance_normals}}},
          {"texels", texels},
          {"target", {{"what", "daylight decode vs path tracer: RMS < 3%, max < max(8%, L2 "
                               "limit max + 1%), relative to the mean E over the normals"},
                      {"worst_rms", worst_rms},
                      {"status", texels.empty() ? "not measured" : (met ? "met" : "missed")}}},
          {"twilight_path_tracer_samples", twilight_rule.samples},
          {"twilight_texels", twilight},
          {"twilight_target",
           {{"what", "twilight decode vs path tracer: RMS < L2 limit RMS + 1%, max < L2 limit "
                     "max + 1%"},
            {"worst_excess", twilight_excess},
            {"status", twilight.empty() ? "not measured"
                                        : (twilight_excess < 0.0 ? "met" : "missed")}}}};
}

}  // namespace skybake
