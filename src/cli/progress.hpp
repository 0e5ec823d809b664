// Progress on a terminal: one line per product, redrawn in place
// ("earth/transmittance [#######.........] 45%  12 s, ETA 15 s",
// cli/progress_text.hpp), only when stderr is a TTY and --quiet is not
// given, so logs on build farms stay clean. The elapsed time keeps counting
// between the baker's reports: the line is redrawn every quarter second.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace skybake::cli {

class ProgressLine {
 public:
  explicit ProgressLine(bool enabled);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Thread-safe; redraws at most every 50 ms, and always at 100%. A new
  // label starts the elapsed time.
  void update(const std::string& label, double fraction);
  // Erases the line so the next message starts clean; nothing is drawn
  // again until the next update.
  void clear();

 private:
  using Clock = std::chrono::steady_clock;
  void draw(Clock::time_point now);  // with mutex_ held
  void tick();

  bool enabled_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;
  bool stop_ = false;
  std::string label_;
  double fraction_ = 0.0;
  Clock::time_point started_, last_;
  bool drawn_ = false;
};

}  // namespace skybake::cli
