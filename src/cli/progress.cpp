#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "cli/progress_text.hpp"

namespace skybake::cli {

ProgressLine::ProgressLine(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO)) {}

ProgressLine::~ProgressLine() {
  if (ticker_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    ticker_.join();
  }
  clear();
}

void ProgressLine::update(const std::string& label, double fraction) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = Clock::now();
  if (label != label_) {
    label_ = label;
    started_ = now;
  }
  fraction_ = fraction;
  if (!ticker_.joinable()) ticker_ = std::thread([this] { tick(); });
  if (drawn_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(50)) return;
  draw(now);
}

void ProgressLine::draw(Clock::time_point now) {
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - started_).count();
  std::fprintf(stderr, "\r\033[K%s", progress_text(label_, fraction_, elapsed).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stop_; }))
    if (drawn_) draw(Clock::now());
}

void ProgressLine::clear() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
  label_.clear();
}

}  // namespace skybake::cli
