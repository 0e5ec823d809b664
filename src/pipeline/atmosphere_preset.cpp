// The planet and atmosphere sections of a scene preset into an Atmosphere:
// km -> m, each component checked on its own (preset_loader.cpp calls it).
#include "pipeline/atmosphere_preset.hpp"

#include <cmath>
#include <set>

#include <fmt/format.h>

namespace skybake::preset {

using nlohmann::json;

double number(const json& obj, const std::string& key, const Source& src, const std::string& at) {
  const double x = obj.at(key).get<double>();
  if (!std::isfinite(x)) src.fail(at + token(key), "must be a finite number");
  return x;
}

glm::dvec3 rgb(const json& obj, const std::string& key, const Source& src, const std::string& at) {
  if (!obj.contains(key)) return glm::dvec3(0.0);
  glm::dvec3 c;
  for (int i = 0; i < 3; ++i) {
    c[i] = obj.at(key).at(i).get<double>();
    if (!std::isfinite(c[i]) || c[i] < 0.0)
      src.fail(at + token(key) + token(i), "must be a finite number >= 0");
  }
  return c;
}

namespace {

DensityProfile density_from(const json& d, const Source& src, const std::string& at) {
  if (d.contains("exponential")) {
    const std::string p = at + "/exponential";
    const double h_km = number(d["exponential"], "scale_height_km", src, p);
    if (!(h_km > 0.0)) src.fail(p + "/scale_height_km", fmt::format("must be > 0, got {}", h_km));
    return exponential_profile(h_km * 1e3);
  }
  if (d.contains("tent")) {
    const std::string p = at + "/tent";
    const double b = number(d["tent"], "bottom_km", src, p);
    const double c = number(d["tent"], "center_km", src, p);
    const double t = number(d["tent"], "top_km", src, p);
    if (!(b < c))
      src.fail(p + "/center_km",
               fmt::format("must be greater than bottom_km ({} <= {})",
                           d["tent"]["center_km"].dump(), d["tent"]["bottom_km"].dump()));
    if (!(c < t))
      src.fail(p + "/top_km",
               fmt::format("must be greater than center_km ({} <= {})", d["tent"]["top_km"].dump(),
                           d["tent"]["center_km"].dump()));
    return tent_profile(b * 1e3, c * 1e3, t * 1e3);
  }
  if (d.contains("uniform")) {
    const std::string p = at + "/uniform";
    const double b = number(d["uniform"], "bottom_km", src, p);
    const double t = number(d["uniform"], "top_km", src, p);
    if (!(b < t))
      src.fail(p + "/top_km",
               fmt::format("must be greater than bottom_km ({} <= {})",
                           d["uniform"]["top_km"].dump(), d["uniform"]["bottom_km"].dump()));
    return uniform_profile(b * 1e3, t * 1e3);
  }
  // "layers": the schema guarantees exactly one form.
  DensityProfile profile;
  const json& layers = d.at("layers");
  for (size_t i = 0; i < layers.size(); ++i) {
    const std::string p = at + "/layers" + token(i);
    DensityLayer l;
    l.width_m = number(layers[i], "width_km", src, p) * 1e3;
    l.exp_term = number(layers[i], "exp_term", src, p);
    l.exp_scale_per_m = number(layers[i], "exp_scale_per_km", src, p) * 1e-3;
    l.linear_term_per_m = number(layers[i], "linear_term_per_km", src, p) * 1e-3;
    l.constant_term = number(layers[i], "constant_term", src, p);
    profile.layers.push_back(l);
  }
  return profile;
}

PhaseKind phase_from(const std::string& name) {
  if (name == "rayleigh") return PhaseKind::rayleigh;
  if (name == "cornette_shanks") return PhaseKind::cornette_shanks;
  if (name == "henyey_greenstein") return PhaseKind::henyey_greenstein;
  return PhaseKind::none;
}

// Adds a component unless its coefficients are all zero (it would cost time
// and change nothing).
void add_component(Atmosphere& atm, MediumComponent c) {
  if (c.scattering_per_m == glm::dvec3(0.0) && c.absorption_per_m == glm::dvec3(0.0)) return;
  atm.components.push_back(std::move(c));
}

MediumComponent component_from(const std::string& name, const json& j, PhaseKind default_phase,
                               const Source& src, const std::string& at) {
  MediumComponent c;
  c.name = name;
  c.scattering_per_m = rgb(j, "scattering_per_m", src, at);
  c.absorption_per_m = rgb(j, "absorption_per_m", src, at);
  c.phase = j.contains("phase") ? phase_from(j["phase"].get<std::string>()) : default_phase;
  c.g = j.contains("g") ? number(j, "g", src, at) : 0.0;
  if (!(c.g > -1.0 && c.g < 1.0))
    src.fail(at + "/g", fmt::format("must be in (-1, 1), got {}", c.g));
  c.density = density_from(j.at("density"), src, at + "/density");
  return c;
}

void check_top_radius(const json& planet, const Source& psrc, const json& atm, const Source& asrc) {
  const double rb = number(planet, "radius_km", psrc, "");
  const double rt = number(atm, "top_radius_km", asrc, "");
  if (rt > rb) return;
  const std::string values = atm["top_radius_km"].dump() + " <= " + planet["radius_km"].dump();
  if (psrc.file == asrc.file)
    asrc.fail("/top_radius_km",
              fmt::format("must be greater than {}/radius_km ({})", psrc.prefix, values));
  asrc.fail("/top_radius_km", fmt::format("must be greater than the planet's radius_km in {} ({})",
                                          psrc.file, values));
}

}  // namespace

// The components of `atm` into `a`, each checked on its own.
void add_components(Atmosphere& a, const json& atm, const Source& asrc, Problems& problems) {
  if (atm.contains("rayleigh"))
    problems.collect([&] {
      add_component(
          a, component_from("rayleigh", atm["rayleigh"], PhaseKind::rayleigh, asrc, "/rayleigh"));
    });
  if (atm.contains("mie"))
    problems.collect([&] {
      add_component(a,
                    component_from("mie", atm["mie"], PhaseKind::cornette_shanks, asrc, "/mie"));
    });
  if (atm.contains("ozone"))
    problems.collect([&] {
      add_component(a, component_from("ozone", atm["ozone"], PhaseKind::none, asrc, "/ozone"));
    });
  std::set<std::string> names = {"rayleigh", "mie", "ozone"};
  const json extra = atm.value("extra", json::array());
  for (size_t i = 0; i < extra.size(); ++i)
    problems.collect([&] {
      const std::string at = "/extra" + token(i);
      const std::string name = extra[i]["name"].get<std::string>();
      if (!names.insert(name).second)
        asrc.fail(at + "/name", fmt::format("component name '{}' is already used", name));
      MediumComponent c = component_from(name, extra[i], PhaseKind::none, asrc, at);
      if (c.phase == PhaseKind::none && c.scattering_per_m != glm::dvec3(0.0))
        asrc.fail(at + "/phase",
                  "a component that scatters needs a phase function (scattering_per_m is not "
                  "zero)");
      add_component(a, std::move(c));
    });
}

Atmosphere atmosphere_from(const json& planet, const Source& psrc, const json& atm,
                           const Source& asrc, Problems& problems) {
  problems.collect([&] { check_top_radius(planet, psrc, atm, asrc); });
  Atmosphere a;
  problems.collect([&] {
    a.bottom_radius_m = number(planet, "radius_km", psrc, "") * 1e3;
    a.top_radius_m = number(atm, "top_radius_km", asrc, "") * 1e3;
    a.ground_albedo = rgb(planet, "ground_albedo", psrc, "");
    a.sun_illuminance = rgb(atm["sun"], "illuminance", asrc, "/sun");
    a.sun_angular_radius_rad = number(atm["sun"], "angular_radius_rad", asrc, "/sun");
  });
  add_components(a, atm, asrc, problems);
  return a;
}


}  // namespace skybake::preset
