// The text of the terminal progress line, apart from the drawing so it can be
// tested: "earth/scattering [######..................]  25%  12 s, ETA 36 s".
// The ETA extrapolates the fraction the baker reports linearly in time.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

namespace skybake::cli {

// "3.2 s" under 10 s, "42 s" under a minute, "4:05" under an hour, "1:02:03".
inline std::string duration_text(double seconds) {
  seconds = std::max(0.0, seconds);
  if (seconds < 9.95) return fmt::format("{:.1f} s", seconds);
  const long s = std::lround(seconds);
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{}:{:02}", s / 60, s % 60);
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

// Seconds left at `fraction` done after `elapsed` seconds; none while there is
// too little to extrapolate from (under 1% or half a second) or when done.
inline std::optional<double> eta_seconds(double fraction, double elapsed) {
  if (!(fraction >= 0.01) || fraction >= 1.0 || elapsed < 0.5) return std::nullopt;
  return elapsed * (1.0 - fraction) / fraction;
}

inline std::string progress_text(const std::string& label, double fraction, double elapsed) {
  constexpr int kWidth = 24;
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int filled = std::clamp(int(f * kWidth + 0.5), 0, kWidth);
  const std::optional<double> eta = eta_seconds(f, elapsed);
  return fmt::format("{} [{}{}] {:3}%  {}{}", label, std::string(filled, '#'),
                     std::string(kWidth - filled, '.'), int(f * 100.0 + 0.5),
                     duration_text(elapsed),
                     f >= 1.0 ? "" : ", ETA " + (eta ? duration_text(*eta) : std::string("--")));
}

}  // namespace skybake::cli
