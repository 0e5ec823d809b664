// Precomputed scattering products (docs/reference.md, "Precomputed
// scattering"): Bruneton's 4D scattering with
// its irradiance and single-Mie companions, and the azimuth-free 3D variant
// with its gathering LUT. One bake_bruneton() / bake_scattering3d() call makes
// all the textures of its family; the companions depend on the main product
// in the graph and take their texture from a per-process cache keyed by the
// main product's inputs, so a scene that writes several of them bakes once.
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "atmosphere/scattering3d_lut.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/error.hpp"
#include "core/hash.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/bruneton_families.hpp"
#include "pipeline/error_measures.hpp"
#include "pipeline/product_graph.hpp"
#include "pipeline/product_options.hpp"
#include "pipeline/product_tables.hpp"

namespace skybake {

BrunetonSpec bruneton_spec(const OutputSpec& spec) {
  BrunetonSpec b;
  b.r_size = spec.size.at(0);
  b.mu_size = spec.size.at(1);
  b.mu_s_size = spec.size.at(2);
  b.nu_size = spec.size.at(3);
  b.mu_s_min = std::cos(option_double(spec, "mu_s_min_deg", 102.0) * kPi / 180.0);
  b.orders = option_int(spec, "orders", b.orders);
  b.tolerance = option_double(spec, "tolerance", 0.0);
  b.max_orders = option_int(spec, "max_orders", b.max_orders);
  b.geometric_tail = option_string(spec, "tail", "geometric") == "geometric";
  b.combined_mie_alpha = option_string(spec, "mie", "alpha") == "alpha";
  return b;
}

Scattering3dSpec scattering3d_spec(const OutputSpec& spec) {
  Scattering3dSpec s;
  s.height_size = spec.size.at(0);
  s.view_size = spec.size.at(1);
  s.sun_size = spec.size.at(2);
  s.orders = option_int(spec, "orders", s.orders);
  s.tolerance = option_double(spec, "tolerance", 0.0);
  s.max_orders = option_int(spec, "max_orders", s.max_orders);
  s.geometric_tail = option_string(spec, "tail", "geometric") == "geometric";
  s.combined_mie_alpha = option_string(spec, "mie", "alpha") == "alpha";
  return s;
}

namespace {

// The scene's own output of `product`, or that product's defaults.
OutputSpec spec_of(const Scene& scene, const std::string& product) {
  if (const OutputSpec* s = scene.find_output(product)) return *s;
  return default_spec(*find_product(product));
}

// Cache of whole families by the inputs that determine them.
template <typename Textures>
class FamilyCache {
 public:
  template <typename Bake>
  std::shared_ptr<const Textures> get(const std::string& key, Bake bake) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = cache_.find(key);
      if (it != cache_.end()) return it->second;
    }
    auto made = std::make_shared<const Textures>(bake());
    std::lock_guard<std::mutex> lock(mutex_);
    cache_[key] = made;
    return made;
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    cache_.clear();
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const Textures>> cache_;
};

FamilyCache<BrunetonTextures>& bruneton_cache() {
  static FamilyCache<BrunetonTextures> cache;
  return cache;
}
FamilyCache<Scattering3dTextures>& scattering3d_cache() {
  static FamilyCache<Scattering3dTextures> cache;
  return cache;
}

std::string family_key(const Scene& scene, const OutputSpec& spec) {
  Hasher h;
  for (const std::string& s : kAtmosphereSections)
    h.add(scene.resolved.contains(s) ? scene.resolved[s].dump() : "null");
  for (int v : spec.size) h.add(std::to_string(v));
  return h.add(spec.options.dump()).hex();
}

}  // namespace

std::shared_ptr<const BrunetonTextures> bruneton_family(const Scene& scene, const ProductInputs& in,
                                                        const BakeContext& ctx) {
  const OutputSpec spec = spec_of(scene, "scattering");
  const OutputSpec irradiance = spec_of(scene, "irradiance");
  BrunetonSpec b = bruneton_spec(spec);
  b.irradiance_width = irradiance.size.at(0);
  b.irradiance_height = irradiance.size.at(1);
  const std::string key = family_key(scene, spec) + "/" + std::to_string(b.irradiance_width) + "x" +
                          std::to_string(b.irradiance_height);
  return bruneton_cache().get(
      key, [&] { return bake_bruneton(scene.atmosphere, *in.at("transmittance"), b, ctx); });
}

std::shared_ptr<const Scattering3dTextures> scattering3d_family(const Scene& scene,
                                                                const ProductInputs& in,
                                                                const BakeContext& ctx) {
  const OutputSpec spec = spec_of(scene, "scattering3d");
  return scattering3d_cache().get(family_key(scene, spec), [&] {
    return bake_scattering3d(scene.atmosphere, *in.at("transmittance"), scattering3d_spec(spec),
                             ctx);
  });
}

void forget_families() {
  bruneton_cache().clear();
  scattering3d_cache().clear();
}

namespace {

// Companions receive the main product's texture as an input but need the
// transmittance LUT to re-bake on a cache miss: they depend on both.
Texture bake_scattering(const Scene& s, const OutputSpec&, const ProductInputs& in,
                        const BakeContext& ctx) {
  return bruneton_family(s, in, ctx)->scattering;
}
Texture bake_single_mie(const Scene& s, const OutputSpec&, const ProductInputs& in,
                        const BakeContext& ctx) {
  return bruneton_family(s, in, ctx)->single_mie;
}
Texture bake_irradiance(const Scene& s, const OutputSpec& spec, const ProductInputs& in,
                        const BakeContext& ctx) {
  const auto family = bruneton_family(s, in, ctx);
  if (!spec.options.value("include_direct", false)) return family->irradiance;
  Texture sum = family->irradiance;
  for (size_t i = 0; i < sum.data.size(); ++i) sum.data[i] += family->direct_irradiance.data[i];
  set_meta(sum.metadata, "quantity", std::string("direct + indirect ground irradiance"));
  return sum;
}
Texture bake_scattering3d_product(const Scene& s, const OutputSpec&, const ProductInputs& in,
                                  const BakeContext& ctx) {
  return scattering3d_family(s, in, ctx)->scattering;
}
Texture bake_gathering_sum(const Scene& s, const OutputSpec&, const ProductInputs& in,
                           const BakeContext& ctx) {
  return scattering3d_family(s, in, ctx)->gathering_sum;
}

// single_mie and gathering_sum come out of their family's bake at the
// family's size: a size of their own would be silently ignored, so refuse it.
CheckFn size_follows(std::string family, std::vector<int> default_size) {
  return [family, default_size](const OutputSpec& spec) -> std::vector<ProductProblem> {
    if (spec.size == default_size) return {};
    return {{"/size", "the size follows the " + family +
                          " output (one bake makes both); remove \"size\" here and set it there"}};
  };
}

}  // namespace

// The bakers' own spec checks ("expected X, got Y"), run at preset load.
template <typename Spec, Spec (*make)(const OutputSpec&), void (*check)(const Spec&)>
std::vector<ProductProblem> spec_rules(const OutputSpec& spec) {
  try {
    check(make(spec));
  } catch (const Error& e) {
    return {{"", e.what()}};
  }
  return {};
}

void add_bruneton_products(std::vector<ProductInfo>& r) {
  ProductInfo scattering = atmosphere_lut_product(
      "scattering",
      "Bruneton 4D (r, mu, mu_s, nu) single + multiple scattering packed in 3D, Mie in alpha",
      {"r", "mu", "mu_s", "nu"}, {32, 128, 32, 8}, {128, 512, 128, 32}, {"transmittance"},
      bake_scattering, 6300.0);
  scattering.check = spec_rules<BrunetonSpec, bruneton_spec, check_bruneton_spec>;
  scattering.measure_error = measure_scattering_error;
  r.push_back(std::move(scattering));
  ProductInfo single_mie = atmosphere_lut_product(
      "single_mie", "single Mie scattering of the 4D table (with \"mie\": \"separate\")",
      {"r", "mu", "mu_s", "nu"}, {32, 128, 32, 8}, {128, 512, 128, 32},
      {"transmittance", "scattering"}, bake_single_mie, 1.0);
  single_mie.check = size_follows("scattering", single_mie.default_size);
  single_mie.measure_error = measure_single_mie_error;
  r.push_back(std::move(single_mie));
  ProductInfo irradiance = atmosphere_lut_product(
      "irradiance", "ground irradiance (mu_s, r) of the 4D model: indirect, or + direct",
      {"mu_s", "r"}, {64, 16}, {1024, 1024}, {"transmittance", "scattering"}, bake_irradiance,
      1.0);
  irradiance.measure_error = measure_irradiance_error;
  r.push_back(std::move(irradiance));
  ProductInfo scattering3d = atmosphere_lut_product(
      "scattering3d",
      "azimuth-free (height, view zenith, sun zenith) scattering with gathering (Elek/Frostbite)",
      {"height", "view", "sun"}, {32, 128, 32}, {128, 512, 128}, {"transmittance"},
      bake_scattering3d_product, 7800.0);
  scattering3d.check = spec_rules<Scattering3dSpec, scattering3d_spec, check_scattering3d_spec>;
  scattering3d.measure_error = measure_scattering3d_error;
  r.push_back(std::move(scattering3d));
  ProductInfo gathering = atmosphere_lut_product(
      "gathering_sum", "gathering LUT of the 3D model, sum over orders (height, sun zenith)",
      {"height", "sun"}, {32, 32}, {128, 128}, {"transmittance", "scattering3d"},
      bake_gathering_sum, 1.0);
  gathering.check = size_follows("scattering3d", gathering.default_size);
  gathering.measure_error = measure_gathering_sum_error;
  r.push_back(std::move(gathering));
}

}  // namespace skybake
