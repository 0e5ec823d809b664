// Tests of WriteBehind (pipeline/write_behind.hpp), the thread an output is
// written on while the next one bakes: jobs in the order given, on another
// thread or in place, and a job's failure rethrown before anything later
// starts, as a serial bake would have stopped there.
#include "pipeline/write_behind.hpp"

#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace skybake {
namespace {

TEST(WriteBehind, JobsRunInTheOrderGiven) {
  for (bool behind : {false, true}) {
    std::vector<int> done;
    {
      WriteBehind writer(behind);
      for (int k = 0; k < 50; ++k) writer.run([&done, k] { done.push_back(k); });
      writer.drain();
    }
    ASSERT_EQ(done.size(), 50u) << behind;
    for (int k = 0; k < 50; ++k) EXPECT_EQ(done[k], k) << behind;
  }
}

TEST(WriteBehind, BehindRunsOnAnotherThreadInPlaceOnThisOne) {
  const std::thread::id me = std::this_thread::get_id();
  std::thread::id ran_on;
  WriteBehind in_place(false);
  in_place.run([&ran_on] { ran_on = std::this_thread::get_id(); });
  EXPECT_EQ(ran_on, me);  // done before run() returned
  WriteBehind behind(true);
  behind.run([&ran_on] { ran_on = std::this_thread::get_id(); });
  behind.drain();
  EXPECT_NE(ran_on, me);
}

TEST(WriteBehind, AFailureIsRethrownAndNothingLaterStarts) {
  for (bool behind : {false, true}) {
    WriteBehind writer(behind);
    bool later_ran = false;
    if (behind) {
      writer.run([] { throw std::runtime_error("disk full"); });
      // The next job waits for the failed one and rethrows its error.
      EXPECT_THROW(writer.run([&later_ran] { later_ran = true; }), std::runtime_error);
    } else {
      EXPECT_THROW(writer.run([] { throw std::runtime_error("disk full"); }), std::runtime_error);
    }
    writer.drain();  // the failure was reported once
    EXPECT_FALSE(later_ran) << behind;
  }
}

TEST(WriteBehind, DrainRethrowsTheJobInFlightsFailure) {
  WriteBehind writer(true);
  writer.run([] { throw std::runtime_error("cannot write"); });
  EXPECT_THROW(writer.drain(), std::runtime_error);
  EXPECT_NO_THROW(writer.drain());
}

}  // namespace
}  // namespace skybake
