#include "farm/stamps.hpp"

#include <fstream>

#include "core/safe_input.hpp"
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
  // A stamp is one hash and a newline; anything else is rewritten. A stamp
  // already right is left untouched, so ninja's restat sees no change.
  const FileText read = read_regular_file(stamp, 4096);
  const std::string old = read.text.substr(0, read.text.find('\n'));
  if (read.status == ReadStatus::ok && old == hash) return;
  // Renamed, not flushed: a stamp lost to a power cut makes ninja run the
  // bake again, which finds the outputs current and writes it anew; a stamp
  // is only written after the manifest that lists its output is flushed.
  write_text_atomic(stamp, hash + "\n", Durability::renamed);
}

}  // namespace skybake
