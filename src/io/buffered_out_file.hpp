// An output file as a std::streambuf with one large buffer, for writers
// that stream many small pieces through a std::ostream (OpenVDB's archive
// writer: a leaf's 64-byte mask, then its 2 KiB of values). libstdc++'s
// filebuf hands every write of 1 KiB or more straight to the kernel (a
// writev per leaf: 16.5k system calls for the HZD shape volume); this one
// copies every write into its buffer and writes whole buffers. Seeks
// (OpenVDB goes back to fill in its stream offsets) flush first, so the
// file's bytes are the same as through a filebuf.
#pragma once

#include <cstddef>
#include <streambuf>
#include <string>
#include <vector>

namespace skybake {

class BufferedOutFile : public std::streambuf {
 public:
  // Creates or truncates `path`; throws IoError when it cannot.
  explicit BufferedOutFile(const std::string& path, size_t buffer_bytes = size_t(1) << 20);
  ~BufferedOutFile() override;  // closes without reporting (close() reports)
  BufferedOutFile(const BufferedOutFile&) = delete;
  BufferedOutFile& operator=(const BufferedOutFile&) = delete;

  // Writes what is buffered and closes; throws IoError naming the path when
  // any write or the close failed.
  void close();

 protected:
  int_type overflow(int_type ch) override;
  int sync() override;
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override;
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override;

 private:
  bool flush_buffer();

  std::string path_;
  int fd_ = -1;
  int error_ = 0;  // the first write's errno, 0 while none failed
  std::vector<char> buffer_;
  long long offset_ = 0;  // the file offset of buffer_[0]
};

}  // namespace skybake
