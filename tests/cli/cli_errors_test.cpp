// The one error grammar: every error class ends the run with exactly one line
// `skybake: error: <message>` on stderr, nothing on stdout (unless --json),
// and its exit code (0 ok, 1 check failed, 2 usage, 3 invalid preset, 4 file
// error, 5 internal error).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using skybake::test::fresh_dir;
using skybake::test::list_files;
using skybake::test::run_skybake;
using skybake::test::RunResult;
using skybake::test::source_path;

namespace {

const std::string kEarth = source_path("presets/earth.json").string();

void expect_error(const RunResult& r, int exit_code, const std::string& message) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_EQ(r.err, "skybake: error: " + message + "\n");
  EXPECT_EQ(r.out, "");
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

TEST(CliErrors, UsageErrorsFromTheParserAreOneLine) {
  expect_error(run_skybake({"bake", kEarth, "--threads", "5000"}), 2,
               "--threads: Value 5000 not in range 0 to 1024");
  expect_error(run_skybake({"bake", kEarth, "-o"}), 2, "--out: 1 required TEXT missing");
  expect_error(run_skybake({"bake"}), 2, "presets is required");
  expect_error(run_skybake({"plan", kEarth, "--emit", "make"}), 2,
               "--emit: make not in {ninja,slurm}");
  expect_error(run_skybake({"plan", kEarth, "--emit-file", "x.ninja"}), 2,
               "--emit-file requires --emit");
  expect_error(run_skybake({"plan", kEarth, "--edges", "scene"}), 2, "--edges requires --emit");
  expect_error(run_skybake({"plan", kEarth, "--emit", "ninja", "--edges", "step"}), 2,
               "--edges: step not in {scene,product}");
}

// A slurm array task bakes whole presets; a product edge cannot hold a chunk of scenes.
TEST(CliErrors, PlanEdgesAndChunksThatTheEngineCannotRun) {
  expect_error(run_skybake({"plan", kEarth, "--emit", "slurm", "--edges", "product"}), 2,
               "--edges product applies to --emit ninja only; a slurm array task bakes whole "
               "presets (--chunk of them)");
  expect_error(run_skybake({"plan", kEarth, "--emit", "ninja", "--edges", "product", "--chunk",
                            "2"}),
               2, "--chunk groups scenes; with --edges product every edge is one product");
}

TEST(CliErrors, UnknownOptionIsNamedBeforeWhatItLeavesMissing) {
  expect_error(run_skybake({"bake", "--bogus"}), 2, "bake: unknown option '--bogus'");
  expect_error(run_skybake({"bake", kEarth, "--forse"}), 2,
               "bake: unknown option '--forse' (did you mean '--force'?)");
  expect_error(run_skybake({"info", "x.exr", "--jsn=1"}), 2,
               "info: unknown option '--jsn' (did you mean '--json'?)");
  expect_error(run_skybake({"--bogus"}), 2, "unknown option '--bogus'");
}

TEST(CliErrors, RenamedFlagsSuggestTheirNewName) {
  expect_error(run_skybake({"plan", kEarth, "-d", "out"}), 2,
               "plan: unknown option '-d' (did you mean '-o'?)");
  expect_error(run_skybake({"plan", kEarth, "--out-dir", "out"}), 2,
               "plan: unknown option '--out-dir' (did you mean '--out'?)");
  expect_error(run_skybake({"plan", kEarth, "--emit", "ninja", "--output", "b.ninja"}), 2,
               "plan: unknown option '--output' (did you mean '--emit-file'?)");
  expect_error(run_skybake({"report", kEarth, "--products", "transmittance"}), 2,
               "report: unknown option '--products' (did you mean '--only'?)");
}

TEST(CliErrors, UnknownOrMissingCommand) {
  const std::string commands = "(commands: bake, validate, plan, info, check-tiling, report)";
  expect_error(run_skybake({}), 2, "no command given " + commands);
  expect_error(run_skybake({"frobnicate"}), 2, "unknown command 'frobnicate' " + commands);
  expect_error(run_skybake({"bak", kEarth}), 2, "unknown command 'bak' (did you mean 'bake'?)");
}

TEST(CliErrors, UnknownProductSuggestsTheNearestInEveryCommand) {
  const fs::path out = fresh_dir("errors_only");
  for (const std::string cmd : {"bake", "plan", "report"})
    expect_error(run_skybake({cmd, kEarth, "-o", out.string(), "--only", "transmitance"}), 2,
                 "--only: unknown product 'transmitance' (did you mean 'transmittance'?)");
  EXPECT_TRUE(list_files(out).empty());
}

TEST(CliErrors, InvalidPresetNamesFilePointerAndRule) {
  const std::string bad = source_path("tests/bad_presets/albedo_above_one.json").string();
  const fs::path out = fresh_dir("errors_preset");
  expect_error(run_skybake({"bake", bad, "-o", out.string()}), 3,
               bad + ": /planet/ground_albedo/1: must be <= 1, got 1.5");
  EXPECT_TRUE(list_files(out).empty());
}

TEST(CliErrors, MissingInputFileIsAFileError) {
  const fs::path dir = fresh_dir("errors_missing");
  expect_error(run_skybake({"info", "nothing.exr"}, dir), 4, "nothing.exr: no such file");
  expect_error(run_skybake({"check-tiling", "nothing.dds"}, dir), 4, "nothing.dds: no such file");
  expect_error(run_skybake({"validate", "nothing.json"}, dir), 4, "nothing.json: no such file");
  for (const std::string cmd : {"bake", "plan", "report"})
    expect_error(run_skybake({cmd, "no/such.json"}, dir), 4, "no/such.json: no such file");
  // Nothing is read before every input was found.
  write_text(dir / "bad.dds", "garbage");
  expect_error(run_skybake({"info", "bad.dds", "nothing.exr"}, dir), 4,
               "nothing.exr: no such file");
  fs::create_directories(dir / "folder.exr");
  // A folder is read as its texture files: one with none is a usage error.
  expect_error(run_skybake({"info", "folder.exr"}, dir), 2,
               "folder.exr: a folder with no exr, dds, ktx2, vdb file");
  // A pattern that matches nothing is a usage error, not a missing file.
  expect_error(run_skybake({"bake", "no/*.json"}, dir), 2,
               "no/*.json: no such preset file, folder or matching pattern");
  EXPECT_EQ(list_files(dir), (std::vector<std::string>{"bad.dds"}));
}

TEST(CliErrors, UnreadableFileIsAFileError) {
  const fs::path dir = fresh_dir("errors_unreadable");
  write_text(dir / "short.dds", "garbage");
  expect_error(run_skybake({"info", "short.dds"}, dir), 4,
               "short.dds: expected at least 128 bytes (magic and DDS_HEADER), got 7");
  write_text(dir / "notes.txt", "garbage");
  expect_error(run_skybake({"check-tiling", "notes.txt"}, dir), 4,
               "notes.txt: expected a .exr, .dds, .ktx2 or .vdb file, got '.txt'");
}

TEST(CliErrors, PlanOutputFolderThatIsAFileIsRefused) {
  const fs::path dir = fresh_dir("errors_plan_file");
  write_text(dir / "build.ninja", "");
  expect_error(run_skybake({"plan", kEarth, "--emit", "ninja", "-o", "build.ninja"}, dir), 2,
               "-o: 'build.ninja' is a file; -o names the output folder (the emitted file is "
               "--emit-file)");
}

// A broken installation (an unreadable schema) is not the user's mistake:
// exit 5, worded as an internal error.
TEST(CliErrors, InternalErrorIsExitFive) {
  const fs::path schemas = fresh_dir("errors_schemas");
  write_text(schemas / "scene.schema.json", "{\n");
  ::setenv("SKYBAKE_SCHEMA_DIR", schemas.c_str(), 1);
  const fs::path out = fresh_dir("errors_internal");
  const auto r = run_skybake({"bake", kEarth, "-o", out.string()});
  ::unsetenv("SKYBAKE_SCHEMA_DIR");
  EXPECT_EQ(r.exit_code, 5) << r.err;
  const std::string prefix =
      "skybake: error: internal error: schema " + (schemas / "scene.schema.json").string() + ": ";
  EXPECT_EQ(r.err.substr(0, prefix.size()), prefix) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(CliErrors, JsonModeAlsoPrintsTheErrorOnStdout) {
  for (const auto& [args, code, message] :
       std::vector<std::tuple<std::vector<std::string>, int, std::string>>{
           {{"info", "--json", "nothing.exr"}, 4, "nothing.exr: no such file"},
           {{"bake", kEarth, "--json", "--bogus"}, 2, "bake: unknown option '--bogus'"},
           {{"plan", kEarth, "--json", "--emit", "ninja"}, 2, "--json excludes --emit"}}) {
    const auto r = run_skybake(args);
    EXPECT_EQ(r.exit_code, code) << message;
    EXPECT_EQ(r.err, "skybake: error: " + message + "\n");
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j, (nlohmann::json{{"ok", false}, {"error", message}, {"exit_code", code}}));
  }
}

TEST(CliErrors, HelpAndVersionAreNotErrors) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--help"}, {"bake", "--help"}, {"--version"}}) {
    const auto r = run_skybake(args);
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err, "");
    EXPECT_FALSE(r.out.empty());
  }
}

}  // namespace
