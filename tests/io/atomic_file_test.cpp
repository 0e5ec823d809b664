// Temporary-then-rename output and the folder lock.
#include <gtest/gtest.h>

#include <fstream>

#include "io/atomic_file.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

TEST(AtomicFile, NothingUnderTheFinalNameUntilCommit) {
  const fs::path dir = test::fresh_dir("atomic_commit");
  const fs::path final_path = dir / "lut.exr";
  AtomicFile f(final_path);
  EXPECT_EQ(f.temp_path().extension(), ".exr") << "writers pick the format by extension";
  EXPECT_EQ(f.temp_path().parent_path(), dir) << "same folder so rename is atomic";
  EXPECT_TRUE(is_temporary_name(f.temp_path().filename().string()));
  std::ofstream(f.temp_path()) << "data";
  EXPECT_FALSE(fs::exists(final_path));
  f.commit();
  EXPECT_TRUE(fs::exists(final_path));
  EXPECT_FALSE(fs::exists(f.temp_path()));
  EXPECT_EQ(test::read_file(final_path), "data");
}

TEST(AtomicFile, AbandonedWriteLeavesNoFile) {
  const fs::path dir = test::fresh_dir("atomic_abandon");
  fs::path temp;
  {
    AtomicFile f(dir / "lut.dds");
    temp = f.temp_path();
    std::ofstream(f.temp_path()) << "partial";
  }  // e.g. an exception unwound past the writer
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_TRUE(test::list_files(dir).empty());
}

TEST(AtomicFile, ReplacesAnExistingFileWhole) {
  const fs::path dir = test::fresh_dir("atomic_replace");
  write_text_atomic(dir / "manifest.json", "old");
  write_text_atomic(dir / "manifest.json", "new");
  EXPECT_EQ(test::read_file(dir / "manifest.json"), "new");
  EXPECT_EQ(test::list_files(dir), std::vector<std::string>{"manifest.json"});
}

TEST(DirectoryLock, CanBeTakenAgainAfterRelease) {
  const fs::path dir = test::fresh_dir("atomic_lock");
  { DirectoryLock a(dir); }
  { DirectoryLock b(dir); }
  EXPECT_TRUE(fs::exists(dir / ".skybake.lock"));
}

}  // namespace
}  // namespace skybake
