#include "noise/worley.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/math.hpp"
#include "noise/lattice_hash.hpp"

namespace skybake {

glm::vec3 worley3_feature_offset(int cx, int cy, int cz, uint32_t seed) {
  // One lattice hash, then two more mixing rounds for the other two axes:
  // 24 independent bits per coordinate.
  const uint32_t h0 = hash_lattice(cx, cy, cz, seed);
  const uint32_t h1 = hash_mix(h0);
  const uint32_t h2 = hash_mix(h1);
  return {unit_float_from_hash(h0), unit_float_from_hash(h1), unit_float_from_hash(h2)};
}

glm::vec2 worley2_feature_offset(int cx, int cy, uint32_t seed) {
  const uint32_t h0 = hash_lattice(cx, cy, seed);
  return {unit_float_from_hash(h0), unit_float_from_hash(hash_mix(h0))};
}

float worley3_f1(glm::vec3 p, glm::ivec3 period, uint32_t seed) {
  assert(period.x > 0 && period.y > 0 && period.z > 0);
  const glm::vec3 cell(std::floor(p.x), std::floor(p.y), std::floor(p.z));
  const int ix = int(cell.x), iy = int(cell.y), iz = int(cell.z);
  // Distances are taken from the position inside the cell (exact: p minus its
  // floor), never from absolute coordinates: they then depend on the wrapped
  // cell only, so F1(p + period) == F1(p) bit for bit wherever p + period is
  // exact, instead of rounding differently with the magnitude of the cell.
  const glm::vec3 f = p - cell;
  // Start at the bound: anything farther is clamped to it (see the header).
  float best = 1.0f;
  for (int oz = -1; oz <= 1; ++oz) {
    for (int oy = -1; oy <= 1; ++oy) {
      for (int ox = -1; ox <= 1; ++ox) {
        const glm::vec3 o =
            worley3_feature_offset(wrap_index(ix + ox, period.x), wrap_index(iy + oy, period.y),
                                   wrap_index(iz + oz, period.z), seed);
        const float dx = f.x - (float(ox) + o.x);
        const float dy = f.y - (float(oy) + o.y);
        const float dz = f.z - (float(oz) + o.z);
        // Summed as dx^2 + (dy^2 + dz^2), the order the volume baker uses.
        best = std::min(best, dx * dx + (dy * dy + dz * dz));
      }
    }
  }
  return std::sqrt(best);
}

float worley2_f1(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
  assert(period.x > 0 && period.y > 0);
  const glm::vec2 cell(std::floor(p.x), std::floor(p.y));
  const int ix = int(cell.x), iy = int(cell.y);
  const glm::vec2 f = p - cell;  // cell-local, as in worley3_f1
  float best = 1.0f;
  for (int oy = -1; oy <= 1; ++oy) {
    for (int ox = -1; ox <= 1; ++ox) {
      const glm::vec2 o = worley2_feature_offset(wrap_index(ix + ox, period.x),
                                                 wrap_index(iy + oy, period.y), seed);
      const float dx = f.x - (float(ox) + o.x);
      const float dy = f.y - (float(oy) + o.y);
      best = std::min(best, dx * dx + dy * dy);
    }
  }
  return std::sqrt(best);
}

}  // namespace skybake
