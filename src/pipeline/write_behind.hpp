// Writing one output while the next one bakes.
//
// A bake's outputs are computed in dependency order, and what follows a
// computation (encoding, the error record, flushing the files to disk,
// the manifest and the stamp: docs/architecture.md "Data flow") needs only
// the finished texture. Much of that time is spent waiting for the disk
// (fsync) or on one thread, so it runs on a thread of its own while the next
// output is computed. Jobs run one at a time, in the order given, so the
// manifest, the stamps and the lines printed come out as in a serial bake;
// the files' bytes do not depend on it at all.
#pragma once

#include <exception>
#include <functional>
#include <thread>

namespace skybake {

class WriteBehind {
 public:
  // behind = false runs every job at once on the calling thread (one thread
  // allowed: --threads 1 means one).
  explicit WriteBehind(bool behind) : behind_(behind) {}
  ~WriteBehind();  // waits for the job in flight; what it throws is dropped
  WriteBehind(const WriteBehind&) = delete;
  WriteBehind& operator=(const WriteBehind&) = delete;

  // Waits for the previous job, rethrowing what it threw (it belongs to an
  // earlier output: a serial bake would have stopped there), then starts
  // `job`.
  void run(std::function<void()> job);

  // Waits for the job in flight, if any, and rethrows what it threw.
  void drain();

 private:
  bool behind_;
  std::thread thread_;
  std::exception_ptr failure_;
};

}  // namespace skybake
