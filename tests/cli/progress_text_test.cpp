// The terminal progress line: elapsed time and an ETA extrapolated from the
// fraction the baker reports.
#include <gtest/gtest.h>

#include "cli/progress_text.hpp"

namespace {

using skybake::cli::duration_text;
using skybake::cli::eta_seconds;
using skybake::cli::progress_text;

TEST(ProgressText, Durations) {
  EXPECT_EQ(duration_text(0.0), "0.0 s");
  EXPECT_EQ(duration_text(3.24), "3.2 s");
  EXPECT_EQ(duration_text(9.96), "10 s");
  EXPECT_EQ(duration_text(42.4), "42 s");
  EXPECT_EQ(duration_text(59.4), "59 s");
  EXPECT_EQ(duration_text(59.6), "1:00");
  EXPECT_EQ(duration_text(245.0), "4:05");
  EXPECT_EQ(duration_text(3723.0), "1:02:03");
  EXPECT_EQ(duration_text(-1.0), "0.0 s");
}

TEST(ProgressText, EtaExtrapolatesTheFraction) {
  EXPECT_DOUBLE_EQ(*eta_seconds(0.25, 12.0), 36.0);
  EXPECT_DOUBLE_EQ(*eta_seconds(0.5, 10.0), 10.0);
  // Too early to tell, or done.
  EXPECT_FALSE(eta_seconds(0.005, 30.0));
  EXPECT_FALSE(eta_seconds(0.5, 0.2));
  EXPECT_FALSE(eta_seconds(1.0, 10.0));
  EXPECT_FALSE(eta_seconds(std::nan(""), 10.0));
}

TEST(ProgressText, Line) {
  EXPECT_EQ(progress_text("earth/scattering", 0.25, 12.0),
            "earth/scattering [######..................]  25%  12 s, ETA 36 s");
  EXPECT_EQ(progress_text("earth/transmittance", 0.0, 0.1),
            "earth/transmittance [........................]   0%  0.1 s, ETA --");
  EXPECT_EQ(progress_text("earth/skyview", 1.0, 65.0),
            "earth/skyview [########################] 100%  1:05");
  EXPECT_EQ(progress_text("x", 1.5, 1.0), "x [########################] 100%  1.0 s");
}

}  // namespace
