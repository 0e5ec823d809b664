// The product graph: requested products plus their dependency closure, hashes
// that change with the inputs that matter and not with those that don't.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"
#include "core/suggest.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

Scene earth() { return load_scene(test::source_path("presets/earth.json")); }

TEST(ProductGraph, RegistryDependenciesComeFirstAndExist) {
  const auto& reg = product_registry();
  for (size_t i = 0; i < reg.size(); ++i) {
    EXPECT_EQ(reg[i].axes.size(), reg[i].default_size.size()) << reg[i].name;
    EXPECT_EQ(reg[i].axes.size(), reg[i].max_size.size()) << reg[i].name;
    EXPECT_TRUE(reg[i].bake) << reg[i].name;
    for (const std::string& dep : reg[i].dependencies) {
      const ProductInfo* d = find_product(dep);
      ASSERT_NE(d, nullptr) << reg[i].name << " -> " << dep;
      EXPECT_LT(d - reg.data(), ptrdiff_t(i)) << "registry order: " << dep << " after " << reg[i].name;
    }
  }
}

TEST(ProductGraph, EveryDependencyPrecedesItsDependent) {
  // Request every product at once through a synthetic scene.
  Scene scene = earth();
  scene.outputs.clear();
  for (const ProductInfo& p : product_registry()) scene.outputs.push_back(default_spec(p));
  const ProductGraph g = build_product_graph(scene, {});
  EXPECT_EQ(g.nodes.size(), product_registry().size());
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    EXPECT_TRUE(g.nodes[i].requested);
    for (size_t d : g.nodes[i].deps) EXPECT_LT(d, i);
  }
}

TEST(ProductGraph, DependencyOnlyNodesAreNotRequested) {
  // Every product with dependencies, requested alone, pulls in its
  // dependencies as in-memory nodes.
  for (const ProductInfo& p : product_registry()) {
    if (p.dependencies.empty()) continue;
    Scene scene = earth();
    scene.outputs = {default_spec(p)};
    const ProductGraph g = build_product_graph(scene, {});
    ASSERT_EQ(g.nodes.back().info, &p);
    EXPECT_TRUE(g.nodes.back().requested);
    for (size_t i = 0; i + 1 < g.nodes.size(); ++i) EXPECT_FALSE(g.nodes[i].requested);
  }
}

TEST(ProductGraph, HashChangesWithAtmosphereButNotWithFileKeys) {
  Scene a = earth();
  const std::string h0 = build_product_graph(a, {}).nodes[0].input_hash;
  const std::string v0 = build_product_graph(a, {}).nodes[0].value_hash;

  Scene b = a;
  b.resolved["atmosphere"]["top_radius_km"] = 6420;
  EXPECT_NE(build_product_graph(b, {}).nodes[0].value_hash, v0);

  Scene c = a;
  c.outputs[0].formats = {"exr"};
  c.outputs[0].options["formats"] = {"exr"};
  const ProductGraph gc = build_product_graph(c, {});
  EXPECT_EQ(gc.nodes[0].value_hash, v0) << "formats do not change texture values";
  EXPECT_NE(gc.nodes[0].input_hash, h0) << "formats change the files";

  Scene d = a;
  d.resolved["description"] = "another description";
  EXPECT_EQ(build_product_graph(d, {}).nodes[0].input_hash, h0)
      << "keys no product reads do not invalidate";

  Scene e = a;
  e.outputs[0].options["max_error"] = 0.01;
  const ProductGraph ge = build_product_graph(e, {});
  EXPECT_EQ(ge.nodes[0].value_hash, v0) << "max_error does not change texture values";
  EXPECT_NE(ge.nodes[0].input_hash, h0) << "max_error changes the recorded warnings";
}

TEST(ProductGraph, OnlyMustNameARequestedProduct) {
  const Scene s = earth();
  EXPECT_THROW(build_product_graph(s, {"transmitance"}), UsageError);
  try {
    build_product_graph(s, {"transmitance"});
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'transmittance'"), std::string::npos);
  }
}

TEST(Suggest, EditDistanceAndDidYouMean) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(did_you_mean("skyveiw", {"skyview", "transmittance"}), " (did you mean 'skyview'?)");
  EXPECT_EQ(did_you_mean("zzzzzzzz", {"skyview"}), "");
}

}  // namespace
}  // namespace skybake
