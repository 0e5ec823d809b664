// Shader constants headers (io/shader_constants.hpp): names, types and
// literals of a hand-made entry; every header compiles with glslangValidator
// (GLSL and HLSL); `skybake bake --emit-shader-constants` writes one pair per
// output whose values, parsed back, equal the manifest's, lists them in the
// manifest, and a re-run finds everything current.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "io/file_record.hpp"
#include "io/shader_constants.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

struct Declared {
  std::string type;
  std::string literal;
};

// name -> (type, literal) of every `[static ]const T NAME = v;` line.
std::map<std::string, Declared> declarations(const std::string& text) {
  std::map<std::string, Declared> out;
  const std::regex line(
      R"(^(?:static )?const (int|uint|float|bool|[i]?vec[23]|int[23]|float[23]) (\w+) = ([^;]+);$)");
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) {
    std::smatch m;
    if (std::regex_match(l, m, line)) {
      EXPECT_FALSE(out.count(m[2])) << "declared twice: " << m[2];
      out[m[2]] = {m[1], m[3]};
    }
  }
  return out;
}

// The value of a literal as the shader compiler reads it (a trailing 'u' is
// the unsigned suffix); the components of a vector constructor.
std::vector<double> literal_values(std::string literal) {
  std::vector<double> out;
  const size_t open = literal.find('(');
  if (open != std::string::npos) literal = literal.substr(open + 1, literal.size() - open - 2);
  std::istringstream parts(literal);
  std::string part;
  while (std::getline(parts, part, ',')) {
    if (!part.empty() && part.back() == 'u') part.pop_back();
    out.push_back(std::strtod(part.c_str(), nullptr));
  }
  return out;
}
double literal_value(const std::string& literal) {
  const std::vector<double> v = literal_values(literal);
  EXPECT_EQ(v.size(), 1u) << literal;
  return v.empty() ? 0.0 : v[0];
}

// The test's own naming rule (docs/runtime.md "Shader constants"), written
// independently of shader_identifier.
std::string expected_name(const std::string& output, const std::string& key) {
  std::string id;
  for (const std::string& part : {output, key}) {
    std::string word;
    for (char c : part) word += std::isalnum((unsigned char)c) ? char(std::toupper(c)) : ' ';
    std::istringstream words(word);
    std::string w;
    while (words >> w) id += "_" + w;
  }
  return "SKYBAKE" + id;
}

struct ToolResult {
  int exit_code = -1;
  std::string out;
};

ToolResult run_tool(const std::string& command) {
  ToolResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) r.out += buf;
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Compiles a header as an include of a compute shader: GLSL to the GL
// front end, HLSL to SPIR-V (glslang's HLSL front end needs a target).
// A missing glslangValidator fails the test (scripts/install-deps.sh installs it).
ToolResult compile_header(const std::string& text, ShaderLanguage language, const fs::path& dir) {
  const bool glsl = language == ShaderLanguage::glsl;
  const fs::path file = dir / (glsl ? "wrapper.comp" : "wrapper.hlsl");
  std::ofstream(file) << (glsl ? "#version 450\n" : "") << text
                      << (glsl ? "layout(local_size_x = 1) in;\nvoid main() {}\n"
                               : "[numthreads(1, 1, 1)] void main() {}\n");
  const std::string command = glsl ? "glslangValidator '" + file.string() + "'"
                                   : "glslangValidator -V -D -S comp -e main -o '" +
                                         (dir / "wrapper.spv").string() + "' '" + file.string() +
                                         "'";
  return run_tool(command);
}

ManifestEntry sample_entry() {
  ManifestEntry e;
  e.name = "sky-view";
  e.product = "skyview";
  e.dimensions = {192, 108};
  e.layers = 8;
  e.channels = {"R", "G", "B"};
  e.metadata = {{"bottom_radius_m", 6360000.0},
                {"mu_s.min", -0.20791169081775931},
                {"mu_s_min", 0.5},  // the same identifier as mu_s.min
                {"sun_angular_radius", 0.004675},
                {"mie_g", 0.80000000000000004},
                {"seed", 4294967295u},
                {"tiny", 1.0000000000000001e-300},
                {"huge", 1e300},
                {"tileable", true},
                {"solar_irradiance", {1.474, 1.8504, 1.91198}},
                {"period", {3, 24}},
                {"mixed", {1, "a"}},
                {"parameterization", "Hillaire 2020 sec. 5.3 \xc3\xa9\nnext line"},
                {"orders", 4},
                {"input_hash", "1234567890123456"},  // digits only, still a hash
                {"height", 108}};                    // the dimension, recorded by the product too
  return e;
}

TEST(ShaderConstants, IdentifiersAreUpperCaseWithSingleUnderscores) {
  EXPECT_EQ(shader_identifier("mu_s.min"), "MU_S_MIN");
  EXPECT_EQ(shader_identifier("type.0.density"), "TYPE_0_DENSITY");
  EXPECT_EQ(shader_identifier("..a__b--c.."), "A_B_C");
  EXPECT_EQ(shader_identifier("sky-view"), "SKY_VIEW");
  EXPECT_EQ(shader_identifier("."), "");
}

TEST(ShaderConstants, TypesLiteralsAndCollisions) {
  const ManifestEntry e = sample_entry();
  const std::string text = shader_constants_text(e, ShaderLanguage::glsl, "skybake test");
  const auto d = declarations(text);
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_WIDTH").literal, "192");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_HEIGHT").literal, "108");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_LAYERS").literal, "8");
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_DEPTH"));
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_HEIGHT_2")) << "one height";
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_BOTTOM_RADIUS_M").type, "float");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_BOTTOM_RADIUS_M").literal, "6360000.0");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_SOLAR_IRRADIANCE").type, "vec3");
  EXPECT_EQ(literal_values(d.at("SKYBAKE_SKY_VIEW_SOLAR_IRRADIANCE").literal),
            (std::vector<double>{1.474, 1.8504, 1.91198}));
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_PERIOD").type, "ivec2");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_PERIOD").literal, "ivec2(3, 24)");
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_MIXED")) << "not a numeric tuple: a comment";
  const auto hlsl = declarations(shader_constants_text(e, ShaderLanguage::hlsl, "skybake test"));
  EXPECT_EQ(hlsl.at("SKYBAKE_SKY_VIEW_SOLAR_IRRADIANCE").type, "float3");
  EXPECT_EQ(hlsl.at("SKYBAKE_SKY_VIEW_PERIOD").literal, "int2(3, 24)");
  // Keys in order: "mu_s.min" < "mu_s_min", so the second takes _2.
  EXPECT_EQ(literal_value(d.at("SKYBAKE_SKY_VIEW_MU_S_MIN").literal), -0.20791169081775931);
  EXPECT_EQ(literal_value(d.at("SKYBAKE_SKY_VIEW_MU_S_MIN_2").literal), 0.5);
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_MU_S_MIN_2").type, "float");
  EXPECT_EQ(literal_value(d.at("SKYBAKE_SKY_VIEW_SUN_ANGULAR_RADIUS").literal), 0.004675);
  EXPECT_EQ(literal_value(d.at("SKYBAKE_SKY_VIEW_MIE_G").literal), 0.8);
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_SEED").type, "uint");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_SEED").literal, "4294967295u");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_TILEABLE").type, "bool");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_ORDERS").type, "int");
  EXPECT_EQ(d.at("SKYBAKE_SKY_VIEW_TINY").type, "float");
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_HUGE")) << "beyond float32: a comment";
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_PARAMETERIZATION")) << "text: a comment";
  EXPECT_FALSE(d.count("SKYBAKE_SKY_VIEW_INPUT_HASH")) << "a 64-bit hash is no number";
  EXPECT_NE(text.find("// parameterization: Hillaire 2020 sec. 5.3    next line\n"),
            std::string::npos)
      << text;
  // A float written as an integer would be an int literal in GLSL.
  for (const auto& [name, decl] : d) {
    if (decl.type == "float") {
      EXPECT_NE(decl.literal.find_first_of(".e"), std::string::npos) << name;
    }
  }
}

TEST(ShaderConstants, GlslAndHlslCompile) {
  const fs::path dir = test::fresh_dir("shader_constants_compile");
  const ManifestEntry e = sample_entry();
  for (ShaderLanguage language : {ShaderLanguage::glsl, ShaderLanguage::hlsl}) {
    const std::string text = shader_constants_text(e, language, "skybake test");
    const ToolResult r = compile_header(text, language, dir);
    EXPECT_EQ(r.exit_code, 0) << shader_language_name(language) << ":\n" << r.out << text;
    // Included twice, the guard keeps the second copy out.
    const ToolResult twice = compile_header(text + text, language, dir);
    EXPECT_EQ(twice.exit_code, 0) << twice.out;
  }
  // The check can fail: a broken declaration does not compile.
  EXPECT_NE(compile_header("const float X = ;\n", ShaderLanguage::glsl, dir).exit_code, 0);
  EXPECT_NE(compile_header("static const float X = ;\n", ShaderLanguage::hlsl, dir).exit_code, 0);
}

// Numbers as the manifest records them: typed JSON numbers, or text that
// holds a number and nothing else.
bool manifest_number(const nlohmann::json& v, double& out) {
  if (v.is_number()) return out = v.get<double>(), true;
  if (!v.is_string()) return false;
  const std::string s = v.get<std::string>();
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  // Digits beyond 32 bits are a hash, not a quantity (docs/runtime.md).
  const bool digits = s.find_first_not_of("-0123456789") == std::string::npos;
  if (digits && std::abs(out) > 4294967295.0) return false;
  return !s.empty() && *end == '\0' && std::isfinite(out) && std::abs(out) < 3.4e38 &&
         s.find_first_of("xXnN ") == std::string::npos;
}

TEST(ShaderConstants, BakeEmitsHeadersEqualToTheManifest) {
  const fs::path out = test::fresh_dir("shader_constants_bake");
  const std::string storm = test::source_path("presets/earth_storm.json").string();
  const std::string noise = test::source_path("presets/clouds/horizon_zero_dawn.json").string();
  const auto r = test::run_skybake(
      {"bake", storm, noise, "-o", out.string(), "--emit-shader-constants", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(r.out);
  size_t outputs = 0, checked_values = 0;
  for (const auto& scene : report["scenes"]) {
    const fs::path dir = scene["folder"].get<std::string>();
    const auto manifest = nlohmann::json::parse(test::read_file(dir / "manifest.json"));
    ASSERT_EQ(scene["shader_constants"].size(), 2 * manifest["outputs"].size());
    for (const auto& o : manifest["outputs"]) {
      ++outputs;
      const std::string name = o["name"];
      std::map<std::string, nlohmann::json> files;
      for (const auto& f : o["files"]) files[f["format"]] = f;
      for (ShaderLanguage language : {ShaderLanguage::glsl, ShaderLanguage::hlsl}) {
        const std::string lang = shader_language_name(language);
        ASSERT_TRUE(files.count(lang)) << name << " lists its ." << lang;
        const fs::path header = dir / files[lang]["path"].get<std::string>();
        EXPECT_EQ(header, dir / (name + "." + lang));
        EXPECT_EQ(files[lang]["size"].get<uint64_t>(), fs::file_size(header));
        EXPECT_EQ(files[lang]["hash"].get<std::string>(), hash_file(header));
        const std::string text = test::read_file(header);
        const ToolResult compiled = compile_header(text, language, out);
        EXPECT_EQ(compiled.exit_code, 0) << header << "\n" << compiled.out;
        const auto d = declarations(text);
        const std::string prefix = expected_name(name, "");
        const auto dims = o["dimensions"];
        const char* axes[3] = {"WIDTH", "HEIGHT", "DEPTH"};
        for (size_t i = 0; i < dims.size(); ++i)
          EXPECT_EQ(literal_value(d.at(prefix + "_" + axes[i]).literal), dims[i].get<double>());
        for (const auto& [key, value] : o["metadata"].items()) {
          std::vector<double> expected;
          double v;
          if (value.is_array() && (value.size() == 2 || value.size() == 3)) {
            for (const auto& e : value)
              if (manifest_number(e, v)) expected.push_back(v);
            if (expected.size() != value.size()) continue;
          } else if (manifest_number(value, v)) {
            expected = {v};
          } else {
            continue;
          }
          const std::string id = expected_name(name, key);
          ASSERT_TRUE(d.count(id)) << header << " lacks " << id << " for " << key;
          EXPECT_EQ(literal_values(d.at(id).literal), expected) << header << " " << key;
          ++checked_values;
        }
      }
    }
  }
  EXPECT_EQ(outputs, 8u) << "earth_storm: 5 outputs, clouds_hzd: 3";
  EXPECT_GT(checked_values, 100u);

  // Everything is current on a re-run, with or without the flag, and the
  // manifest does not change.
  const fs::path storm_manifest = out / "earth_storm" / "manifest.json";
  const std::string before = test::read_file(storm_manifest);
  for (bool flag : {true, false}) {
    std::vector<std::string> args = {"bake", storm, "-o", out.string(), "--json"};
    if (flag) args.push_back("--emit-shader-constants");
    const auto again = test::run_skybake(args);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(nlohmann::json::parse(again.out)["summary"]["baked"], 0) << again.out;
    EXPECT_EQ(test::read_file(storm_manifest), before);
  }
}

}  // namespace
}  // namespace skybake
