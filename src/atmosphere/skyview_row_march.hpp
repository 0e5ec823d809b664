// The sky-view's ray march split into what a row shares and what a texel
// adds (the march of sky_integrator.hpp, Hillaire 2020 eq. 1-4 and 11).
//
// A row of a sky-view layer is one view zenith angle seen from one viewer
// radius; its texels differ only in azimuth, and the layers at that radius
// only in the sun. Rotating a view ray about the viewer's zenith moves none
// of its points off their altitude, so the segment lengths, radii, media,
// segment weights and the view transmittance are the row's, as are the
// radius halves of the two table lookups. A texel adds the sun: the phase of
// each component at its scattering cosine nu, and per segment the sun's
// zenith cosine
//   mu_s = (p . sun) / r = along cos(theta_s) + across cos(phi) sin(theta_s),
//   along = (r0 + t mu) / r,  across = t sqrt(1 - mu^2) / r,
// for a viewer at (0, 0, r0) looking along (sin theta cos phi, sin theta sin phi,
// mu) and the sun at (sin theta_s, 0, cos theta_s) (skyview_lut.hpp's frame),
// t the segment's midpoint distance and r = |p| its radius.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyviewRowSegment {
  double along = 0.0, across = 0.0;  // mu_s = along cos(theta_s) + across cos(phi) sin(theta_s)
  double mu_v = 0.0;  // the view ray's zenith cosine at the midpoint, (t + r0 mu) / r
  glm::dvec3 sigma_s{0.0};           // scattering of every component at the midpoint, 1/m
  // E T(viewer, segment start) (1 - exp(-sigma_t dt)) / sigma_t: what the
  // segment's source term is multiplied by (sky_integrator.hpp segment_weights).
  glm::dvec3 view_weight{0.0};
  TransmittanceAtRadius transmittance;      // the sun's lookup at the midpoint's radius
  MultiscatteringAtRadius multiscattering;  // Psi_ms's lookup at the same radius
};

struct SkyviewRowMarch {
  std::vector<SkyviewRowSegment> segments;  // segments with any medium, viewer first
  std::vector<double> densities;            // segments x scattering components, row-major
  std::vector<const MediumComponent*> components;  // the components that scatter, in order
};

// The row's part of the march from (0, 0, r) along zenith cosine mu, `steps`
// segments placed by `distribution` to the ground or the top (viewers above
// the top start where the ray enters), the medium at each midpoint.
SkyviewRowMarch march_skyview_row(const Atmosphere& atm, const Texture& transmittance_lut,
                                  const Texture& multiscattering_lut,
                                  const MultiscatteringMapping& mapping, double r, double mu,
                                  int steps, StepDistribution distribution);

// In-scattered luminance of one texel of the row: view azimuth cos_phi from
// the sun's plane, sun zenith (cos_theta_s, sin_theta_s), scattering cosine
// nu between the view ray and the sun. scattering_phase is scratch space
// (one entry per scattering component), reused from texel to texel.
glm::dvec3 skyview_texel_luminance(const SkyviewRowMarch& row, const Atmosphere& atm,
                                   const Texture& transmittance_lut,
                                   const Texture& multiscattering_lut, double cos_phi,
                                   double cos_theta_s, double sin_theta_s, double nu,
                                   std::vector<glm::dvec3>& scattering_phase);
}  // namespace skybake
