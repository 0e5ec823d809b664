#include "report/setup.hpp"

#include "core/error.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

ReportLevel ReportLevel::full() {
  ReportLevel l;
  l.name = "full";
  l.min_timing_seconds = 0.05;
  l.quadrature_tolerance = 1e-9;
  l.single_scattering_tolerance = 1e-6;
  l.reference_transmittance_size = {1024, 256};
  l.reference_transmittance_steps = 48;
  return l;
}

ReportLevel ReportLevel::quick() {
  ReportLevel l;
  l.name = "quick";
  l.min_timing_seconds = 0.005;
  l.quadrature_tolerance = 1e-8;
  l.single_scattering_tolerance = 1e-5;
  l.reference_transmittance_size = {512, 128};
  l.reference_transmittance_steps = 24;
  return l;
}

OutputSpec operating_spec(const Scene& scene, const std::string& product) {
  if (const OutputSpec* spec = scene.find_output(product)) return *spec;
  const ProductInfo* info = find_product(product);
  if (!info) throw Error("report: unknown product " + product);
  return default_spec(*info);
}

}  // namespace skybake
