// What every section of `skybake report` shares: the sample counts of a run
// (quick or full) and the tables baked once at the preset's own settings
// (the operating point) that later products read.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/texture.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// Sample counts and ladders of one run. `full` is meant for a report a person
// reads (a few minutes per scene on 2 cores); `quick` for tests and a first
// look (seconds): fewer ladder points, fewer queries, coarser references and
// a noisier path tracer. Every number is recorded in report.json.
struct ReportLevel {
  std::string name;                  // "quick" or "full"
  double min_timing_seconds = 0.05;  // a bake is repeated until this much time has passed

  // Transmittance: steps x sizes, queries against adaptive quadrature.
  std::vector<int> transmittance_steps;
  std::vector<std::vector<int>> transmittance_sizes;
  int transmittance_queries = 0;
  double quadrature_tolerance = 1e-9;  // relative, reference_* of atmosphere_quadrature.hpp

  // Multiscattering: directions x steps x sizes; the reference is the same
  // integral with many more directions and steps.
  std::vector<int> multiscattering_directions;
  std::vector<std::vector<int>> multiscattering_sizes;  // empty: the preset's size only
  std::vector<int> multiscattering_steps;
  int multiscattering_queries = 0;
  int multiscattering_reference_directions = 0;
  int multiscattering_reference_steps = 0;

  // Sky-view: steps x sizes over the preset's layers; the reference is the
  // same march with many more steps, and for single scattering the adaptive
  // quadrature.
  std::vector<int> skyview_steps;
  std::vector<std::vector<int>> skyview_sizes;
  int skyview_queries = 0;
  int skyview_reference_steps = 0;
  double single_scattering_tolerance = 1e-6;

  // Aerial perspective: steps_per_slice x slice counts.
  std::vector<int> aerial_steps;
  std::vector<int> aerial_depths;
  int aerial_queries = 0;
  int aerial_reference_steps = 0;

  // Scattering (Bruneton 4D, single scattering): shapes (r, mu, mu_s, nu) x
  // ray nodes, queries against adaptive quadrature.
  std::vector<std::vector<int>> scattering_shapes;
  std::vector<int> scattering_ray_nodes;
  int scattering_queries = 0;

  // Single Mie (the 4D family's separate texture, one order): shapes
  // (r, mu, mu_s, nu) x ray nodes, queries against adaptive quadrature of
  // the Mie group's phase-free single scattering.
  std::vector<std::vector<int>> single_mie_shapes;
  std::vector<int> single_mie_ray_nodes;
  int single_mie_queries = 0;

  // Irradiance (the 4D family's ground irradiance, one order, read from a
  // 4D table of the preset's scattering shape): sizes (mu_s, r) x
  // hemisphere directions; the reference integrates adaptive quadrature of
  // single scattering over the hemisphere, to this relative tolerance.
  std::vector<std::vector<int>> irradiance_sizes;
  std::vector<int> irradiance_directions;
  int irradiance_queries = 0;
  double irradiance_reference_tolerance = 1e-4;

  // Scattering3d (azimuth-free, one order): shapes (h, mu, mu_s) x ray
  // nodes; the reference is the mean over this many sun azimuths of the
  // phase-free quadrature.
  std::vector<std::vector<int>> scattering3d_shapes;
  std::vector<int> scattering3d_ray_nodes;
  int scattering3d_queries = 0;
  int scattering3d_reference_azimuths = 0;

  // Gathering sum (the 3D family's, the preset's orders): shapes (h, mu,
  // mu_s) x gathering directions, against one finer bake (self-convergence).
  std::vector<std::vector<int>> gathering_shapes;
  std::vector<int> gathering_directions;
  int gathering_queries = 0;
  std::vector<int> gathering_reference_shape;
  int gathering_reference_directions = 0;
  int gathering_reference_ray_nodes = 0;

  // The reference transmittance table the fine references read.
  std::vector<int> reference_transmittance_size;
  int reference_transmittance_steps = 0;

  // Sky radiance against the path tracer.
  std::vector<double> sun_elevations_deg;
  std::vector<double> view_elevations_deg;
  int view_azimuths = 8;
  int path_samples = 0;         // paths per channel and view, every order
  int path_samples_single = 0;  // the same for single scattering (also checked by quadrature)

  // Bruneton's tables for the Hillaire-vs-Bruneton comparison, when the scene
  // has no scattering output of its own: shape (r, mu, mu_s, nu) and orders,
  // or with tolerance > 0 orders until the residual drops below it.
  std::vector<int> bruneton_shape;
  int bruneton_orders = 4;
  double bruneton_tolerance = 0.0;
  int bruneton_max_orders = 100;

  // Sky preview picture size.
  int preview_width = 0, preview_height = 0;

  static ReportLevel quick();
  static ReportLevel full();
};

// Every field, for report.json (so a report says how it was measured).
nlohmann::json level_json(const ReportLevel& level);

// Progress of the report, one message per stage ("transmittance ladder 3/15").
using ReportStage = std::function<void(const std::string&)>;

struct ReportInputs {
  const Scene& scene;
  const ReportLevel& level;
  const Texture& transmittance;            // at the preset's settings
  const Texture& multiscattering;          // at the preset's settings, read from `transmittance`
  const Texture& reference_transmittance;  // fine table for the fine references
  ReportStage on_stage;

  void stage(const std::string& message) const {
    if (on_stage) on_stage(message);
  }
};

// The output spec the scene gives `product`, or the registry defaults when
// the scene only needs it as a dependency.
OutputSpec operating_spec(const Scene& scene, const std::string& product);

}  // namespace skybake
