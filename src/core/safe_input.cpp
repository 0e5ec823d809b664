#include "core/safe_input.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

namespace skybake {

namespace {

// What a non-regular file is, for messages.
std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

FileText refused(std::string why) {
  FileText r;
  r.status = ReadStatus::refused;
  r.why = std::move(why);
  return r;
}

std::string too_large(std::uintmax_t size, std::uintmax_t max_bytes) {
  return fmt::format("is {} bytes, more than the limit of {} bytes", size, max_bytes);
}

}  // namespace

FileText read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      FileText r;
      r.status = ReadStatus::missing;
      r.why = std::strerror(err);
      return r;
    }
    return refused(std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) return refused("is " + file_kind(st.st_mode) + ", expected a regular file");
  if (std::uintmax_t(st.st_size) > max_bytes) return refused(too_large(std::uintmax_t(st.st_size), max_bytes));

  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return refused(std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  // The path may have been replaced between stat and open.
  if (::fstat(fd, &st) != 0) return refused(std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return refused("is " + file_kind(st.st_mode) + ", expected a regular file");

  FileText r;
  r.text.resize(size_t(st.st_size) + 1);
  size_t got = 0;
  for (;;) {
    if (got == r.text.size()) {
      if (got > max_bytes) return refused(too_large(got, max_bytes));
      r.text.resize(std::min<std::uintmax_t>(max_bytes + 1, got * 2 + 4096));
    }
    const ssize_t n = ::read(fd, &r.text[got], r.text.size() - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      return refused(std::strerror(errno));
    }
    if (n == 0) break;
    got += size_t(n);
  }
  if (got > max_bytes) return refused(too_large(got, max_bytes));
  r.text.resize(got);
  return r;
}

std::optional<std::string> json_nesting_problem(std::string_view text, int max_depth) {
  int depth = 0;
  size_t line = 1, line_start = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;  // the escaped character cannot end the string
      else if (c == '"')
        in_string = false;
      else if (c == '\n') {  // invalid JSON, but keep the line count right
        ++line;
        line_start = i + 1;
      }
      continue;
    }
    switch (c) {
      case '"':
        in_string = true;
        break;
      case '[':
      case '{':
        if (++depth > max_depth)
          return fmt::format(
              "nests arrays and objects deeper than the limit of {} levels (line {}, column {})",
              max_depth, line, i - line_start + 1);
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        break;
      case '\n':
        ++line;
        line_start = i + 1;
        break;
      default:
        break;
    }
  }
  return std::nullopt;
}

}  // namespace skybake
