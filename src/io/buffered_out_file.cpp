#include "io/buffered_out_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/write_all.hpp"

namespace skybake {

BufferedOutFile::BufferedOutFile(const std::string& path, size_t buffer_bytes)
    : path_(path), buffer_(buffer_bytes) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0)
    throw IoError(fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno)));
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

BufferedOutFile::~BufferedOutFile() {
  if (fd_ >= 0) {
    flush_buffer();
    ::close(fd_);
  }
}

bool BufferedOutFile::flush_buffer() {
  const size_t bytes = size_t(pptr() - pbase());
  if (error_ == 0) {
    error_ = pwrite_all(fd_, pbase(), bytes, uint64_t(offset_));
    if (error_ == 0) offset_ += decltype(offset_)(bytes);
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

BufferedOutFile::int_type BufferedOutFile::overflow(int_type ch) {
  if (!flush_buffer()) return traits_type::eof();
  if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
  *pptr() = traits_type::to_char_type(ch);
  pbump(1);
  return ch;
}

int BufferedOutFile::sync() { return flush_buffer() ? 0 : -1; }

BufferedOutFile::pos_type BufferedOutFile::seekoff(off_type off, std::ios_base::seekdir dir,
                                                   std::ios_base::openmode) {
  const long long here = offset_ + (pptr() - pbase());
  if (dir == std::ios_base::cur && off == 0) return pos_type(here);  // tellp: no flush
  if (!flush_buffer()) return pos_type(off_type(-1));
  long long base = here;
  if (dir == std::ios_base::beg) base = 0;
  if (dir == std::ios_base::end) {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) return pos_type(off_type(-1));
    base = st.st_size;
  }
  if (base + off < 0) return pos_type(off_type(-1));
  offset_ = base + off;
  return pos_type(offset_);
}

BufferedOutFile::pos_type BufferedOutFile::seekpos(pos_type pos, std::ios_base::openmode which) {
  return seekoff(off_type(pos), std::ios_base::beg, which);
}

void BufferedOutFile::close() {
  if (fd_ < 0) return;
  flush_buffer();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && error_ == 0) error_ = errno;
  if (error_ != 0)
    throw IoError(fmt::format("{}: cannot write: {}", path_, std::strerror(error_)));
}

}  // namespace skybake
