#include "pipeline/spectral_preset.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "atmosphere/spectral_medium.hpp"
#include "core/math.hpp"
#include "core/spectral_data.hpp"
#include "pipeline/product.hpp"

namespace skybake::preset {

using nlohmann::json;

namespace {

struct SampledSpectrum {
  std::vector<double> nm, values;
  double operator()(double l) const {
    if (l <= nm.front()) return values.front();
    if (l >= nm.back()) return values.back();
    const size_t i = size_t(std::upper_bound(nm.begin(), nm.end(), l) - nm.begin()) - 1;
    const double f = (l - nm[i]) / (nm[i + 1] - nm[i]);
    return values[i] * (1.0 - f) + values[i + 1] * f;
  }
};

// A "spectral_table" object's key (values or absorption) as a spectrum.
// `absorption` is the Mie table's only; an albedo is at most 1.
SpectrumFn table_from(const json& t, const char* key, const Source& src, const std::string& at) {
  if (t.contains("absorption") && at != "/spectrum/mie/table")
    src.fail(at + "/absorption", "applies to the mie table only (sigma_a beside its sigma_s)");
  SampledSpectrum s;
  s.nm = t.at("wavelengths_nm").get<std::vector<double>>();
  s.values = t.contains(key) ? t[key].get<std::vector<double>>() : std::vector<double>(s.nm.size());
  for (size_t i = 1; i < s.nm.size(); ++i)
    if (!(s.nm[i] > s.nm[i - 1]))
      src.fail(at + "/wavelengths_nm" + token(i),
               fmt::format("must be greater than the wavelength before it ({} <= {})", s.nm[i],
                           s.nm[i - 1]));
  if (s.values.size() != s.nm.size())
    src.fail(at + token(key), fmt::format("expected {} values, one per wavelength, got {}",
                                          s.nm.size(), s.values.size()));
  if (at == "/spectrum/ground_albedo/table")
    for (size_t i = 0; i < s.values.size(); ++i)
      if (s.values[i] > 1.0)
        src.fail(at + "/values" + token(i), fmt::format("must be an albedo <= 1, got {}", s.values[i]));
  return s;
}

const MediumComponent& component_for(const Atmosphere& a, const std::string& name,
                                     const Source& src, const std::string& at) {
  for (const MediumComponent& c : a.components)
    if (c.name == name) return c;
  src.fail(at, fmt::format("needs the atmosphere's '{}' component (its density profile), which "
                           "is absent or zero",
                           name));
}

SpectrumFn sun_from(const json& sun, const Source& src) {
  if (sun.contains("constant")) {
    const double v = sun["constant"]["irradiance_w_m2_nm"].get<double>();
    return [v](double) { return v; };
  }
  if (sun.contains("table")) return table_from(sun["table"], "values", src, "/spectrum/sun/table");
  const double scale = sun.contains("astm_g173") ? sun["astm_g173"].value("scale", 1.0) : 1.0;
  return [scale](double nm) { return scale * astm_g173_solar_irradiance(nm); };
}

// Rayleigh scattering of air from its molecular constants (docs/reference.md
// "Spectral skies"): the refractive index of standard air (Peck & Reeder
// 1972), n - 1 proportional to the number density.
double rayleigh_molecular(double nm, double number_density, double depolarization) {
  constexpr double kStandardAirPerM3 = 2.547e25;
  const double s2 = std::pow(1000.0 / nm, 2.0);  // (1 / lambda in um)^2
  const double n1 = (8060.51 + 2480990.0 / (132.274 - s2) + 17455.7 / (39.32957 - s2)) * 1e-8 *
                    number_density / kStandardAirPerM3;
  const double n2m1 = n1 * (2.0 + n1);  // n^2 - 1
  const double lambda = nm * 1e-9;
  return 8.0 * std::pow(kPi, 3) * n2m1 * n2m1 / (3.0 * number_density * std::pow(lambda, 4)) *
         (6.0 + 3.0 * depolarization) / (6.0 - 7.0 * depolarization);
}

ComponentSpectrum rayleigh_from(const json& r, const Source& src) {
  if (r.contains("table")) return {table_from(r["table"], "values", src, "/spectrum/rayleigh/table"), {}};
  if (r.contains("molecular")) {
    const double n = r["molecular"].value("number_density_per_m3", 2.547e25);
    const double rho = r["molecular"].value("depolarization", 0.0279);
    return {[n, rho](double nm) { return rayleigh_molecular(nm, n, rho); },
            [](double) { return 0.0; }};
  }
  const json& p = r.at("power_law");
  const double s = p["scattering_per_m"].get<double>();
  const double ref = p.value("reference_nm", 1000.0), e = p.value("exponent", 4.0);
  return {[s, ref, e](double nm) { return s * std::pow(nm / ref, -e); },
          [](double) { return 0.0; }};
}

ComponentSpectrum mie_from(const json& m, const MediumComponent& mie, const Atmosphere& a,
                           const Source& src) {
  if (m.contains("table"))
    return {table_from(m["table"], "values", src, "/spectrum/mie/table"),
            table_from(m["table"], "absorption", src, "/spectrum/mie/table")};
  const json& p = m.at("angstrom");
  const double column = profile_column_m(mie.density, a.top_radius_m - a.bottom_radius_m);
  if (!(column > 0.0))
    src.fail("/spectrum/mie/angstrom", "needs a Mie density profile that is not zero");
  const double alpha = p["exponent"].get<double>(), beta = p["turbidity"].get<double>();
  const double albedo = p.value("single_scattering_albedo", 0.9);
  auto extinction = [alpha, beta, column](double nm) {
    return beta * std::pow(nm / 1000.0, -alpha) / column;
  };
  return {[extinction, albedo](double nm) { return albedo * extinction(nm); },
          [extinction, albedo](double nm) { return (1.0 - albedo) * extinction(nm); }};
}

ComponentSpectrum ozone_from(const json& o, const MediumComponent& ozone, const Atmosphere& a,
                             const Source& src) {
  if (o.contains("table"))
    return {[](double) { return 0.0; }, table_from(o["table"], "values", src, "/spectrum/ozone/table")};
  const double column = profile_column_m(ozone.density, a.top_radius_m - a.bottom_radius_m);
  if (!(column > 0.0))
    src.fail("/spectrum/ozone/column", "needs an ozone density profile that is not zero");
  const double peak_per_m3 = o["column"]["dobson"].get<double>() * kDobsonUnitPerM2 / column;
  return {[](double) { return 0.0; },
          [peak_per_m3](double nm) { return peak_per_m3 * ozone_cross_section_m2(nm); }};
}

void add_component_laws(SpectralMedium& m, const json& spec, const Source& src,
                        const Atmosphere& a, Problems& problems) {
  if (spec.contains("rayleigh"))
    problems.collect([&] {
      component_for(a, "rayleigh", src, "/spectrum/rayleigh");
      m.components["rayleigh"] = rayleigh_from(spec["rayleigh"], src);
    });
  if (spec.contains("mie"))
    problems.collect([&] {
      const MediumComponent& c = component_for(a, "mie", src, "/spectrum/mie");
      m.components["mie"] = mie_from(spec["mie"], c, a, src);
    });
  if (spec.contains("ozone"))
    problems.collect([&] {
      const MediumComponent& c = component_for(a, "ozone", src, "/spectrum/ozone");
      m.components["ozone"] = ozone_from(spec["ozone"], c, a, src);
    });
}

}  // namespace

std::shared_ptr<const SpectralScene> spectral_from(const json& spectral, const json& atm,
                                                   const Source& asrc, const Atmosphere& a,
                                                   Problems& problems) {
  auto s = std::make_shared<SpectralScene>();
  s->wavelengths = spectral.value("wavelengths", 15);
  if (spectral.value("sampling", std::string("visible")) == "uniform")
    s->sampling = SpectralSampling::uniform;
  if (spectral.value("colour_space", std::string("rec709")) == "acescg")
    s->colour_space = ColourSpace::acescg;
  const std::string units = spectral.value("units", std::string("relative"));
  s->units = units == "photometric"   ? SpectralUnits::photometric
             : units == "radiometric" ? SpectralUnits::radiometric
                                      : SpectralUnits::relative;
  const json spec = atm.value("spectrum", json::object());
  const size_t before = problems.size();
  problems.collect([&] { s->medium.sun_w_m2_nm = sun_from(spec.value("sun", json::object()), asrc); });
  add_component_laws(s->medium, spec, asrc, a, problems);
  if (spec.contains("ground_albedo"))
    problems.collect([&] {
      const json& g = spec["ground_albedo"];
      if (g.contains("constant")) {
        const double v = g["constant"].get<double>();
        s->medium.ground_albedo = [v](double) { return v; };
      } else {
        s->medium.ground_albedo = table_from(g["table"], "values", asrc, "/spectrum/ground_albedo/table");
      }
    });
  if (problems.size() != before) return nullptr;
  return s;
}

namespace {

bool spectral_reads_atmosphere(const std::string& product) {
  const ProductInfo* p = find_product(product);
  if (!p) return false;
  return std::find(p->scene_sections.begin(), p->scene_sections.end(), "atmosphere") !=
         p->scene_sections.end();
}

}  // namespace

void check_spectral_outputs(const json& spectral, const std::vector<OutputSpec>& outputs,
                            const Source& scene_src, Problems& problems) {
  if (spectral.value("units", std::string("relative")) != "photometric") return;
  for (const OutputSpec& o : outputs)
    if (o.precision == "half" && spectral_reads_atmosphere(o.product))
      problems.add(scene_src, o.pointer + "/precision",
                   "must be \"float\" with spectral units \"photometric\" (the sun's 1.28e5 lux "
                   "passes half's 65504; units \"radiometric\" are luminance / 683 and fit)");
}

void load_spectral(Scene& scene, const json& doc, const Source& asrc, const Source& scene_src,
                   bool atmosphere_read, Problems& problems) {
  if (!doc.contains("spectral")) return;
  check_spectral_outputs(doc["spectral"], scene.outputs, scene_src, problems);
  if (!scene.has_atmosphere || !atmosphere_read) return;
  scene.spectral = spectral_from(doc["spectral"], doc["atmosphere"], asrc, scene.atmosphere, problems);
  // The sun a spectral table is lit by, in the tables' colour space and units.
  if (scene.spectral) scene.atmosphere.sun_illuminance = scene.spectral->sun_colour();
}

}  // namespace skybake::preset
