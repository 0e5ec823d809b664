// Perlin-Worley noise: Perlin fBm dilated by an inverted-Worley fBm, the
// "cauliflower" base shape of the cloud noise (Schneider, GPU Pro 7 sec. 4.3.1,
// figure 4.7; Frostbite 2016 sec. 5.4 and Appendix D).
//
// The papers disagree on the remap, so the variant is a named option
// (docs/reference.md "Cloud noise"). With perlin01 = Perlin fBm * 0.5 + 0.5 clamped
// to [0, 1], w = the Worley fBm in [0, 1], and
// remap(v, lo, hi, new_lo, new_hi) = new_lo + (v - lo) / (hi - lo) * (new_hi - new_lo):
//
//   worley_new_min (default)  remap(perlin01, 0, 1, w, 1) = w + perlin01 (1 - w).
//       The code Frostbite's Appendix D points to (TileableVolumeNoise, main.cpp),
//       whose author reads it as the GPU Pro text; the Worley billows lift the
//       Perlin floor, as in figure 4.7. Always in [w, 1]: no clamp, no division.
//   worley_old_min            saturate(remap(perlin01, w, 1, 0, 1)): the GPU Pro 7
//       sec. 4.3.1 text read literally ("OldMin = Worley_FBM"); carves the
//       Perlin noise wherever the Worley fBm exceeds it.
//   dilate                    remap(perlin01, -(1 - w), 1, 0, 1)
//       = (perlin01 + 1 - w) / (2 - w): the dilation of the GPU Pro 7 sampler
//       (sec. 4.3.4, base_cloud) with the negative old minimum that
//       TileableVolumeNoise uses for its packed shape; in [0, 1] without clamp.
#pragma once

#include <algorithm>
#include <optional>
#include <string>

namespace skybake {

enum class PerlinWorleyRemap { worley_new_min, worley_old_min, dilate };

// "worley_new_min", "worley_old_min", "dilate": the names presets and
// metadata use.
const char* remap_name(PerlinWorleyRemap remap);
std::optional<PerlinWorleyRemap> remap_from_name(const std::string& name);

// perlin_fbm: a Perlin fBm value (about [-1, 1]); worley_fbm: an inverted
// Worley fBm value in [0, 1]. Result in [0, 1]. Inline: the shape baker calls
// it for every voxel.
inline float perlin_worley(float perlin_fbm, float worley_fbm, PerlinWorleyRemap remap) {
  const float p = std::clamp(perlin_fbm * 0.5f + 0.5f, 0.0f, 1.0f);
  const float w = std::clamp(worley_fbm, 0.0f, 1.0f);
  switch (remap) {
    case PerlinWorleyRemap::worley_new_min:
      return std::min(w + p * (1.0f - w), 1.0f);  // min: rounding only
    case PerlinWorleyRemap::worley_old_min:
      // Where w reaches 1 the old range is empty; p <= 1 = w gives 0 (carved).
      return w >= 1.0f ? 0.0f : std::clamp((p - w) / (1.0f - w), 0.0f, 1.0f);
    case PerlinWorleyRemap::dilate:
      return std::min((p + 1.0f - w) / (2.0f - w), 1.0f);
  }
  return 0.0f;
}

}  // namespace skybake
