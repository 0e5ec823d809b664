#include "core/worker_start.hpp"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace skybake {

void start_workers() {
  if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1)
    tbb::this_task_arena::enqueue([] {});
  else
    tbb::parallel_for(0, 1, [](int) {});
}

}  // namespace skybake
