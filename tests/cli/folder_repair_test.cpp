// manifest.json or .skybake.lock replaced by something that is not a regular
// file (a folder, a FIFO, a symbolic link loop, a link to /dev/zero): the
// bake fails as a file error (exit 4), without blocking, with a message that
// says what to remove; once it is removed the next bake repairs the folder.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using skybake::test::run_skybake;

namespace {

struct Replacement {
  const char* name;
  std::function<void(const fs::path&)> make;
};

const std::vector<Replacement>& replacements() {
  static const std::vector<Replacement> all = {
      {"folder", [](const fs::path& p) { fs::create_directory(p); }},
      {"fifo", [](const fs::path& p) { ASSERT_EQ(::mkfifo(p.c_str(), 0644), 0); }},
      {"link_loop", [](const fs::path& p) { fs::create_symlink(p.filename(), p); }},
      {"dev_zero", [](const fs::path& p) { fs::create_symlink("/dev/zero", p); }},
  };
  return all;
}

class FolderRepair : public testing::TestWithParam<std::string> {};

TEST_P(FolderRepair, TheMessageSaysWhatToRemoveAndTheBakeThenRepairs) {
  const fs::path dir = skybake::test::test_dir("cli_folder_repair");
  const nlohmann::json scene = {
      {"name", "repair"},
      {"planet", {{"radius_km", 6360}, {"ground_albedo", {0.3, 0.3, 0.3}}}},
      {"atmosphere", skybake::test::source_path("presets/atmospheres/earth.json").string()},
      {"outputs", {{{"product", "transmittance"}, {"size", {32, 16}}, {"formats", {"exr"}}}}}};
  std::ofstream(dir / "scene.json") << scene.dump();
  const std::vector<std::string> bake = {"bake", (dir / "scene.json").string(), "-o",
                                         (dir / "out").string(), "-q"};
  ASSERT_EQ(run_skybake(bake).exit_code, 0);
  const fs::path file = dir / "out" / "repair" / GetParam();
  for (const Replacement& r : replacements()) {
    SCOPED_TRACE(r.name);
    fs::remove(file);
    r.make(file);
    std::vector<std::string> forced = bake;
    forced.push_back("--force");  // the lock is only taken to record a baked output
    const auto broken = run_skybake(forced);
    EXPECT_EQ(broken.exit_code, 4) << broken.err;
    EXPECT_THAT(broken.err, HasSubstr(file.string() + ": cannot "));
    EXPECT_THAT(broken.err, HasSubstr("remove"));
    EXPECT_THAT(broken.err, HasSubstr("docs/farm.md, \"Repairing an output folder\""));
    fs::remove(file);
    const auto repaired = run_skybake(bake);
    EXPECT_EQ(repaired.exit_code, 0) << repaired.err;
  }
}

INSTANTIATE_TEST_SUITE_P(Files, FolderRepair, testing::Values("manifest.json", ".skybake.lock"),
                         [](const auto& info) {
                           return info.param == "manifest.json" ? std::string("manifest")
                                                                : std::string("lock");
                         });

}  // namespace
