#include "io/texel_spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.hpp"

namespace skybake {

namespace {

std::string spill_error(const std::filesystem::path& folder, const char* what) {
  return std::string("spectral bake: ") + what + " the running sums' temporary file in " +
         folder.string() + ": " + std::strerror(errno);
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
  if (fd_ < 0) return;
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
    if (n <= 0) throw Error(spill_error(folder_, "cannot write"));
    done += size_t(n);
  }
  TexelVector().swap(tex.data);
  slot.out = true;
}

void TexelSpill::take(size_t key, Texture& tex) {
  auto it = slots_.find(key);
  if (fd_ < 0 || it == slots_.end() || !it->second.out) return;
  Slot& slot = it->second;
  tex.data.resize(slot.floats);
  char* p = reinterpret_cast<char*>(tex.data.data());
  size_t done = 0, bytes = slot.floats * sizeof(float);
  while (done < bytes) {
    const ssize_t n = ::pread(fd_, p + done, bytes - done, off_t(slot.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(spill_error(folder_, "cannot read"));
    done += size_t(n);
  }
  slot.out = false;
}

}  // namespace skybake
