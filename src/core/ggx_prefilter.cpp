#include "core/ggx_prefilter.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/cube_map.hpp"
#include "core/math.hpp"
#include "core/mip_chain.hpp"

namespace skybake {

namespace {

// Van der Corput's radical inverse in base 2: the Hammersley set's second axis.
double ggx_radical_inverse(unsigned i) {
  i = (i << 16u) | (i >> 16u);
  i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
  i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
  i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
  i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
  return double(i) * 2.3283064365386963e-10;
}

// Trilinear read of the box chain at a fractional level.
glm::dvec3 ggx_chain_read(const std::vector<Texture>& chain, int cube, glm::dvec3 d, double lod) {
  const double top = double(chain.size() - 1);
  lod = std::clamp(lod, 0.0, top);
  const int l0 = std::min(int(lod), int(chain.size()) - 1);
  const int l1 = std::min(l0 + 1, int(chain.size()) - 1);
  const double f = lod - l0;
  const CubeCoord at = cube_coord(d);
  const glm::dvec3 a = sample_cube(chain[l0], cube, at);
  return f > 0.0 ? a * (1.0 - f) + sample_cube(chain[l1], cube, at) * f : a;
}

}  // namespace

double ggx_level_roughness(int level, int levels) {
  return levels > 1 ? double(level) / double(levels - 1) : 0.0;
}

double ggx_distribution(double cos_h, double alpha) {
  const double a2 = alpha * alpha;
  const double q = cos_h * cos_h * (a2 - 1.0) + 1.0;
  return a2 / (kPi * q * q);
}

std::vector<GgxSample> ggx_samples(double alpha, int samples, int face) {
  const double texel_solid_angle = 4.0 * kPi / (kCubeFaces * double(face) * double(face));
  const double a2 = alpha * alpha;
  std::vector<GgxSample> out(size_t(std::max(samples, 0)));
  for (int i = 0; i < samples; ++i) {
    const double u = (i + 0.5) / samples, v = ggx_radical_inverse(unsigned(i));
    const double phi = 2.0 * kPi * v;
    GgxSample& s = out[size_t(i)];
    s.cos_h = std::sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
    s.sin_h = std::sqrt(std::max(0.0, 1.0 - s.cos_h * s.cos_h));
    s.cos_phi = std::cos(phi);
    s.sin_phi = std::sin(phi);
    const double pdf = ggx_distribution(s.cos_h, alpha) / 4.0;  // of l, with V = N
    const double sample_solid_angle = 1.0 / (samples * pdf);
    s.lod = std::max(0.0, 0.5 * std::log2(sample_solid_angle / texel_solid_angle));
  }
  return out;
}

glm::dvec3 ggx_prefiltered_radiance(const std::vector<Texture>& box_chain, int cube, glm::dvec3 n,
                                    const std::vector<GgxSample>& samples) {
  const glm::dvec3 helper = std::abs(n.z) < 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 tx = glm::normalize(glm::cross(helper, n));
  const glm::dvec3 ty = glm::cross(n, tx);
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (const GgxSample& s : samples) {
    const glm::dvec3 h = (s.cos_phi * tx + s.sin_phi * ty) * s.sin_h + s.cos_h * n;
    const glm::dvec3 l = 2.0 * s.cos_h * h - n;
    const double n_l = glm::dot(n, l);
    if (n_l <= 0.0) continue;
    sum += n_l * ggx_chain_read(box_chain, cube, l, s.lod);
    weight += n_l;
  }
  return weight > 0.0 ? sum / weight : glm::dvec3(0.0);
}

std::vector<Texture> ggx_prefilter_levels(const Texture& level0, int levels, int samples,
                                          bool z_mirror) {
  const std::vector<Texture> box = build_mip_chain(level0, MipEdge::clamp);
  std::vector<Texture> out;
  for (int m = 1; m < levels; ++m) {
    Texture level = box[size_t(m)];  // shape, channels and any channel past the third
    const double r = ggx_level_roughness(m, levels);
    const std::vector<GgxSample> set = ggx_samples(r * r, samples, box[0].width);
    const int n = level.width;
    tbb::parallel_for(0, level.layers * n, [&](int row) {
      const int layer = row / n, j = row % n;
      for (int i = 0; i < n; ++i) {
        if (z_mirror && !cube_texel_in_z_half(layer % kCubeFaces, i, j, n)) continue;
        const glm::dvec3 d = cube_texel_direction(layer % kCubeFaces, i, j, n);
        const glm::dvec3 p = ggx_prefiltered_radiance(box, layer / kCubeFaces, d, set);
        for (int c = 0; c < std::min(3, level.channel_count()); ++c)
          level.at(i, j, 0, layer, c) = float(p[c]);
      }
    });
    if (z_mirror) fill_z_mirrors(level);
    out.push_back(std::move(level));
  }
  return out;
}

}  // namespace skybake
