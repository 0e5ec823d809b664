// Bounds of the extinction for the path tracer's tracking (Woodcock / delta
// tracking and residual ratio tracking, Novak, Selle & Jarosz 2014), and a
// walk of a ray through the altitude bins they are stored in.
//
// The shell is cut into altitude bins; each stores a lower and an upper
// bound of sigma_t = sum_i sigma_t,i density_i(h) over the bin
// (min_density_over / max_density_over per component, exact up to rounding;
// a sum of minima bounds the minimum of the sum, likewise for maxima),
// widened by 1e-9 for rounding. Along a ray the bins are spheres, so the
// ray's length inside each follows from ray / sphere intersections:
// AltitudeBinWalker yields the segments [t0, t1) of the ray in bin order.
// The tracker then has a piecewise-constant majorant (the bin's upper bound:
// few null collisions in thin air) and, for transmittance, a piecewise-
// constant control (the bin's lower bound: its optical depth is exact, and
// only the residual between the bounds is estimated stochastically, whose
// relative variance is about exp(residual optical depth) - 1 instead of
// exp(optical depth) - 1 for plain ratio tracking with a tight majorant).
//
// Bins are uniform, or adaptive: grown from the ground up as tall as they
// can be while, in every channel, the spread upper - lower stays below a
// fraction of upper or the spread times the longest chord through the bin
// (a ray grazing its floor) stays below an optical depth; density kinks are
// always bin boundaries. The residual optical depth along any ray is then at
// most about max_relative_spread times its optical depth, and thin air,
// where nothing is at stake, gets few bins.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/medium.hpp"

namespace skybake {

struct AdaptiveBinning {
  double max_relative_spread = 0.05;  // (upper - lower) / upper per bin
  double max_chord_spread = 0.05;     // or (upper - lower) * longest chord, optical depth
  double min_bin_fraction = 1e-5;     // no bin thinner than this fraction of the shell
};

class ExtinctionBounds {
 public:
  // `bins` equal bins.
  ExtinctionBounds(const Atmosphere& atm, int bins);
  // Adaptive bins (see the top).
  ExtinctionBounds(const Atmosphere& atm, const AdaptiveBinning& binning);

  int bins() const { return int(lower_.size()); }
  double bottom_radius_m() const { return bottom_radius_m_; }
  // Altitude (m) of the floor of bin k; k = bins() gives the top.
  double boundary_altitude_m(int k) const { return boundaries_m_[size_t(k)]; }
  // The bin holding altitude h (m), clamped to the shell.
  int bin_of_altitude(double altitude_m) const;
  // sigma_t (1/m, per channel) lies in [lower(k), upper(k)] over bin k.
  glm::dvec3 lower(int bin) const { return lower_[size_t(bin)]; }
  glm::dvec3 upper(int bin) const { return upper_[size_t(bin)]; }

 private:
  void fill_bounds(const Atmosphere& atm);

  double bottom_radius_m_ = 0.0;
  std::vector<double> boundaries_m_;  // bins() + 1 altitudes, 0 to the top
  std::vector<glm::dvec3> lower_, upper_;
};

// Walks the ray that starts at radius r (m, inside the shell) with zenith
// cosine mu, from t = 0 to t_end (m, where it leaves the shell or meets the
// ground), through the altitude bins: each call to next() gives the next
// segment [t0, t1) and the bin it lies in; false at the end. Segments are
// contiguous and cover [0, t_end]. The ray descends to its perigee (or the
// ground) crossing the bins' floors, then rises crossing their ceilings;
// each crossing is one square root.
class AltitudeBinWalker {
 public:
  AltitudeBinWalker(const ExtinctionBounds& bounds, double r, double mu, double t_end);
  bool next(double& t0, double& t1, int& bin);

 private:
  double crossing(int boundary, bool first) const;

  const ExtinctionBounds& bounds_;
  double r_, mu_, t_end_;
  double t_ = 0.0;
  double t_perigee_;
  int bin_;
  bool descending_;
};

}  // namespace skybake
