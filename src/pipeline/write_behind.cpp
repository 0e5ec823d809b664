#include "pipeline/write_behind.hpp"

#include <utility>

namespace skybake {

WriteBehind::~WriteBehind() {
  if (thread_.joinable()) thread_.join();
}

void WriteBehind::run(std::function<void()> job) {
  drain();
  if (!behind_) {
    job();
    return;
  }
  thread_ = std::thread([this, job = std::move(job)] {
    try {
      job();
    } catch (...) {
      failure_ = std::current_exception();
    }
  });
}

void WriteBehind::drain() {
  if (thread_.joinable()) thread_.join();
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

}  // namespace skybake
