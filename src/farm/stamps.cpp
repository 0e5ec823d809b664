#include "farm/stamps.hpp"

#include <fstream>

#include "io/atomic_file.hpp"

namespace fs = std::filesystem;

namespace skybake {

fs::path stamp_path(const fs::path& scene_dir, const std::string& name) {
  return scene_dir / ".stamps" / (name + ".stamp");
}

void update_stamp(const fs::path& scene_dir, const std::string& name, const std::string& hash) {
  const fs::path stamp = stamp_path(scene_dir, name);
  std::error_code ec;
  fs::create_directories(stamp.parent_path(), ec);
  std::ifstream in(stamp);
  std::string old;
  std::getline(in, old);
  if (old == hash) return;  // untouched, so ninja's restat sees no change
  write_text_atomic(stamp, hash + "\n");
}

}  // namespace skybake
