// What every baker receives besides its inputs: a progress hook. Threading is
// global (tbb::global_control set by the CLI); bakers split work per row or
// slice with tbb::parallel_for and compute every texel independently, so the
// output does not depend on the thread count.
#pragma once

#include <atomic>
#include <functional>

namespace skybake {

struct BakeContext {
  // Called with the fraction done in [0, 1]; may be called from any worker
  // thread, so it must be thread-safe. Empty = no progress reporting.
  std::function<void(double)> on_progress;

  // Bakers call this after each finished unit of work (row, slice, order).
  void report(size_t done, size_t total) const {
    if (on_progress && total > 0) on_progress(double(done) / double(total));
  }
};

// Counts finished work units across threads and forwards to the context.
class ProgressCounter {
 public:
  ProgressCounter(const BakeContext& ctx, size_t total) : ctx_(ctx), total_(total) {}
  void tick() const { ctx_.report(++done_, total_); }

 private:
  const BakeContext& ctx_;
  size_t total_;
  mutable std::atomic<size_t> done_{0};
};

}  // namespace skybake
