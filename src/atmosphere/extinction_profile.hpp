// sigma_t(h) of an atmosphere's components laid out for the inner loop of
// the transmittance quadrature (atmosphere/transmittance_lut.cpp): the sum
// over quadrature nodes of weight times extinction.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"

namespace skybake {

// Whether the quadrature samples component c: every component with
// extinction, except, when `closed_form_linear` is set, those whose profile
// is piecewise linear (a LinearLayerDepth integrates them).
bool integrated_by_quadrature(const MediumComponent& c, bool closed_form_linear);

// How exp is evaluated at the nodes: std::exp (bit-identical to
// extinction_at) or exp_block (core/kernels/exp_block.hpp, within 3e-16
// relative, over lanes), the table's.
enum class NodeExp { libm, block };

class ExtinctionProfile {
 public:
  // The components integrated_by_quadrature(c, closed_form_linear) selects;
  // each component's sigma_t = sigma_s + sigma_a summed once and its layer
  // tops accumulated once.
  ExtinctionProfile(const Atmosphere& atm, bool closed_form_linear, NodeExp exp_kind);

  bool empty() const { return components_.empty(); }

  // sum_j w[j] sigma_t(h[j]) over the selected components: per component,
  // its density at each h (the first layer whose top lies above h, the last
  // has none, its formula clamped to [0, 1] as medium.cpp density_at does)
  // summed with the weights, times its sigma_t once. A component of one
  // layer (every exponential profile the helpers build) needs no search.
  // With NodeExp::libm the arithmetic per sample is extinction_at's, term
  // for term, so the sums are bit-identical to it.
  glm::dvec3 integrate(const std::vector<double>& h, const std::vector<double>& w,
                       std::vector<double>& density) const;

 private:
  struct Layer {
    double top;  // the altitude where the next layer starts; +inf for the last
    DensityLayer layer;
  };
  struct Component {
    glm::dvec3 sigma_t;
    size_t first_layer, layer_count;
    NodeExp exp_kind;  // libm where an exponent could leave exp_block's range
    bool unclamped_exponential;  // NodeExp::block on a exp(b h) that never clamps
  };
  std::vector<Layer> layers_;
  std::vector<Component> components_;
  size_t unclamped_count_ = 0;  // components with unclamped_exponential set
};

}  // namespace skybake
