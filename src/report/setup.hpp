// What every section of `skybake report` shares: the settings of a run
// (quick or full) common to several sections, and the tables baked once at
// the preset's own settings (the operating point) that later products read.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/texture.hpp"
#include "pipeline/scene.hpp"

namespace skybake {

// What several sections of one run share. `full` is meant for a report a
// person reads (a few minutes per scene on 2 cores); `quick` for tests and a
// first look (seconds): fewer ladder points, fewer queries, coarser
// references and a noisier path tracer. Each section's own counts are its
// setup (report/sections.hpp); every number is recorded in report.json's
// "level_settings", whose keys are these field names.
struct ReportLevel {
  std::string name;                    // "quick" or "full"
  double min_timing_seconds = 0.05;    // a bake is repeated until this much time has passed
  double quadrature_tolerance = 1e-9;  // relative, reference_* of atmosphere_quadrature.hpp
  // Tolerance of every adaptive quadrature of single scattering.
  double single_scattering_tolerance = 1e-6;
  // The fine transmittance table the fine references read.
  std::vector<int> reference_transmittance_size;
  int reference_transmittance_steps = 0;

  static ReportLevel quick();
  static ReportLevel full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ReportLevel, name, min_timing_seconds, quadrature_tolerance,
                                   single_scattering_tolerance, reference_transmittance_size,
                                   reference_transmittance_steps)

// Progress of the report, one message per stage ("transmittance ladder 3/15").
using ReportStage = std::function<void(const std::string&)>;

struct ReportInputs {
  const Scene& scene;
  const ReportLevel& level;
  const Texture& transmittance;            // at the preset's settings
  const Texture& multiscattering;          // at the preset's settings, read from `transmittance`
  const Texture& reference_transmittance;  // fine table for the fine references
  const nlohmann::json& report;            // report.json so far: the sections run before
  std::filesystem::path folder;            // DIR/<scene>/report, for a section's own files
  ReportStage on_stage;

  void stage(const std::string& message) const {
    if (on_stage) on_stage(message);
  }
};

// The output spec the scene gives `product`, or the registry defaults when
// the scene only needs it as a dependency.
OutputSpec operating_spec(const Scene& scene, const std::string& product);

}  // namespace skybake
