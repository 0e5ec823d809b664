// The incident radiance of order k - 1 around a point of the 4D table: the
// field the scattering density integrates (scattering_orders.hpp, "One order
// k >= 2 from order k - 1"), on a direction grid fixed in the frame of the
// sun, with the light the ground reflects into it.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

// Light reflected by the ground toward the sky: the irradiance of order k - 2
// at the ground, direct sunlight (E_0, from the transmittance LUT) or a table
// of irradiance_lut.hpp.
struct GroundIrradiance {
  const Texture* table = nullptr;  // nullptr: direct sunlight
  glm::dvec3 irradiance(const Atmosphere& atm, const Texture& transmittance_lut, double mu_s) const;
};

// Direction grid of the density: `bands` zenith bands x 2 bands azimuths,
// azimuth measured from the sun's vertical plane, each cell's exact solid
// angle (they sum to 4 pi).
struct SphereGrid {
  int bands = 0, azimuths = 0;
  std::vector<glm::dvec3> directions;  // band-major
  std::vector<double> solid_angle;
};
SphereGrid sphere_grid(int bands);

// The part of a zenith band [theta0, theta1] on one side of the horizon or
// one of its zenith sub-steps: its middle zenith angle, its share of the
// band's solid angle, and, below the horizon, the ground it sees (distance
// and transmittance along the ray itself: ray_transfer.hpp, the LUT's ratio
// overshoots in dense media; transmittance only with with_transmittance).
// Within one band's width of the horizon at r a band is cut into kIncidentSubBands
// equal zenith steps, and at the horizon itself when it falls inside;
// elsewhere it is one part, its middle. The incident field varies fastest
// near the horizon (the brightest sky just above it, the ground just
// below), and a band's middle alone gave Earth's J 2.7% too little light at
// 3 km with 16 bands (the bright sky between the horizontal and the
// horizon, 1.8 degrees there, read as dark ground). Used by the density's
// field (compute_incident_radiance) and the 3D table's gathering
// (gathering_lut.cpp); the phase weights keep the band's middle direction.
constexpr int kIncidentSubBands = 8;
struct BandPart {
  double theta = 0.0, share = 1.0;
  bool hits = false;
  double d = 0.0;
  glm::dvec3 T_ground{0.0};
};
std::vector<BandPart> band_parts(const Atmosphere& atm, double r, double theta0, double theta1,
                                 bool with_transmittance);

// band_parts of every band of the grid at r (with transmittance when the
// ground reflects or the order is read per opacity): they depend on r
// alone, so a baker computes them once per altitude for all its suns.
std::vector<std::vector<BandPart>> grid_band_parts(const Atmosphere& atm, double r,
                                                   const SphereGrid& grid,
                                                   const ScatteringOrder& previous);

// The incident radiance of order k - 1 at (r, mu_s) on the grid (sky plus
// ground term, see scattering_orders.hpp). Each grid cell holds the
// solid-angle weighted mean of the field over 4 zenith sub-bands of its band,
// cut once more at the horizon at r (sky above it, ground below).
std::vector<glm::dvec3> compute_incident_radiance(const Atmosphere& atm,
                                                  const Texture& transmittance_lut,
                                                  const ScatteringShape& shape,
                                                  const ScatteringOrder& previous,
                                                  const GroundIrradiance& ground, double r,
                                                  double mu_s, const SphereGrid& grid);
// The same with the parts of grid_band_parts(atm, r, grid, previous).
std::vector<glm::dvec3> compute_incident_radiance(
    const Atmosphere& atm, const Texture& transmittance_lut, const ScatteringShape& shape,
    const ScatteringOrder& previous, const GroundIrradiance& ground, double r, double mu_s,
    const SphereGrid& grid, const std::vector<std::vector<BandPart>>& parts);

// Rays that meet the ground: the incident field of the density reads the
// previous order's radiance toward the ground by interpolating between mu
// texels of the ground half, which are spaced linearly in the distance to
// the ground. In a dense sky that radiance saturates within a mean free path
// (L ~ J/sigma_t (1 - T)), far shorter than the texel spacing (300 m at the
// ground at 100x Rayleigh, 2.3 km between texels 105 m up on a 32 x 128
// table), and a linear blend of the saturating 1 - T reads too little: an
// energy loss every order, compounded over the hundreds a dense sky needs.
// So the density reads those rows divided by their ray's opacity 1 - T (a
// smooth mean of the source along the ray) and multiplies by the opacity of
// its own ray: exact at texels, and the saturation follows 1 - T instead of
// a straight line between texels. The opacity is per texel row (r, mu) of
// the ground half, RGB, 1 - ray_transmittance to the ground.
std::vector<glm::dvec3> ground_row_opacity(const Atmosphere& atm, const ScatteringShape& shape);
Texture divide_ground_rows_by_opacity(const Texture& table, const ScatteringShape& shape,
                                      const std::vector<glm::dvec3>& opacity);
// The same on a table in place (the orders reuse one buffer for it).
void divide_ground_rows_by_opacity_in_place(Texture& table, const ScatteringShape& shape,
                                            const std::vector<glm::dvec3>& opacity);

// Nodes of the ray from a point to the ground it sees, for the light the
// ground reflects into the incident field (compute_incident_radiance).
constexpr int kGroundRayNodes = 51;

}  // namespace skybake
