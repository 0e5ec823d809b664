#include "support/run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace fs = std::filesystem;

namespace skybake::test {

namespace {
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string scratch_file(const std::string& group, const std::string& test,
                         const std::string& file) {
  const fs::path dir = fs::path(SKYBAKE_TEST_TMP) / group / test;
  fs::create_directories(dir);
  fs::remove(dir / file);
  return (dir / file).string();
}

fs::path fresh_dir(const std::string& name) {
  // ctest runs test cases as parallel processes: one folder per process.
  const fs::path dir = fs::path(SKYBAKE_TEST_TMP) / (name + "." + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path test_dir(const std::string& group) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = group + "_" + info->test_suite_name() + "_" + info->name();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return fresh_dir(name);
}

fs::path source_path(const std::string& relative) {
  return fs::path(SKYBAKE_SOURCE_DIR) / relative;
}

std::string skybake_exe() {
  const char* other = std::getenv("SKYBAKE_TEST_EXE");
  return other && *other ? std::string(other) : std::string(SKYBAKE_EXE);
}

RunResult run_skybake(const std::vector<std::string>& args, const fs::path& cwd) {
  static int counter = 0;
  const fs::path capture = fs::path(SKYBAKE_TEST_TMP) / "capture";
  fs::create_directories(capture);
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const fs::path out = capture / (tag + ".out"), err = capture / (tag + ".err");
  std::string cmd;
  if (!cwd.empty()) cmd += "cd " + quote(cwd.string()) + " && ";
  cmd += quote(skybake_exe());
  for (const std::string& a : args) cmd += " " + quote(a);
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

std::vector<std::string> list_files(const fs::path& dir) {
  // Entries that vanish while listed (a live bake renaming its temporaries)
  // are skipped; the relative name is lexical, since a canonical path needs
  // the file to still exist.
  std::vector<std::string> files;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    std::error_code status;
    if (it->is_regular_file(status) && !status)
      files.push_back(it->path().lexically_relative(dir).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string run_shell(const std::string& command, int* status) {
  std::string out;
  *status = -1;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  char buf[65536];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  *status = pclose(pipe);
  return out;
}

}  // namespace skybake::test
