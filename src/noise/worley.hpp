// Periodic Worley (cellular) noise F1 in 2D and 3D (Worley 1996), as the cloud
// noises use it (Schneider, GPU Pro 7 sec. 4.3.1; Frostbite 2016 sec. 5.4).
//
// One feature point per cell, its offset inside the cell a pure hash of the
// wrapped cell coordinates; the cell coordinates of the 27 (3D) or 9 (2D)
// neighbour cells are wrapped with a floor-based modulo by the period, so
// F1(p + period) = F1(p), also for negative p (docs/reference.md "Cloud noise").
//
// Normalisation: F1 is the Euclidean distance in cells to the nearest feature
// point, divided by the bound 1 cell and clamped to [0, 1]. The bound 1 is the
// one for which the 3x3(x3) search is exact rather than an approximation: a
// point outside the neighbour cells is at least 1 cell away along some axis,
// so it can only matter where the distance is clamped anyway. It is also what
// the TileableVolumeNoise generator of Frostbite's Appendix D does (it clamps
// the distance to [0, 1]; it keeps it squared, we keep it linear like Worley).
// Clouds use the inverted noise, 1 - F1, so that cells are bright (Schneider).
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace skybake {

// Offset of the feature point of a cell inside the cell, in [0, 1) per axis;
// the cell coordinates are already wrapped into [0, period). Public so that
// the volume bakers tabulate the very same points.
glm::vec3 worley3_feature_offset(int cx, int cy, int cz, uint32_t seed);
glm::vec2 worley2_feature_offset(int cx, int cy, uint32_t seed);

// Normalised F1 in [0, 1]: distance in cells to the nearest feature point,
// clamped at 1. p in cells; period > 0 per axis (cells).
float worley3_f1(glm::vec3 p, glm::ivec3 period, uint32_t seed);
float worley2_f1(glm::vec2 p, glm::ivec2 period, uint32_t seed);

// Inverted Worley, 1 - F1, in [0, 1]: 1 on a feature point.
inline float worley3_inverted(glm::vec3 p, glm::ivec3 period, uint32_t seed) {
  return 1.0f - worley3_f1(p, period, seed);
}
inline float worley2_inverted(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
  return 1.0f - worley2_f1(p, period, seed);
}

}  // namespace skybake
