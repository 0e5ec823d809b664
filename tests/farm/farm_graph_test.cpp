// Farm planning (farm/catalog.hpp, farm_graph.hpp, stamps.hpp) on a small
// catalog: scene "a" requests transmittance, multiple scattering and sky-view
// (a diamond of dependencies), scene "b" multiple scattering alone (its
// transmittance is computed in memory, not a node).
#include "farm/farm_graph.hpp"

#include <fcntl.h>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/error.hpp"
#include "farm/catalog.hpp"
#include "farm/emit.hpp"
#include "farm/stamps.hpp"
#include "io/atomic_file.hpp"
#include "io/file_record.hpp"
#include "pipeline/bake.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/preset_loader.hpp"
#include "pipeline/product_graph.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace skybake {
namespace {

json output(const std::string& product, std::vector<int> size) {
  return json::object({{"product", product}, {"size", size}, {"formats", {"exr"}}});
}

json scene_preset(const std::string& name, json outputs) {
  return json::object({{"name", name},
                       {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
                       {"atmosphere", "atmospheres/earth.json"},
                       {"outputs", std::move(outputs)}});
}

void write_json(const fs::path& file, const json& j) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << j.dump(2);
}

class FarmGraphTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::test_dir("farm");
    catalog_ = dir_ / "catalog";
    out_ = dir_ / "out";
    // The referenced atmosphere has no "outputs": the catalog skips it.
    fs::create_directories(catalog_ / "atmospheres");
    fs::copy_file(test::source_path("presets/atmospheres/earth.json"),
                  catalog_ / "atmospheres" / "earth.json");
    write_json(catalog_ / "a.json",
               scene_preset("a", json::array({output("transmittance", {32, 16}),
                                              output("multiscattering", {8, 8}),
                                              output("skyview", {16, 8})})));
    write_json(catalog_ / "b.json",
               scene_preset("b", json::array({output("multiscattering", {8, 8})})));
  }

  std::vector<Scene> scenes() const {
    std::vector<Scene> out;
    for (const fs::path& p : expand_catalog({catalog_.string()})) out.push_back(load_scene(p));
    return out;
  }

  FarmGraph graph() const { return build_farm_graph(scenes(), out_); }

  fs::path dir_, catalog_, out_;
};

const FarmNode& node(const FarmGraph& g, const std::string& id) {
  for (const FarmNode& n : g.nodes)
    if (n.id == id) return n;
  throw std::runtime_error("no node " + id);
}

std::vector<std::string> ids(const FarmGraph& g) {
  std::vector<std::string> out;
  for (const FarmNode& n : g.nodes) out.push_back(n.id);
  return out;
}

TEST_F(FarmGraphTest, CatalogTakesScenesAndSkipsTheirReferencedPresets) {
  EXPECT_EQ(expand_catalog({catalog_.string()}),
            (std::vector<fs::path>{catalog_ / "a.json", catalog_ / "b.json"}));
  // A pattern and a file naming the same scene: listed once.
  EXPECT_EQ(expand_catalog({(catalog_ / "*.json").string(), (catalog_ / "b.json").string()}),
            (std::vector<fs::path>{catalog_ / "a.json", catalog_ / "b.json"}));
  EXPECT_THROW(expand_catalog({(dir_ / "nothing*.json").string()}), UsageError);
}

TEST_F(FarmGraphTest, OneNodePerRequestedProductWithItsFilesAndStamp) {
  const std::vector<Scene> all = scenes();
  const FarmGraph g = build_farm_graph(all, out_);
  EXPECT_EQ(g.out_dir, out_);
  EXPECT_EQ(ids(g), (std::vector<std::string>{"a/transmittance", "a/multiscattering", "a/skyview",
                                              "b/multiscattering"}));
  for (const Scene& scene : all) {
    const ProductGraph pg = build_product_graph(scene, {});
    for (const GraphNode& gn : pg.nodes) {
      if (!gn.requested) continue;
      const FarmNode& n = node(g, scene.name + "/" + gn.spec.name);
      SCOPED_TRACE(n.id);
      EXPECT_EQ(n.scene, scene.name);
      EXPECT_EQ(n.product, gn.info->name);
      EXPECT_EQ(n.preset, scene.file.string());
      EXPECT_EQ(n.input_hash, gn.input_hash);
      std::vector<std::string> files;
      for (const std::string& f : output_files(gn.spec))
        files.push_back((fs::path(scene.name) / f).string());
      EXPECT_EQ(n.files, files);
      EXPECT_EQ(n.stamp, stamp_path(scene.name, gn.spec.name).string());
      // The preset first, then the files it references: a change to either
      // re-runs the node.
      ASSERT_EQ(n.sources.size(), 2u);
      EXPECT_EQ(n.sources[0], scene.file.string());
      EXPECT_EQ(fs::path(n.sources[1]).filename(), "earth.json");
      EXPECT_FALSE(n.current);
      EXPECT_EQ(n.reason, "not baked yet");
      EXPECT_GT(n.estimated_seconds, 0.0);
    }
  }
}

TEST_F(FarmGraphTest, EdgesFollowDependenciesBetweenRequestedProductsOfOneScene) {
  const FarmGraph g = graph();
  EXPECT_TRUE(node(g, "a/transmittance").deps.empty());
  EXPECT_EQ(node(g, "a/multiscattering").deps, std::vector<std::string>{"a/transmittance"});
  EXPECT_EQ(
      std::set<std::string>(node(g, "a/skyview").deps.begin(), node(g, "a/skyview").deps.end()),
      (std::set<std::string>{"a/transmittance", "a/multiscattering"}));
  // b's transmittance is not requested: computed in memory, no node, no edge.
  EXPECT_TRUE(node(g, "b/multiscattering").deps.empty());

  const json j = farm_graph_json(g);
  std::set<std::pair<std::string, std::string>> edges, from_deps;
  for (const json& e : j["edges"])
    edges.insert({e.at(0).get<std::string>(), e.at(1).get<std::string>()});
  for (const FarmNode& n : g.nodes)
    for (const std::string& d : n.deps) from_deps.insert({d, n.id});
  EXPECT_EQ(edges, from_deps);
  EXPECT_EQ(j["nodes"].size(), g.nodes.size());
}

TEST_F(FarmGraphTest, DependenciesComeFirstSoTheGraphHasNoCycle) {
  const FarmGraph g = graph();
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < g.nodes.size(); ++i) index[g.nodes[i].id] = i;
  for (size_t i = 0; i < g.nodes.size(); ++i)
    for (const std::string& d : g.nodes[i].deps) {
      ASSERT_EQ(index.count(d), 1u) << g.nodes[i].id << " reads unknown " << d;
      EXPECT_LT(index[d], i) << g.nodes[i].id << " before its dependency " << d;
      EXPECT_EQ(g.nodes[index[d]].scene, g.nodes[i].scene) << "an edge between scenes";
    }
}

TEST_F(FarmGraphTest, EstimatesIncludeDependenciesComputedInMemory) {
  // b's node also computes a default-size transmittance table; a's reads it.
  const FarmGraph g = graph();
  const ProductInfo& t = *find_product("transmittance");
  double texels = 1.0;
  for (int s : t.default_size) texels *= s;
  EXPECT_NEAR(node(g, "b/multiscattering").estimated_seconds -
                  node(g, "a/multiscattering").estimated_seconds,
              texels * t.ns_per_texel * 1e-9, 1e-12);
}

TEST_F(FarmGraphTest, BakedNodesAreUpToDateAndLeftOutOfTheJson) {
  BakeOptions options;
  options.out_dir = out_;
  for (const Scene& s : scenes())
    if (s.name == "a") bake_scene(s, options);

  FarmGraph g = graph();
  for (const char* id : {"a/transmittance", "a/multiscattering", "a/skyview"}) {
    EXPECT_TRUE(node(g, id).current) << id;
    EXPECT_EQ(node(g, id).reason, "up to date") << id;
  }
  EXPECT_FALSE(node(g, "b/multiscattering").current);
  json j = farm_graph_json(g);
  ASSERT_EQ(j["nodes"].size(), 1u);
  EXPECT_EQ(j["nodes"][0]["id"], "b/multiscattering");
  EXPECT_TRUE(j["edges"].empty());

  // A deleted file makes its node stale; its current dependencies are read
  // from disk, so no edge leads to it.
  fs::remove(out_ / "a" / "skyview.exr");
  g = graph();
  EXPECT_FALSE(node(g, "a/skyview").current);
  EXPECT_EQ(node(g, "a/skyview").reason, "missing file skyview.exr");
  EXPECT_TRUE(node(g, "a/multiscattering").current);
  j = farm_graph_json(g);
  EXPECT_EQ(j["nodes"].size(), 2u);
  EXPECT_TRUE(j["edges"].empty());
}

TEST_F(FarmGraphTest, TwoScenesWithOneNameAreAUsageError) {
  write_json(catalog_ / "c.json",
             scene_preset("a", json::array({output("transmittance", {32, 16})})));
  EXPECT_THROW(graph(), UsageError);
}

TEST_F(FarmGraphTest, NinjaEdgesWaitForTheStampsOfTheirDependencies) {
  const FarmGraph g = graph();
  EmitOptions options;
  options.skybake = "/usr/bin/skybake";
  options.edges = NinjaEdges::kProduct;
  const std::string ninja = emit_ninja(g, options);
  EXPECT_NE(ninja.find("restat = 1"), std::string::npos);
  const auto stamp = [&](const FarmNode& n) {
    return fs::absolute(out_ / n.stamp).lexically_normal().string();
  };
  for (const FarmNode& n : g.nodes) {
    SCOPED_TRACE(n.id);
    const size_t at = ninja.find("build " + stamp(n) + " ");
    ASSERT_NE(at, std::string::npos);
    const std::string line = ninja.substr(at, ninja.find('\n', at) - at);
    for (const std::string& d : n.deps) EXPECT_NE(line.find(stamp(node(g, d))), std::string::npos);
    for (const std::string& f : n.files)
      EXPECT_NE(line.find(fs::absolute(out_ / f).lexically_normal().string()), std::string::npos);
  }
}

// The "build ..." lines of a ninja file.
std::vector<std::string> build_lines(const std::string& ninja) {
  std::vector<std::string> lines;
  for (size_t at = ninja.find("\nbuild "); at != std::string::npos;
       at = ninja.find("\nbuild ", at + 1))
    lines.push_back(ninja.substr(at + 1, ninja.find('\n', at + 1) - at - 1));
  return lines;
}

// Scene edges: one per scene (or per --chunk of scenes), every stamp of its
// scenes an explicit output, every file an implicit one, no stamp an input:
// a scene's dependencies stay inside its process.
TEST_F(FarmGraphTest, NinjaSceneEdgesOwnEveryStampAndFileOfTheirScenes) {
  const FarmGraph g = graph();
  const auto abs = [&](const std::string& p) {
    return fs::absolute(out_ / p).lexically_normal().string();
  };
  for (int chunk : {1, 2}) {
    SCOPED_TRACE(chunk);
    EmitOptions options;
    options.skybake = "/usr/bin/skybake";
    options.chunk = chunk;
    const std::string ninja = emit_ninja(g, options);
    EXPECT_NE(ninja.find("restat = 1"), std::string::npos);
    EXPECT_EQ(ninja.find("--only"), std::string::npos) << ninja;
    const std::vector<std::string> lines = build_lines(ninja);
    // The scene edges, then `build all`.
    ASSERT_EQ(lines.size(), chunk == 1 ? 3u : 2u) << ninja;
    for (const FarmNode& n : g.nodes) {
      SCOPED_TRACE(n.id);
      const size_t edge = chunk == 1 && n.scene == "b" ? 1 : 0;
      const std::string& line = lines[edge];
      const size_t colon = line.find(": bake ");
      ASSERT_NE(colon, std::string::npos) << line;
      const std::string outputs = line.substr(0, colon), inputs = line.substr(colon);
      const size_t bar = outputs.find(" | ");
      ASSERT_NE(bar, std::string::npos) << line;
      EXPECT_NE(outputs.substr(0, bar).find(" " + abs(n.stamp)), std::string::npos) << line;
      for (const std::string& f : n.files)
        EXPECT_NE(outputs.substr(bar).find(" " + abs(f)), std::string::npos) << line;
      EXPECT_EQ(inputs.find(abs(n.stamp)), std::string::npos) << "a stamp read by a scene edge";
      EXPECT_NE(inputs.find(fs::absolute(n.preset).lexically_normal().string()),
                std::string::npos);
      EXPECT_NE(lines.back().find(abs(n.stamp)), std::string::npos) << "not in `all`";
    }
  }
}

// --max-parallel is a ninja pool for either kind of edge: declared before
// the rule, with the depth asked for, and named by the rule; none without it.
TEST_F(FarmGraphTest, NinjaMaxParallelIsAPoolOfTheBakeRule) {
  const FarmGraph g = graph();
  for (NinjaEdges edges : {NinjaEdges::kScene, NinjaEdges::kProduct}) {
    EmitOptions options;
    options.skybake = "/usr/bin/skybake";
    options.edges = edges;
    EXPECT_EQ(emit_ninja(g, options).find("pool"), std::string::npos);
    options.max_parallel = 3;
    const std::string ninja = emit_ninja(g, options);
    const size_t pool = ninja.find("pool bake_pool\n  depth = 3\n");
    const size_t rule = ninja.find("rule bake\n");
    ASSERT_NE(pool, std::string::npos) << ninja;
    ASSERT_NE(rule, std::string::npos) << ninja;
    EXPECT_LT(pool, rule);
    const size_t first_build = ninja.find("\nbuild ");
    const size_t uses = ninja.find("  pool = bake_pool\n", rule);
    EXPECT_LT(uses, first_build) << ninja;
  }
}

void set_mtime_ns(const fs::path& file, int64_t ns) {
  const timespec t{time_t(ns / 1000000000), long(ns % 1000000000)};
  const timespec times[2] = {t, t};
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0);
}

TEST(Stamps, RewrittenOnlyWhenTheHashChanges) {
  const fs::path scene_dir = test::fresh_dir("farm_stamps");
  const fs::path stamp = stamp_path(scene_dir, "transmittance");
  EXPECT_EQ(stamp, scene_dir / ".stamps" / "transmittance.stamp");

  update_stamp(scene_dir, "transmittance", "0123abcd");
  EXPECT_EQ(test::read_file(stamp), "0123abcd\n");
  // An old time, so a rewrite could not go unnoticed within the clock's
  // resolution.
  const int64_t old_time = int64_t(1000000000) * 1000000000;
  set_mtime_ns(stamp, old_time);
  update_stamp(scene_dir, "transmittance", "0123abcd");
  EXPECT_EQ(stat_file(stamp).mtime_ns, old_time) << "an unchanged hash rewrote the stamp";
  EXPECT_EQ(test::read_file(stamp), "0123abcd\n");

  update_stamp(scene_dir, "transmittance", "4567ef01");
  EXPECT_EQ(test::read_file(stamp), "4567ef01\n");
  EXPECT_NE(stat_file(stamp).mtime_ns, old_time);
  for (const auto& e : fs::directory_iterator(stamp.parent_path()))
    EXPECT_FALSE(is_temporary_name(e.path().filename().string())) << e.path();
}

}  // namespace
}  // namespace skybake
