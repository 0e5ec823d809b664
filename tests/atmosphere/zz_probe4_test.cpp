// scratch probe, not committed
#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/skyview_multiple4d.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "reference/path_tracer.hpp"
#include "support/test_atmospheres.hpp"
namespace skybake {
TEST(ZzProbe4, NodesVsPathTracer) {
  const Atmosphere atm = fixtures::earth_atmosphere();
  const Texture t = bake_transmittance_lut(atm, {}, {});
  const ConvergedField field = compute_converged_field(atm, t, ConvergedMultiscatteringSpec{}, {});
  const SkyPathTracer tracer(atm);
  const int n = field.shape.mu_s_size;
  const double r = atm.bottom_radius_m + 1.0;
  for (int k = 0; k < n; ++k) {
    const ScatteringParams p = r_mu_mu_s_nu_from_scattering_uvwz(atm, field.shape, glm::dvec4(0.5, (k + 0.5) / n, 0.75, 0.5 / field.shape.r_size));
    const double z = std::acos(p.mu_s);
    if (z < 88.0 * kDeg) continue;
    for (double zz : {z, z + 0.5 * kDeg}) {
    for (double el : {30.0, 80.0}) {
      const glm::dvec3 sun(std::sin(zz), 0, std::cos(zz));
      const glm::dvec3 w(0.0, std::cos(el * kDeg), std::sin(el * kDeg));
      const glm::dvec3 ms = lookup_field_multiple_scattering(atm, field, r, SkyviewDirection{w.z, 90.0 * kDeg}, zz);
      PathTracerSpec spec;
      spec.samples = 16000;
      spec.sun_estimate = SunEstimate::segment;
      const auto all = tracer.trace(glm::dvec3(0, 0, r), w, sun, spec);
      spec.max_bounces = 1;
      const auto one = tracer.trace(glm::dvec3(0, 0, r), w, sun, spec);
      const double pt = all.mean.g - one.mean.g;
      std::printf("node %d zen %.2f el %.0f: field ms %.3e PT ms %.3e +- %.0f%% ratio %.2f\n", k, zz / kDeg, el, ms.g, pt, 100 * all.ci95.g / pt, ms.g / pt);
      std::fflush(stdout);
    }
    }
  }
}
}
