// Error estimates recorded by every bake: the manifest holds each output's
// estimated error and the time it took (`estimated_error`). Each estimator
// recomputes a fixed, deterministic sample of texels with a much finer
// integration (the same integrand, 8-16x the steps or directions) and reports
// how far the baked texels are from it. This measures the discretisation
// error of the bake; `skybake report` measures the model error against
// independent references (adaptive quadrature, path tracing).
#pragma once

#include <nlohmann/json.hpp>

#include "pipeline/product.hpp"

namespace skybake {

// {"reference": text, "samples": n, "max_abs": x, "max_rel": x, "rms_rel": x}
// Relative errors divide by max(|ref|, 1e-3 * the largest |ref| sampled), so
// texels that are nearly black do not dominate.
nlohmann::json estimate_transmittance_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                            const Texture&);
nlohmann::json estimate_multiscattering_error(const Scene&, const OutputSpec&,
                                              const ProductInputs&, const Texture&);
nlohmann::json estimate_skyview_error(const Scene&, const OutputSpec&, const ProductInputs&,
                                      const Texture&);
nlohmann::json estimate_aerial_perspective_error(const Scene&, const OutputSpec&,
                                                 const ProductInputs&, const Texture&);

}  // namespace skybake
