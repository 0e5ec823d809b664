// Sky-view LUT: the distant sky around a viewer as a latitude/longitude
// texture (Hillaire 2020 section 5.3), one layer per (viewer altitude, sun
// zenith) pair.
//
// Shape: width x height (default 192 x 108, Hillaire's demo) x `views.size()`
// layers (a 2D array), channels R, G, B = in-scattered luminance (units of
// Atmosphere::sun_illuminance), float32. No sun disk (composited later, see
// sky_render.hpp) and no ground: below the horizon a texel holds the
// in-scattering between the viewer and the ground, the ground itself is scene
// geometry.
//
// Local frame of a layer: z = the viewer's zenith, the sun in the x-z plane
// at azimuth 0, sun_dir = (sin theta_s, 0, cos theta_s).
//
// Longitude (u): azimuth phi of the view direction around z measured from the
// sun's vertical plane, the full circle as in the paper: u = phi / (2 pi),
// phi in [0, 2 pi), texel i centred at phi = 2 pi (i + 0.5) / width, so the
// sun's plane falls between the last and the first texel and the sky is
// mirror-symmetric: texels i and width - 1 - i see mirrored directions (the
// bake marches half of each row and mirrors it).
// Lookups wrap around in u.
//
// Latitude (v): the paper's quadratic mapping that puts texels near the
// horizon, with the latitude l measured from the horizon as seen from the
// viewer's altitude (Hillaire's demo): with cos(beta) = sqrt(r^2 - Rb^2) / r,
// the horizon has zenith angle Z = pi - beta; a view of zenith angle theta has
// l = Z - theta in [-beta, Z] (> 0 sky, < 0 ground) and
//   x = 0.5 - 0.5 sqrt(l / Z)      for l >= 0
//   x = 0.5 + 0.5 sqrt(-l / beta)  for l < 0
//   v = texel_coord_from_unit(x, height)
// At the ground (beta = Z = pi / 2) this is the paper's
// v = 0.5 + 0.5 sign(l) sqrt(|l| / (pi / 2)) flipped so that row 0 is the
// zenith and the last row the nadir: the texture reads like a picture of the
// sky (Figure 4; y = 0 is the top row in our EXR, DDS and PNG files, and
// Hillaire's demo/Unreal put the zenith at v = 0). Above the ground the two
// halves stretch over their true angular ranges, so the horizon stays at
// x = 0.5 at every altitude; zenith and nadir are texel centres.
//
// Ray march: sky_integrator.hpp's, with `steps` segments (default 30, paper
// Table 2), quadratic step distribution by default, to the ground or the top;
// viewers above the top start where the ray enters the atmosphere. The bake
// marches each row once for all its azimuths and all the layers at its
// viewer altitude, and adds the sun per texel (skyview_row_march.hpp).
// Accuracy on Earth against a 3000-segment march: 30 quadratic segments stay
// within 1.2 % (RMS 0.3 %) with the sun up, 5 % with it just below the horizon
// (the planet's shadow edge); 30 uniform segments would err by up to 19 %.
// Reads: transmittance LUT, multiple-scattering LUT.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/sky_integrator.hpp"
#include "atmosphere/table_convention.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

struct SkyviewView {
  double altitude_m = 0.0;      // viewer altitude above the ground, m
  double sun_zenith_rad = 0.0;  // sun zenith angle, rad (> pi / 2: below the horizon)
};

struct SkyviewLutSpec {
  int width = 192;   // azimuth texels (u)
  int height = 108;  // latitude texels (v)
  int steps = 30;    // segments per ray
  StepDistribution distribution = StepDistribution::quadratic;
  std::vector<SkyviewView> views{SkyviewView{}};  // one layer each
  // Texel layout (table_convention.hpp): skybake's full circle above, or
  // hillaire_demo's half circle u = sqrt(0.5 - 0.5 cos phi) (the sun at
  // u = 0) with both axes read through (x n + 0.5) / (n + 1).
  TableConvention convention = TableConvention::skybake;
};

// A view direction in a layer's local frame.
struct SkyviewDirection {
  double mu = 1.0;           // cosine of the view zenith angle
  double azimuth_rad = 0.0;  // from the sun's vertical plane, [0, 2 pi)
};

// Texel-centre mapping pair at viewer radius r (see the opening comment).
glm::dvec2 skyview_uv_from_view(const Atmosphere& atm, double r, SkyviewDirection view, int width,
                                int height);
SkyviewDirection view_from_skyview_uv(const Atmosphere& atm, double r, glm::dvec2 uv, int width,
                                      int height);

// The texture coordinates in skybake's layout (view_from_skyview_uv's
// input) of the direction texel (x, y) of a table of `spec` holds; the
// texel's own centre for skybake's convention.
glm::dvec2 skyview_texel_uv(const Atmosphere& atm, double r, const SkyviewLutSpec& spec, int x,
                            int y);

// Unit view vector of a local-frame direction, and back (z up, sun at azimuth 0).
glm::dvec3 skyview_vector_from_direction(SkyviewDirection view);
SkyviewDirection skyview_direction_from_vectors(glm::dvec3 up, glm::dvec3 view_dir,
                                                glm::dvec3 sun_dir);

// Bakes one layer per spec.views entry; rows of all layers in parallel
// (tbb::parallel_for), each texel independent.
Texture bake_skyview_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                         const Texture& multiscattering_lut, const SkyviewLutSpec& spec,
                         const BakeContext& ctx);

// Luminance of layer `layer` (baked for viewer radius r) toward `view`,
// bilinear, wrapping in azimuth.
glm::dvec3 lookup_skyview(const Texture& lut, int layer, const Atmosphere& atm, double r,
                          SkyviewDirection view);

}  // namespace skybake
