#include "io/texel_spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace skybake {

namespace {

// Floats read per piece in add_to: 64 KiB.
constexpr size_t kPieceFloats = 16384;

// An I/O failure (exit 4), as for the outputs themselves.
IoError spill_error(const std::filesystem::path& folder, const char* what) {
  return IoError(folder.string() + ": " + what + " the spectral bake's running sums: " +
                 std::strerror(errno));
}

}  // namespace

TexelSpill::TexelSpill(const std::filesystem::path& folder) : folder_(folder) {
  if (folder.empty()) return;
#ifdef O_TMPFILE
  fd_ = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
#endif
  if (fd_ >= 0) return;
  // File systems without O_TMPFILE (overlayfs before Linux 6.6, NFS): a
  // named file, unlinked at once.
  std::string name = (folder / ".skybake-spill-XXXXXX").string();
  fd_ = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd_ >= 0) ::unlink(name.c_str());
}

TexelSpill::~TexelSpill() {
  if (fd_ >= 0) ::close(fd_);
}

void TexelSpill::put(size_t key, Texture& tex) {
  if (fd_ < 0) {
    held_[key] = std::move(tex.data);
    TexelVector().swap(tex.data);
    return;
  }
  Slot& slot = slots_[key];
  if (slot.floats == 0) {
    slot.offset = end_;
    slot.floats = tex.data.size();
    end_ += slot.floats * sizeof(float);
  }
  if (slot.floats != tex.data.size()) throw Error("spectral bake: a table changed size");
  const char* p = reinterpret_cast<const char*>(tex.data.data());
  size_t done = 0, bytes = slot.floats * sizeof(float);
  while (done < bytes) {
    const ssize_t n = ::pwrite(fd_, p + done, bytes - done, off_t(slot.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw spill_error(folder_, "cannot write");
    done += size_t(n);
  }
  TexelVector().swap(tex.data);
  slot.kept = true;
}

void TexelSpill::add_to(size_t key, Texture& tex) {
  if (auto h = held_.find(key); h != held_.end()) {
    if (h->second.size() != tex.data.size()) throw Error("spectral bake: a table changed size");
    for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] += h->second[i];
    held_.erase(h);
    return;
  }
  auto it = slots_.find(key);
  if (it == slots_.end() || !it->second.kept) return;
  Slot& slot = it->second;
  if (slot.floats != tex.data.size()) throw Error("spectral bake: a table changed size");
  std::vector<float> piece(std::min(kPieceFloats, slot.floats));
  for (size_t first = 0; first < slot.floats; first += piece.size()) {
    const size_t count = std::min(piece.size(), slot.floats - first);
    char* p = reinterpret_cast<char*>(piece.data());
    size_t done = 0, bytes = count * sizeof(float);
    while (done < bytes) {
      const off_t at = off_t(slot.offset + first * sizeof(float) + done);
      const ssize_t n = ::pread(fd_, p + done, bytes - done, at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw spill_error(folder_, "cannot read");
      done += size_t(n);
    }
    for (size_t i = 0; i < count; ++i) tex.data[first + i] += piece[i];
  }
  slot.kept = false;
}

}  // namespace skybake
