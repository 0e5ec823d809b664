#include "report/sky_radiance.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_render.hpp"
#include "atmosphere/orders_resolution.hpp"
#include "atmosphere/skyview_multiple4d.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "reference/path_tracer.hpp"

namespace skybake {

namespace {

const char* const kChannels[3] = {"R", "G", "B"};
constexpr double kVisibleFraction = 1e-3;

nlohmann::json vec_json(glm::dvec3 v) {
  return {v.x, v.y, v.z};
}

// The views of one sun elevation, in the camera's local frame (z up, the sun
// at azimuth 0).
std::vector<glm::dvec3> view_directions(const SkyRadianceSetup& setup) {
  std::vector<glm::dvec3> dirs;
  for (double elevation : setup.view_elevations_deg)
    for (int k = 0; k < setup.view_azimuths; ++k) {
      const double phi = 2.0 * kPi * k / setup.view_azimuths, e = elevation * kDeg;
      dirs.push_back({std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e)});
    }
  return dirs;
}

// Hillaire's Psi_ms without its series of higher orders: the second order
// L_2 alone (eq. 5-6), in the multiple-scattering table's layout. With it the
// sky-view march gives orders 1 and 2, which the path tracer gives with
// max_bounces = 2: the split shows whether an error comes from L_2's
// assumptions (isotropic phase, the same light at every point) or from the
// geometric series 1 / (1 - f_ms) that stands for orders >= 3.
Texture second_order_table(const Atmosphere& atm, const Texture& transmittance,
                           const MultiscatteringLutSpec& spec, const Texture& operating) {
  Texture tex(spec.width, spec.height, 1, 1, {"R", "G", "B"});
  const MultiscatteringMapping mapping = multiscattering_mapping_of(operating);
  set_multiscattering_mapping_metadata(tex.metadata, mapping);
  const std::vector<glm::dvec3> dirs = fibonacci_sphere_directions(spec.directions);
  tbb::parallel_for(0, spec.height, [&](int y) {
    for (int x = 0; x < spec.width; ++x) {
      const RadiusSunCosine p = r_mu_s_from_multiscattering_uv(
          atm, {texel_center(x, spec.width), texel_center(y, spec.height)}, spec.width,
          spec.height, mapping);
      const glm::dvec3 l2 =
          compute_multiscattering(atm, transmittance, p.r, p.mu_s, dirs, spec.steps).l2;
      for (int c = 0; c < 3; ++c) tex.at(x, y, 0, 0, c) = float(l2[c]);
    }
  });
  return tex;
}

// Everything measured for one view.
struct ViewResult {
  double sun_elevation_deg = 0, view_elevation_deg = 0, view_azimuth_deg = 0;
  glm::dvec3 lut{0.0}, lut_second{0.0}, lut_single{0.0}, quadrature_single{0.0};
  glm::dvec3 lut_converged{0.0};  // the same views with the converged Psi_ms (mean)
  glm::dvec3 lut_converged_relative{0.0};  // and with its relative estimator
  glm::dvec3 lut_converged_angular{0.0};   // and its source by view angle (nu slices)
  glm::dvec3 lut_multiple4d{0.0};  // sky-view: single marched + the 4D orders >= 2
  RadianceEstimate all, second, single;  // path tracer: every order, 2 vertices, 1 vertex
};

nlohmann::json view_json(const ViewResult& v) {
  return {{"sun_elevation_deg", v.sun_elevation_deg},
          {"view_elevation_deg", v.view_elevation_deg},
          {"view_azimuth_deg", v.view_azimuth_deg},
          {"lut", vec_json(v.lut)},
          {"lut_converged", vec_json(v.lut_converged)},
          {"lut_converged_relative", vec_json(v.lut_converged_relative)},
          {"lut_converged_angular", vec_json(v.lut_converged_angular)},
          {"lut_skyview_multiple4d", vec_json(v.lut_multiple4d)},
          {"path_traced", vec_json(v.all.mean)},
          {"path_traced_ci95", vec_json(v.all.ci95)},
          {"lut_second_order", vec_json(v.lut_second)},
          {"path_traced_2", vec_json(v.second.mean)},
          {"path_traced_2_ci95", vec_json(v.second.ci95)},
          {"lut_single", vec_json(v.lut_single)},
          {"path_traced_single", vec_json(v.single.mean)},
          {"path_traced_single_ci95", vec_json(v.single.ci95)},
          {"quadrature_single", vec_json(v.quadrature_single)}};
}

// The path tracer's three modes: every order, two vertices, single scattering.
struct PathSpecs {
  PathTracerSpec all, second, single;
};
PathSpecs path_specs(const Atmosphere& atm, const SkyRadianceSetup& setup) {
  PathSpecs p;
  p.all.samples = setup.path_samples;
  p.all.max_bounces = sky_radiance_max_bounces(atm);
  p.second = p.all;
  p.second.samples = setup.path_samples_single;
  p.second.max_bounces = 2;
  p.single = single_scattering_spec(p.all);
  p.single.samples = setup.path_samples_single;
  return p;
}

// The path tracer's single scattering against the quadrature: how many
// standard errors apart at most (|z| above ~4 would mean a biased
// reference), where single scattering is visible at all.
double path_tracer_max_z(const std::vector<ViewResult>& views) {
  double max_z = 0.0;
  for (const ViewResult& v : views)
    for (int c = 0; c < 3; ++c) {
      const double se = v.single.ci95[c] / 1.96;
      if (se > 0.0 && v.quadrature_single[c] > kVisibleFraction * v.all.mean[c])
        max_z = std::max(max_z, std::abs(v.single.mean[c] - v.quadrature_single[c]) / se);
    }
  return max_z;
}

// Statistics of one comparison over a set of views.
template <typename Pick>
nlohmann::json compare(const std::vector<ViewResult>& views, Pick pick) {
  std::vector<RadiancePair> pairs;
  for (const ViewResult& v : views) pairs.push_back(pick(v));
  return radiance_stats(pairs);
}

// Share of the path-traced radiance that orders >= 2 carry, per channel,
// averaged over the views: how much rides on the multiple-scattering model.
nlohmann::json multiple_scattering_share(const std::vector<ViewResult>& views) {
  glm::dvec3 sum(0.0);
  for (const ViewResult& v : views)
    for (int c = 0; c < 3; ++c)
      if (v.all.mean[c] > 0.0) sum[c] += 1.0 - v.quadrature_single[c] / v.all.mean[c];
  return vec_json(sum / double(std::max<size_t>(views.size(), 1)));
}

}  // namespace

// A medium of optical depth tau with little absorption needs ~tau^2 orders
// (path_tracer.hpp); 4 tau^2 leaves a margin, 64 covers Earth-like skies,
// 4096 bounds the cost.
int sky_radiance_max_bounces(const Atmosphere& atm) {
  const glm::dvec3 tau = reference_optical_depth(atm, atm.bottom_radius_m, 1.0,
                                                 atm.top_radius_m - atm.bottom_radius_m, 1e-6)
                             .value;
  const double t = std::max({tau.x, tau.y, tau.z});
  return int(std::clamp(std::ceil(4.0 * t * t), 64.0, 4096.0));
}

SkyRadianceCamera sky_radiance_camera(const Scene& scene, const SkyRadianceSetup& setup) {
  const Atmosphere& atm = scene.atmosphere;
  SkyRadianceCamera c;
  c.altitude_m = std::min(200.0, 0.5 * (atm.top_radius_m - atm.bottom_radius_m));
  c.position = glm::dvec3(0.0, 0.0, atm.bottom_radius_m + c.altitude_m);
  c.dirs = view_directions(setup);
  c.sky = skyview_spec(operating_spec(scene, "skyview"));
  return c;
}

glm::dvec3 sky_radiance_sun(double sun_elevation_deg) {
  const double e = sun_elevation_deg * kDeg;
  return {std::cos(e), 0.0, std::sin(e)};
}

std::vector<glm::dvec3> render_sky_views(const Atmosphere& atm, const Texture& transmittance,
                                         const Texture& multiscattering,
                                         const SkyRadianceCamera& camera,
                                         double sun_elevation_deg) {
  SkyviewLutSpec sky = camera.sky;
  sky.views = {{camera.altitude_m, kPi / 2 - sun_elevation_deg * kDeg}};
  const Texture layer = bake_skyview_lut(atm, transmittance, multiscattering, sky, BakeContext{});
  SkyRenderOptions render;
  render.sun_disk = false;
  render.ground = false;
  const SkyLuts luts{&transmittance, &multiscattering, &layer, 0};
  std::vector<glm::dvec3> out;
  for (const glm::dvec3& dir : camera.dirs)
    out.push_back(render_sky_luminance(atm, luts, camera.position, dir,
                                       sky_radiance_sun(sun_elevation_deg), render));
  return out;
}

nlohmann::json target_json(const nlohmann::json& multiple) {
  const double raw = multiple["worst"]["rel_rmse"];
  const double denoised = multiple["worst"]["rel_rmse_denoised"];
  std::string status = "undetermined";
  if (raw < kDaytimeRelativeRmseTarget)
    status = "met";
  else if (denoised > kDaytimeRelativeRmseTarget)
    status = "not met";
  return {{"what",
           "Earth daytime: relative RMSE < 1% for the model with multiple scattering, worst "
           "channel, all sun elevations"},
          {"threshold", kDaytimeRelativeRmseTarget},
          {"rel_rmse", raw},
          {"rel_rmse_denoised", denoised},
          {"status", status}};
}

nlohmann::json radiance_stats(const std::vector<RadiancePair>& rows) {
  nlohmann::json channels = nlohmann::json::array();
  double worst_rmse = 0.0, worst_denoised = 0.0, worst_noise = 0.0, worst_max = 0.0;
  for (int c = 0; c < 3; ++c) {
    double sq = 0.0, rel_sq = 0.0, noise_sq = 0.0, bias = 0.0, max_rel = 0.0, max_ci = 0.0;
    size_t n = 0;
    for (const RadiancePair& p : rows) {
      sq += (p.lut[c] - p.mean[c]) * (p.lut[c] - p.mean[c]);
      const double denominator = std::max(p.mean[c], kVisibleFraction * p.scale[c]);
      if (!(denominator > 0.0)) continue;  // no relative error against a black sky
      const double rel = (p.lut[c] - p.mean[c]) / denominator;
      const double se_rel = p.ci95[c] / 1.96 / denominator;
      rel_sq += rel * rel;
      noise_sq += se_rel * se_rel;
      bias += rel;
      max_rel = std::max(max_rel, std::abs(rel));
      max_ci = std::max(max_ci, p.ci95[c] / denominator);
      ++n;
    }
    const double count = double(std::max<size_t>(n, 1));
    const double rel_rmse = std::sqrt(rel_sq / count), noise = std::sqrt(noise_sq / count);
    const double denoised = std::sqrt(std::max(rel_rmse * rel_rmse - noise * noise, 0.0));
    channels.push_back({{"channel", kChannels[c]},
                        {"views", n},
                        {"rmse", std::sqrt(sq / double(std::max<size_t>(rows.size(), 1)))},
                        {"rel_rmse", rel_rmse},
                        {"noise_rel_rms", noise},
                        {"rel_rmse_denoised", denoised},
                        {"rel_bias", bias / count},
                        {"max_rel", max_rel},
                        {"max_ci95_rel", max_ci}});
    worst_rmse = std::max(worst_rmse, rel_rmse);
    worst_denoised = std::max(worst_denoised, denoised);
    worst_noise = std::max(worst_noise, noise);
    worst_max = std::max(worst_max, max_rel);
  }
  return {{"channels", channels},
          {"worst",
           {{"rel_rmse", worst_rmse},
            {"rel_rmse_denoised", worst_denoised},
            {"noise_rel_rms", worst_noise},
            {"max_rel", worst_max}}}};
}

namespace {

// What every sun elevation reads: the camera, its views, the sky-view spec
// and the multiple-scattering tables with Psi_ms replaced.
struct SkyRadianceScene {
  SkyRadianceCamera camera;
  Texture no_multiscattering, second_order;
  // Both Psi_ms models at the operating point's size and mapping, each
  // baked once more and timed (docs/report.md "Two Psi_ms models").
  Texture converged, converged_relative;  // estimators mean and relative
  Texture converged_angular;  // relative, with kReportNuSlices nu slices
  ConvergedField field;  // the iteration behind `converged`, shared with the 4D sky-view
  // The 4D sky-view's own iteration at the shape of orders_resolution.hpp,
  // where the Mie group shapes the orders (full level); else empty.
  ConvergedField field_mie_lobe;
  double hillaire_seconds = 0.0, converged_seconds = 0.0, angular_table_seconds = 0.0;
  int converged_orders = 0;
  double converged_residual = 1.0;
};

// The operating point's table under both models, with their bake times.
void bake_both_models(const ReportInputs& in, SkyRadianceScene& s) {
  const Atmosphere& atm = in.scene.atmosphere;
  const OutputSpec op = operating_spec(in.scene, "multiscattering");
  const MultiscatteringLutSpec table = multiscattering_spec(op);
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  const Texture hillaire = bake_multiscattering_lut(atm, in.transmittance, table, BakeContext{});
  s.hillaire_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  in.stage("sky radiance: the converged Psi_ms model");
  t0 = clock::now();
  ConvergedMultiscatteringSpec spec = converged_multiscattering_spec(op);
  spec.estimator = PsiEstimator::mean;
  s.field = compute_converged_field(atm, in.transmittance, spec, BakeContext{});
  s.converged = converged_multiscattering_table(atm, in.transmittance, table, spec, s.field,
                                                BakeContext{});
  s.converged_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  spec.estimator = PsiEstimator::relative;
  s.converged_relative = converged_multiscattering_table(atm, in.transmittance, table, spec,
                                                         s.field, BakeContext{});
  t0 = clock::now();
  spec.nu_slices = kReportNuSlices;
  spec.zenith_slices = kReportZenithSlices;
  s.converged_angular = converged_multiscattering_table(atm, in.transmittance, table, spec,
                                                        s.field, BakeContext{});
  s.angular_table_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  s.converged_orders = meta_int(s.converged.metadata, "orders_used");
  s.converged_residual = meta_double(s.converged.metadata, "last_residual");
}

SkyRadianceScene sky_radiance_scene(const ReportInputs& in, const SkyRadianceSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  SkyRadianceScene s;
  s.camera = sky_radiance_camera(in.scene, setup);
  s.no_multiscattering = in.multiscattering;
  std::fill(s.no_multiscattering.data.begin(), s.no_multiscattering.data.end(), 0.0f);
  s.second_order = second_order_table(
      atm, in.transmittance, multiscattering_spec(operating_spec(in.scene, "multiscattering")),
      in.multiscattering);
  bake_both_models(in, s);
  if (in.level.name == "full" && mie_shapes_multiple_scattering(atm)) {
    ConvergedMultiscatteringSpec spec =
        converged_multiscattering_spec(operating_spec(in.scene, "multiscattering"));
    spec.bruneton = with_mie_lobe_shape(spec.bruneton);
    in.stage("sky radiance: the 4D sky-view's iteration at the Mie lobe's shape");
    s.field_mie_lobe = compute_converged_field(atm, in.transmittance, spec, BakeContext{});
  }
  return s;
}

// The views of one sun elevation, appended to `views`.
void measure_sun(const ReportInputs& in, const SkyRadianceSetup& setup, SkyRadianceScene& s,
                 const SkyPathTracer& tracer, PathSpecs& paths, double sun_elevation,
                 std::vector<ViewResult>& views) {
  const Atmosphere& atm = in.scene.atmosphere;
  const SkyRadianceCamera& cam = s.camera;
  const glm::dvec3 sun_dir = sky_radiance_sun(sun_elevation);
  auto render = [&](const Texture& ms) {
    return render_sky_views(atm, in.transmittance, ms, cam, sun_elevation);
  };
  const std::vector<glm::dvec3> full = render(in.multiscattering), second = render(s.second_order),
                                single = render(s.no_multiscattering),
                                converged = render(s.converged),
                                converged_relative = render(s.converged_relative),
                                converged_angular = render(s.converged_angular);
  SkyviewLutSpec sky = cam.sky;
  sky.views = {{cam.altitude_m, kPi / 2 - sun_elevation * kDeg}};
  const Texture multiple4d =
      bake_skyview_lut_multiple4d(atm, in.transmittance,
                                  s.field_mie_lobe.orders_used > 0 ? s.field_mie_lobe : s.field,
                                  sky, BakeContext{});
  SkyRenderOptions no_disk;
  no_disk.sun_disk = false;
  no_disk.ground = false;
  const SkyLuts luts4d{&in.transmittance, &s.no_multiscattering, &multiple4d, 0};
  for (size_t v = 0; v < cam.dirs.size(); ++v) {
    const glm::dvec3 dir = cam.dirs[v];
    ViewResult r;
    r.sun_elevation_deg = sun_elevation;
    r.view_elevation_deg = std::asin(dir.z) / kDeg;
    r.view_azimuth_deg = 360.0 * double(v % size_t(setup.view_azimuths)) / setup.view_azimuths;
    r.lut = full[v];
    r.lut_converged = converged[v];
    r.lut_converged_relative = converged_relative[v];
    r.lut_converged_angular = converged_angular[v];
    r.lut_multiple4d = render_sky_luminance(atm, luts4d, cam.position, dir, sun_dir, no_disk);
    r.lut_second = second[v];
    r.lut_single = single[v];
    r.quadrature_single = reference_single_scattering(atm, cam.position, dir, sun_dir,
                                                      in.level.single_scattering_tolerance)
                              .value;
    // Every view and mode draws its own paths.
    const uint64_t seed = 3 * views.size();
    paths.all.seed = seed + 1, paths.second.seed = seed + 2, paths.single.seed = seed + 3;
    r.all = tracer.trace(cam.position, dir, sun_dir, paths.all);
    r.second = tracer.trace(cam.position, dir, sun_dir, paths.second);
    r.single = tracer.trace(cam.position, dir, sun_dir, paths.single);
    views.push_back(r);
  }
}

RadiancePair multiple_pair(const ViewResult& v) {
  return {v.lut, v.all.mean, v.all.ci95, v.all.mean};
}

// The comparisons of the header over every view.
nlohmann::json comparisons_json(const std::vector<ViewResult>& views) {
  const nlohmann::json multiple = compare(views, multiple_pair);
  return {
      {"multiple_scattering_share", multiple_scattering_share(views)},
      {"multiple", multiple},
      {"converged_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_converged, v.all.mean, v.all.ci95, v.all.mean};
               })},
      {"converged_relative_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_converged_relative, v.all.mean, v.all.ci95,
                                     v.all.mean};
               })},
      {"converged_angular_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_converged_angular, v.all.mean, v.all.ci95,
                                     v.all.mean};
               })},
      {"skyview_multiple4d_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_multiple4d, v.all.mean, v.all.ci95, v.all.mean};
               })},
      {"second_order_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_second, v.second.mean, v.second.ci95, v.all.mean};
               })},
      {"single_vs_path_tracer",
       compare(views,
               [](const ViewResult& v) {
                 return RadiancePair{v.lut_single, v.single.mean, v.single.ci95, v.all.mean};
               })},
      {"single_vs_quadrature",
       compare(
           views,
           [](const ViewResult& v) {
             return RadiancePair{v.lut_single, v.quadrature_single, glm::dvec3(0.0), v.all.mean};
           })},
      {"target", target_json(multiple)}};
}

}  // namespace

SkyRadianceSetup SkyRadianceSetup::full() {
  SkyRadianceSetup s;
  s.sun_elevations_deg = {60.0, 20.0, 5.0};
  s.view_elevations_deg = {5.0, 20.0, 60.0};
  s.view_azimuths = 8;
  s.path_samples = 65536;
  s.path_samples_single = 16384;
  return s;
}

SkyRadianceSetup SkyRadianceSetup::quick() {
  SkyRadianceSetup s = full();
  s.path_samples = 256;
  s.path_samples_single = 256;
  return s;
}

nlohmann::json sky_radiance_report(const ReportInputs& in, const SkyRadianceSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  SkyRadianceScene scene = sky_radiance_scene(in, setup);
  PathSpecs paths = path_specs(atm, setup);
  const SkyPathTracer tracer(atm);
  std::vector<ViewResult> views;
  nlohmann::json by_sun = nlohmann::json::array();
  for (double sun_elevation : setup.sun_elevations_deg) {
    in.stage(fmt::format("sky radiance: sun at {:g} deg, {} views, {} paths", sun_elevation,
                         scene.camera.dirs.size(), setup.path_samples));
    const size_t first = views.size();
    measure_sun(in, setup, scene, tracer, paths, sun_elevation, views);
    const std::vector<ViewResult> these(views.begin() + long(first), views.end());
    by_sun.push_back({{"sun_elevation_deg", sun_elevation},
                      {"multiple", compare(these, multiple_pair)},
                      {"converged", compare(these, [](const ViewResult& v) {
                         return RadiancePair{v.lut_converged, v.all.mean, v.all.ci95, v.all.mean};
                       })},
                      {"converged_relative", compare(these, [](const ViewResult& v) {
                         return RadiancePair{v.lut_converged_relative, v.all.mean, v.all.ci95,
                                             v.all.mean};
                       })},
                      {"converged_angular", compare(these, [](const ViewResult& v) {
                         return RadiancePair{v.lut_converged_angular, v.all.mean, v.all.ci95,
                                             v.all.mean};
                       })}});
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const ViewResult& v : views) rows.push_back(view_json(v));
  nlohmann::json out = comparisons_json(views);
  out["converged_target"] = target_json(out["converged_vs_path_tracer"]);
  out["converged_relative_target"] = target_json(out["converged_relative_vs_path_tracer"]);
  out["converged_angular_target"] = target_json(out["converged_angular_vs_path_tracer"]);
  out["skyview_multiple4d_target"] = target_json(out["skyview_multiple4d_vs_path_tracer"]);
  out["models"] = {
      {"hillaire2020", {{"bake_seconds", scene.hillaire_seconds}}},
      {"converged",
       {{"bake_seconds", scene.converged_seconds},
        {"orders_used", scene.converged_orders},
        {"last_residual", scene.converged_residual},
        {"scattering_shape", meta_string(scene.converged.metadata, "scattering_shape")},
        {"tolerance", meta_double(scene.converged.metadata, "tolerance")}}},
      {"converged_angular",
       {{"bake_seconds", scene.converged_seconds + scene.angular_table_seconds},
        {"nu_slices", kReportNuSlices}}}};
  out.update(
      {{"camera_altitude_m", scene.camera.altitude_m},
       {"sun_elevations_deg", setup.sun_elevations_deg},
       {"view_elevations_deg", setup.view_elevations_deg},
       {"view_azimuths", setup.view_azimuths},
       {"skyview",
        {{"size", {scene.camera.sky.width, scene.camera.sky.height}},
         {"steps", scene.camera.sky.steps}}},
       {"path_tracer",
        {{"samples", setup.path_samples},
         {"samples_single_and_second_order", setup.path_samples_single},
         {"max_bounces", paths.all.max_bounces},
         {"ground_albedo", vec_json(atm.ground_albedo)},
         {"single_scattering_max_z_vs_quadrature", path_tracer_max_z(views)}}},
       {"multiple_by_sun", by_sun},
       {"views", rows}});
  return out;
}

}  // namespace skybake
