// Progress on a terminal: one line per product, redrawn in place
// ("earth/transmittance [#######.........] 45%"), only when stderr is a TTY
// and --quiet is not given, so logs on build farms stay clean.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace skybake::cli {

class ProgressLine {
 public:
  explicit ProgressLine(bool enabled);
  // Thread-safe; redraws at most every 50 ms, and always at 100%.
  void update(const std::string& label, double fraction);
  // Erases the line so the next message starts clean.
  void clear();

 private:
  bool enabled_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_;
  bool drawn_ = false;
};

}  // namespace skybake::cli
