// Scattering3d (azimuth-free, one order) ladder of `skybake report`
// (scattering3d.cpp): shapes (h, mu, mu_s) x ray nodes; the reference is the
// mean over sun azimuths of the phase-free quadrature.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct Scattering3dSetup {
  std::vector<std::vector<int>> scattering3d_shapes;
  std::vector<int> scattering3d_ray_nodes;
  int scattering3d_queries = 0;
  int scattering3d_reference_azimuths = 0;

  static Scattering3dSetup quick();
  static Scattering3dSetup full();
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Scattering3dSetup, scattering3d_shapes, scattering3d_ray_nodes,
                                   scattering3d_queries, scattering3d_reference_azimuths)

nlohmann::json scattering3d_report(const ReportInputs& in, const Scattering3dSetup& setup);

}  // namespace skybake
