#include "pipeline/runtime_metadata.hpp"

#include <fmt/format.h>

#include "atmosphere/table_convention.hpp"
#include "core/error.hpp"

namespace skybake {

namespace {

const char* phase_name(PhaseKind kind) {
  switch (kind) {
    case PhaseKind::none: return "none";
    case PhaseKind::rayleigh: return "rayleigh";
    case PhaseKind::cornette_shanks: return "cornette_shanks";
    case PhaseKind::henyey_greenstein: return "henyey_greenstein";
  }
  return "none";
}

bool is_mie(const MediumComponent& c) {
  return c.phase == PhaseKind::cornette_shanks || c.phase == PhaseKind::henyey_greenstein;
}

}  // namespace

void set_mie_phase_metadata(const Atmosphere& atm, Metadata& meta) {
  const MediumComponent* first = nullptr;
  bool mixed = false;
  for (const MediumComponent& c : atm.components) {
    if (!is_mie(c)) continue;
    if (!first) first = &c;
    mixed = mixed || c.phase != first->phase || c.g != first->g;
  }
  if (!first) {
    set_meta(meta, "mie_phase", "none");
    set_meta(meta, "mie_g", 0.0);
    return;
  }
  if (!mixed) {
    set_meta(meta, "mie_phase", phase_name(first->phase));
    set_meta(meta, "mie_g", first->g);
    return;
  }
  set_meta(meta, "mie_phase", "mixed");
  set_meta(meta, "mie_g", 0.0);
  for (const MediumComponent& c : atm.components) {
    if (c.phase == PhaseKind::none) continue;
    set_meta(meta, fmt::format("component.{}.phase", c.name), phase_name(c.phase));
    set_meta(meta, fmt::format("component.{}.g", c.name), c.g);
  }
}

void add_runtime_metadata(const Scene& scene, const ProductInfo& product, Texture& tex) {
  const Sampling& s = product.sampling;
  const size_t axes = tex.is_volume() ? 3 : 2;
  // A volume product baked one slice deep is a 2D texture: its first two.
  if (s.wrap.size() < axes)
    throw Error(fmt::format("{}: expected {} wrap modes for a {} texture, got {}", product.name,
                            axes, tex.shape_string(), s.wrap.size()));
  set_meta(tex.metadata, "filter", s.filter);
  const char* names[3] = {"wrap_u", "wrap_v", "wrap_w"};
  for (size_t a = 0; a < axes; ++a) set_meta(tex.metadata, names[a], s.wrap[a]);
  // Hillaire's demo samples every table with clamp to edge (samplerLinearClamp):
  // its sky-view azimuth runs over the half circle and does not wrap.
  if (table_convention_of(tex) == TableConvention::hillaire_demo)
    for (size_t a = 0; a < axes; ++a) set_meta(tex.metadata, names[a], std::string("clamp"));
  if (!product.atmosphere_table) return;
  set_meta(tex.metadata, "solar_irradiance", scene.atmosphere.sun_illuminance);
  if (product.reads_mie_phase) set_mie_phase_metadata(scene.atmosphere, tex.metadata);
}

}  // namespace skybake
