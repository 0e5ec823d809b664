#include "core/tiling_rgba.hpp"

#include <algorithm>
#include <cstddef>

#include "core/kernels/tiling_rgba.hpp"

namespace skybake {

std::vector<TilingProfiles> compute_tiling_profiles_rgba(const Texture& t, int layer, int axis) {
  const int n[3] = {t.width, t.height, t.depth};
  const int len = n[axis];
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  const int lines = n[u_axis], planes = n[v_axis];
  std::vector<int> lags;
  for (int k : {2, 3, 4, 5})
    if (len / k >= 2 && std::find(lags.begin(), lags.end(), len / k) == lags.end())
      lags.push_back(len / k);
  const TilingRgbaSums sums = tiling_rgba_sums(t, layer, axis, lags);
  const double total = double(size_t(lines) * size_t(planes));
  std::vector<TilingProfiles> profiles(4);
  for (int c = 0; c < 4; ++c) {
    TilingProfiles& p = profiles[size_t(c)];
    const std::pair<std::vector<double>*, const std::vector<TexelChannels>*> parts[] = {
        {&p.jump, &sums.jump}, {&p.jump_side, &sums.jump_side},
        {&p.turn, &sums.turn}, {&p.turn_side, &sums.turn_side}};
    for (const auto& [out, in] : parts) {
      out->resize(size_t(len));
      for (int f = 0; f < len; ++f) (*out)[size_t(f)] = (*in)[size_t(f)].c[c] / total;
    }
    p.far = lags.empty() ? 0.0 : double(sums.far[c] / (total * len * lags.size()));
  }
  return profiles;
}

}  // namespace skybake
