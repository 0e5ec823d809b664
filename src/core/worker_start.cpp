#include "core/worker_start.hpp"

#include <sched.h>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

namespace skybake {

namespace {

// Moves the calling thread off `cpu` once, then gives it back the CPUs it
// was allowed: a nudge, not a pin. Linux places a woken thread on the CPU
// it last ran on, or beside its waker when they share a last-level cache.
// Where the kernel sees no shared cache between CPUs (virtual machines that
// report none, such as the development VM), a new worker woken by the
// thread that created it can land on that thread's CPU and share it until
// the periodic load balancing moves it, about 10 ms later: a bake shorter
// than that ran at one thread's speed on two (docs/decisions/fresh-pages.md). Once moved, the worker is woken where it last
// ran. Does nothing where it is not on `cpu` or may run nowhere else.
void move_off(int cpu) {
  if (cpu < 0 || sched_getcpu() != cpu) return;
  cpu_set_t allowed;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return;
  if (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed) || CPU_COUNT(&allowed) < 2) return;
  cpu_set_t others = allowed;
  CPU_CLR(cpu, &others);
  if (sched_setaffinity(0, sizeof others, &others) == 0)
    (void)sched_setaffinity(0, sizeof allowed, &allowed);
}

// Calls move_off on each worker thread's first entry into the scheduler.
class SpreadWorkers : public tbb::task_scheduler_observer {
 public:
  explicit SpreadWorkers(int cpu) : cpu_(cpu) { observe(true); }
  void on_scheduler_entry(bool is_worker) override {
    thread_local bool placed = false;
    if (!is_worker || placed) return;
    placed = true;
    move_off(cpu_);
  }

 private:
  int cpu_;
};

}  // namespace

void start_workers() {
  if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1) {
    // Created once, before the first worker, and never destroyed: workers
    // may enter the scheduler until the process exits.
    static SpreadWorkers* const spread = new SpreadWorkers(sched_getcpu());
    (void)spread;
    tbb::this_task_arena::enqueue([] {});
  } else {
    tbb::parallel_for(0, 1, [](int) {});
  }
}

}  // namespace skybake
