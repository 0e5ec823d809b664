// Test support: runs the real skybake executable and captures its exit code,
// stdout and stderr; makes fresh scratch folders.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace skybake::test {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// The skybake executable under test: $SKYBAKE_TEST_EXE when set (a sanitizer
// build, scripts/sanitize.sh), else the one this build made (SKYBAKE_EXE).
std::string skybake_exe();

// Runs skybake_exe() with the arguments (shell-quoted here), in `cwd` if given.
RunResult run_skybake(const std::vector<std::string>& args, const std::filesystem::path& cwd = {});

// The standard output of a shell command (popen), its wait status in
// `status` (-1 when it could not start).
std::string run_shell(const std::string& command, int* status);

// An empty folder under SKYBAKE_TEST_TMP named after the test (and this
// process, since ctest runs cases in parallel processes).
std::filesystem::path fresh_dir(const std::string& name);

// fresh_dir() named `<group>_<suite>_<test>` after the running GoogleTest case.
std::filesystem::path test_dir(const std::string& group);

std::string read_file(const std::filesystem::path& path);

// Path of `file` in SKYBAKE_TEST_TMP/<group>/<test>/, the folder created and
// any old copy of the file removed.
std::string scratch_file(const std::string& group, const std::string& test,
                         const std::string& file);

// Path inside the source tree.
std::filesystem::path source_path(const std::string& relative);

// All regular files under a folder (recursive), relative paths, sorted;
// safe to call on a folder a running bake is writing (vanished entries are
// skipped).
std::vector<std::string> list_files(const std::filesystem::path& dir);

}  // namespace skybake::test
