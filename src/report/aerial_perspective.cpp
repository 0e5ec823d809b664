// Aerial-perspective ladder of `skybake report` (ladders.hpp):
// steps_per_slice x slice counts at the preset's screen size, camera, sun
// and depth range, each volume read with lookup_aerial_perspective at
// pseudo-random (screen position, distance) and compared with the same march
// (sky_integrator.hpp) from the camera to that distance with many uniform
// steps, reading the same transmittance and multiple-scattering tables.
// RGB (in-scattered luminance) gives the primary numbers; A (the mean
// transmittance) is reported beside it as "transmittance".
//
// Queries: screen position uniform, distance uniform between the camera and
// the nearer of the depth range and the ground along that ray: an engine
// reads the volume at the depth of a visible surface, never past the ground
// (the froxels past it repeat the value at the ground).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "report/aerial_perspective.hpp"
#include "report/ladders.hpp"
#include "report/stats.hpp"

namespace skybake {

namespace {

struct AerialQuery {
  glm::dvec2 screen_uv{0.0};
  double distance_m = 0.0;
  glm::dvec4 reference{0.0};  // RGB luminance, A mean transmittance
};

std::vector<AerialQuery> aerial_queries(const ReportInputs& in, const AerialPerspectiveSetup& setup,
                                        const AerialPerspectiveSpec& op) {
  const Atmosphere& atm = in.scene.atmosphere;
  const glm::dvec3 sun_dir = sun_direction(op.sun_zenith_rad, op.sun_azimuth_rad);
  std::vector<AerialQuery> q(size_t(setup.aerial_queries));
  tbb::parallel_for(size_t(0), q.size(), [&](size_t i) {
    const AerialQueryPoint point = aerial_query(atm, op, i);
    q[i].screen_uv = point.screen_uv;
    q[i].distance_m = point.distance_m;
    const ScatteringResult ref = integrate_scattered_luminance(
        atm, in.transmittance, &in.multiscattering, point.position, point.view_dir, sun_dir,
        q[i].distance_m, setup.aerial_reference_steps);
    const glm::dvec3& t = ref.transmittance;
    q[i].reference = glm::dvec4(ref.luminance, (t.x + t.y + t.z) / 3.0);
  });
  return q;
}

nlohmann::json measure(const Texture& lut, double depth_range_m,
                       const std::vector<AerialQuery>& queries) {
  ErrorTally luminance, transmittance;
  for (const AerialQuery& q : queries) {
    const glm::dvec4 v = lookup_aerial_perspective(lut, depth_range_m, q.screen_uv, q.distance_m);
    for (int c = 0; c < 3; ++c) luminance.add(v[c], q.reference[c]);
    transmittance.add(v.w, q.reference.w);
  }
  nlohmann::json j = luminance.stats().json();
  j["transmittance"] = transmittance.stats().json();
  return j;
}

}  // namespace

AerialPerspectiveSetup AerialPerspectiveSetup::full() {
  AerialPerspectiveSetup s;
  s.aerial_steps = {1, 2, 4, 8};
  s.aerial_depths = {16, 32, 64};
  s.aerial_queries = 2048;
  s.aerial_reference_steps = 2000;
  return s;
}

AerialPerspectiveSetup AerialPerspectiveSetup::quick() {
  AerialPerspectiveSetup s;
  s.aerial_steps = {1, 2, 4};
  s.aerial_depths = {16, 32};
  s.aerial_queries = 256;
  s.aerial_reference_steps = 500;
  return s;
}

nlohmann::json aerial_perspective_report(const ReportInputs& in,
                                         const AerialPerspectiveSetup& setup) {
  const Atmosphere& atm = in.scene.atmosphere;
  const AerialPerspectiveSpec op =
      aerial_perspective_spec(operating_spec(in.scene, "aerial_perspective"));
  in.stage("aerial_perspective: reference march");
  const std::vector<AerialQuery> queries = aerial_queries(in, setup, op);

  std::vector<nlohmann::json> grid;
  for (int depth : setup.aerial_depths)
    for (int steps : setup.aerial_steps)
      grid.push_back({{"size", {op.width, op.height, depth}}, {"steps_per_slice", steps}});
  nlohmann::json sizes = nlohmann::json::array();
  for (int depth : setup.aerial_depths) sizes.push_back({op.width, op.height, depth});
  const nlohmann::json axes = {{"steps_per_slice", setup.aerial_steps}, {"size", sizes}};
  const LadderMeasure bake_and_measure = [&](const nlohmann::json& s) {
    AerialPerspectiveSpec spec = op;
    spec.width = s["size"][0];
    spec.height = s["size"][1];
    spec.depth = s["size"][2];
    spec.steps_per_slice = s["steps_per_slice"];
    Texture lut;
    const double seconds = time_bake(
        [&] {
          return bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, spec,
                                             BakeContext{});
        },
        lut, in.level.min_timing_seconds);
    nlohmann::json point = measure(lut, op.depth_range_m, queries);
    point["seconds"] = seconds;
    return point;
  };
  const nlohmann::json op_settings = {{"size", {op.width, op.height, op.depth}},
                                      {"steps_per_slice", op.steps_per_slice}};
  nlohmann::json out =
      run_ladder("aerial_perspective", axes, grid, op_settings, bake_and_measure, in);
  out["product"] = "aerial_perspective";
  out["kind"] = "lut";
  out["reference"] = fmt::format(
      "the same march from the camera with {} uniform steps to each query's distance, reading "
      "the same transmittance and multiple-scattering tables",
      setup.aerial_reference_steps);
  out["queries"] = fmt::format(
      "{} points: screen position uniform, distance uniform up to the nearer of {:g} km and "
      "the ground; RGB in max_rel / rms_rel, A in transmittance; lookup_aerial_perspective "
      "(trilinear)",
      queries.size(), op.depth_range_m * 1e-3);
  const Texture lut =
      bake_aerial_perspective_lut(atm, in.transmittance, in.multiscattering, op, BakeContext{});
  out["half"] = {{"float", measure(lut, op.depth_range_m, queries)},
                 {"half", measure(half_round_trip(lut), op.depth_range_m, queries)},
                 {"storage", half_storage_stats(lut)}};
  return out;
}

}  // namespace skybake
