// skybake's reads of tables baked in the hillaire_demo convention
// (table_convention.hpp): each table's own mapping (transmittance_lut.hpp,
// multiscattering_lut.hpp, skyview_lut.hpp, aerial_perspective_lut.hpp) to
// the unit axis, then the convention's placement to the texture coordinate,
// bilinear with clamp to edge. The C++ twins of runtime/glsl/hillaire_demo.glsl.
#pragma once

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"
#include "atmosphere/skyview_lut.hpp"
#include "core/texture.hpp"

namespace skybake {

// Transmittance from (r, mu) to the top (mu below the horizon reads the horizon).
glm::dvec3 lookup_demo_transmittance_to_top(const Texture& lut, const Atmosphere& atm, double r,
                                            double mu);

// Psi_ms at radius r and sun zenith cosine mu_s (linear axes).
glm::dvec3 lookup_demo_multiscattering(const Texture& lut, const Atmosphere& atm, double r,
                                       double mu_s);

// Sky-view luminance of `layer` (baked for viewer radius r) toward `view`;
// azimuths phi and 2 pi - phi read the same texels (the half circle).
glm::dvec3 lookup_demo_skyview(const Texture& lut, int layer, const Atmosphere& atm, double r,
                               SkyviewDirection view);

// RGB in-scattering and A opacity toward screen_uv at distance_m, trilinear
// in (u, v, sqrt(d / depth_range_m)); before the first slice a linear fade
// to (0, 0, 0, 0) at distance 0.
glm::dvec4 lookup_demo_aerial_perspective(const Texture& lut, double depth_range_m,
                                          glm::dvec2 screen_uv, double distance_m);

}  // namespace skybake
