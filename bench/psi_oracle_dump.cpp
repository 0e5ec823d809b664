// Research tool, not part of the product: dumps the report's sky views as a
// linear function of a multiple-scattering table (report/psi_weights.hpp),
// with the path-traced references, for bench/psi_oracle.py, which finds the
// best table any Psi(r, mu_s) could be (docs/decisions/converged-psi-ms.md).
//
//   build/bench/psi_oracle_dump PRESET OUT.json [WIDTHxHEIGHT] [PATHS] [SEED_SETS]
//        WIDTHxHEIGHT: the table's size (default: the preset's operating point)
//        PATHS: path tracer paths per channel and view (default 16384)
//        SEED_SETS: independent references (default 2); set 0 uses the
//        report's seeds, so its references are the report's bit for bit.
//        A 6th argument `heldout` replaces the report's views with others
//        (elevations 10, 35, 50 degrees, azimuths offset by half a step),
//        to check a table fitted to the report's views on views it was not;
//        `heldout2` another set (elevations 2, 14, 75, a quarter step); `-`
//        the report's views.
//        A 7th argument `view` dumps the form by view instead
//        (docs/reference.md "Psi_ms by view", 8 nu x 8 zenith slices): the
//        weights of every texel of its volume, the converged relative table
//        by view, and the isotropic relative table as the same form (a its
//        value at every nu node, b 0), "form": "view".
//
// Views, camera, sky-view settings, sun elevations and path tracer settings
// are the report's (`skybake report PRESET --only skyview --quick --paths
// PATHS`); the tables are the operating point's Hillaire table and the
// converged model's two estimators at the requested size.
#include <cstdio>
#include <fstream>
#include <string>

#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "reference/path_tracer.hpp"
#include "report/psi_weights.hpp"
#include "report/setup.hpp"

using namespace skybake;

namespace {

nlohmann::json channel_arrays(const std::vector<glm::dvec3>& v) {
  nlohmann::json out = nlohmann::json::array();
  for (int c = 0; c < 3; ++c) {
    std::vector<double> a;
    for (const glm::dvec3& x : v) a.push_back(x[c]);
    out.push_back(a);
  }
  return out;
}

nlohmann::json table_json(const Texture& t) {
  std::vector<glm::dvec3> v;
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x)
        v.push_back({t.at(x, y, z, 0, 0), t.at(x, y, z, 0, 1), t.at(x, y, z, 0, 2)});
  return channel_arrays(v);
}

// An isotropic table as a table by view of `like`'s slices: a its value at
// every nu node, b 0 (the same views, read the by-view way).
Texture isotropic_as_view(const Texture& isotropic, const Texture& like) {
  Texture t = like;
  const int nu_slices = meta_int(like.metadata, "nu_slices");
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x)
        for (int c = 0; c < 3; ++c)
          t.texel(x, y, z)[c] = z <= nu_slices ? isotropic.at(x, y, 0, 0, c) : 0.0f;
  return t;
}

// The references of every view, seeds as the report's plus `set` x a large odd offset.
nlohmann::json references(const Atmosphere& atm, const SkyRadianceCamera& cam,
                          const std::vector<double>& suns, int paths, int set) {
  const SkyPathTracer tracer(atm);
  PathTracerSpec spec;
  spec.samples = paths;
  spec.max_bounces = sky_radiance_max_bounces(atm);
  std::vector<glm::dvec3> mean, ci;
  for (size_t s = 0; s < suns.size(); ++s)
    for (size_t v = 0; v < cam.dirs.size(); ++v) {
      spec.seed = 3 * (s * cam.dirs.size() + v) + 1 + uint64_t(set) * 1000003ull;
      const RadianceEstimate e =
          tracer.trace(cam.position, cam.dirs[v], sky_radiance_sun(suns[s]), spec);
      mean.push_back(e.mean), ci.push_back(e.ci95);
    }
  return {{"mean", channel_arrays(mean)}, {"ci95", channel_arrays(ci)}};
}

// The report's camera, or with `held` "heldout" / "heldout2" its held-out
// twin: other elevations (written into `views`) and the azimuths turned
// about the zenith by half / a quarter of a step.
SkyRadianceCamera oracle_camera(const Scene& scene, const std::string& held,
                                SkyRadianceSetup& views) {
  if (held == "heldout") views.view_elevations_deg = {10.0, 35.0, 50.0};
  if (held == "heldout2") views.view_elevations_deg = {2.0, 14.0, 75.0};
  SkyRadianceCamera cam = sky_radiance_camera(scene, views);
  if (held != "heldout" && held != "heldout2") return cam;
  const double turn = held == "heldout2" ? 0.25 : 0.5;  // of an azimuth step
  for (glm::dvec3& d : cam.dirs) {
    const double a = 2.0 * kPi * turn / views.view_azimuths, x = d.x, y = d.y;
    d.x = std::cos(a) * x - std::sin(a) * y;
    d.y = std::sin(a) * x + std::cos(a) * y;
  }
  return cam;
}

// Each texel's altitude and sun cosine, and the range of the true source
// over directions there: where any mean of it with weights >= 0 (any
// estimator of that kind) must lie.
void add_texel_source_ranges(nlohmann::json& out, const Atmosphere& atm,
                             const Texture& transmittance, const Texture& table,
                             const ConvergedMultiscatteringSpec& spec, const ConvergedField& field) {
  std::vector<double> altitude, mu_s;
  const MultiscatteringMapping mapping = multiscattering_mapping_of(table);
  for (int y = 0; y < table.height; ++y)
    for (int x = 0; x < table.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, table.width), texel_center(y, table.height)}, table.width,
          table.height, mapping);
      altitude.push_back(p.r - atm.bottom_radius_m), mu_s.push_back(p.mu_s);
    }
  out["texel_altitude_m"] = altitude;
  out["texel_mu_s"] = mu_s;
  const PsiQuadrature q = psi_quadrature(spec, field.phases);  // relative: has the kernels
  std::vector<glm::dvec3> lo(altitude.size()), hi(altitude.size());
  tbb::parallel_for(size_t(0), altitude.size(), [&](size_t k) {
    const SourceRange range = converged_source_range(atm, transmittance, field,
                                                     atm.bottom_radius_m + altitude[k], mu_s[k], q);
    lo[k] = range.min, hi[k] = range.max;
  });
  out["texel_source_min"] = channel_arrays(lo);
  out["texel_source_max"] = channel_arrays(hi);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: psi_oracle_dump PRESET OUT.json [WxH] [PATHS] [SEED_SETS] [heldout]\n");
    return 2;
  }
  const Scene scene = load_scene(argv[1]);
  const Atmosphere& atm = scene.atmosphere;
  const SkyRadianceSetup setup = SkyRadianceSetup::quick();
  const int paths = argc > 4 ? std::stoi(argv[4]) : 16384, sets = argc > 5 ? std::stoi(argv[5]) : 2;
  const Texture transmittance = bake_transmittance_lut(
      atm, transmittance_spec(operating_spec(scene, "transmittance")), BakeContext{});
  const OutputSpec op = operating_spec(scene, "multiscattering");
  MultiscatteringLutSpec table = multiscattering_spec(op);
  if (argc > 3 && std::sscanf(argv[3], "%dx%d", &table.width, &table.height) != 2) return 2;
  const Texture hillaire = bake_multiscattering_lut(atm, transmittance, table, BakeContext{});
  ConvergedMultiscatteringSpec spec = converged_multiscattering_spec(op);
  const ConvergedField field = compute_converged_field(atm, transmittance, spec, BakeContext{});
  spec.estimator = PsiEstimator::mean;
  const Texture mean = converged_multiscattering_table(atm, transmittance, table, spec, field, {});
  spec.estimator = PsiEstimator::relative;
  const Texture rel = converged_multiscattering_table(atm, transmittance, table, spec, field, {});

  const bool by_view = argc > 7 && std::string(argv[7]) == "view";
  Texture view;
  if (by_view) {
    spec.nu_slices = spec.zenith_slices = 8;
    view = converged_multiscattering_table(atm, transmittance, table, spec, field, {});
  }
  SkyRadianceSetup views = setup;
  const std::string held = argc > 6 ? argv[6] : "";
  const bool heldout = held == "heldout" || held == "heldout2";
  const SkyRadianceCamera cam = oracle_camera(scene, held, views);
  const std::vector<double>& suns = setup.sun_elevations_deg;
  const PsiWeights w =
      sky_view_psi_weights(atm, transmittance, by_view ? view : hillaire, cam, suns);
  nlohmann::json out;
  out["preset"] = argv[1];
  out["table"] = {table.width, table.height};
  out["paths"] = paths;
  out["sun_elevations_deg"] = suns;
  out["view_elevations_deg"] = views.view_elevations_deg;
  out["heldout"] = heldout;
  out["form"] = by_view ? "view" : "isotropic";
  out["view_azimuths"] = setup.view_azimuths;
  out["single"] = channel_arrays(w.single);
  nlohmann::json weights = nlohmann::json::array();
  for (size_t v = 0; v < w.views; ++v)
    weights.push_back(channel_arrays(std::vector<glm::dvec3>(
        w.weights.begin() + long(v * w.texels()), w.weights.begin() + long((v + 1) * w.texels()))));
  out["weights"] = weights;  // [view][channel][texel], texel = (z * height + y) * width + x
  add_texel_source_ranges(out, atm, transmittance, hillaire, spec, field);
  std::vector<std::pair<const char*, const Texture*>> tables = {
      {"hillaire", &hillaire}, {"converged_mean", &mean}, {"converged_relative", &rel}};
  const Texture rel_as_view = by_view ? isotropic_as_view(rel, view) : Texture{};
  if (by_view) tables = {{"converged_relative", &rel_as_view}, {"converged_view", &view}};
  for (const auto& [name, t] : tables) {
    std::vector<glm::dvec3> rendered;
    for (double sun : suns)
      for (const glm::dvec3& l : render_sky_views(atm, transmittance, *t, cam, sun))
        rendered.push_back(l);
    out["tables"][name] = {{"values", table_json(*t)}, {"rendered", channel_arrays(rendered)}};
  }
  for (int set = 0; set < sets; ++set)
    out["references"].push_back(references(atm, cam, suns, paths, set));
  std::ofstream(argv[2]) << out.dump();
  return 0;
}
