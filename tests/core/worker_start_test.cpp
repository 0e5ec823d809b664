// start_workers places its workers without pinning them: after a parallel
// loop every thread that ran it may still run on every CPU the process may,
// and the loop's work is all done, on one thread or several.
#include <gtest/gtest.h>

#include <sched.h>

#include <atomic>
#include <mutex>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "core/worker_start.hpp"

namespace skybake {
namespace {

bool same_mask(const cpu_set_t& a, const cpu_set_t& b) { return CPU_EQUAL(&a, &b); }

TEST(WorkerStart, LeavesEveryThreadFreeToRunOnEveryAllowedCpu) {
  cpu_set_t process;
  ASSERT_EQ(sched_getaffinity(0, sizeof process, &process), 0);
  for (size_t threads : {1u, 2u, 4u}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    start_workers();
    std::atomic<int> done{0};
    std::mutex m;
    std::vector<cpu_set_t> masks;
    tbb::parallel_for(0, 256, [&](int) {
      volatile double s = 0;
      for (int k = 0; k < 20000; ++k) s = s + k;
      cpu_set_t mine;
      ASSERT_EQ(sched_getaffinity(0, sizeof mine, &mine), 0);
      std::lock_guard<std::mutex> lock(m);
      masks.push_back(mine);
      ++done;
    });
    EXPECT_EQ(done.load(), 256) << threads << " threads";
    for (const cpu_set_t& mask : masks) EXPECT_TRUE(same_mask(mask, process)) << threads;
    cpu_set_t after;
    ASSERT_EQ(sched_getaffinity(0, sizeof after, &after), 0);
    EXPECT_TRUE(same_mask(after, process));
  }
}

}  // namespace
}  // namespace skybake
