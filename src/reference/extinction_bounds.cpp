// Altitude-binned extinction bounds and the ray's walk through the bins; see
// the header.
#include "reference/extinction_bounds.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/math.hpp"
#include "reference/density_bounds.hpp"

namespace skybake {

namespace {

struct Spread {
  glm::dvec3 lower{0.0}, upper{0.0};
};

// Bounds of sigma_t over the altitudes [lo, hi), the ceiling excluded (it
// belongs to the next bin, which matters where a density jumps).
Spread extinction_spread(const Atmosphere& atm, double lo, double hi) {
  const double below = std::max(lo, std::nextafter(hi, lo));
  Spread s;
  for (const MediumComponent& c : atm.components) {
    const glm::dvec3 sigma_t = c.scattering_per_m + c.absorption_per_m;
    if (sigma_t == glm::dvec3(0.0)) continue;
    s.lower += min_density_over(c.density, lo, below) * sigma_t;
    s.upper += max_density_over(c.density, lo, below) * sigma_t;
  }
  return s;
}

// Whether [lo, hi) may be one bin under `binning`.
bool narrow_enough(const Atmosphere& atm, const AdaptiveBinning& binning, double lo, double hi) {
  const Spread s = extinction_spread(atm, lo, hi);
  const double rb = atm.bottom_radius_m;
  const double chord = 2.0 * std::sqrt((hi - lo) * (2.0 * rb + hi + lo));  // grazing the floor
  for (int c = 0; c < 3; ++c) {
    const double spread = s.upper[c] - s.lower[c];
    if (spread > binning.max_relative_spread * s.upper[c] &&
        spread * chord > binning.max_chord_spread)
      return false;
  }
  return true;
}

}  // namespace

ExtinctionBounds::ExtinctionBounds(const Atmosphere& atm, int bins)
    : bottom_radius_m_(atm.bottom_radius_m) {
  assert(bins >= 1);
  const double thickness = atm.top_radius_m - atm.bottom_radius_m;
  for (int k = 0; k < bins; ++k) boundaries_m_.push_back(thickness * k / bins);
  boundaries_m_.push_back(thickness);
  fill_bounds(atm);
}

ExtinctionBounds::ExtinctionBounds(const Atmosphere& atm, const AdaptiveBinning& binning)
    : bottom_radius_m_(atm.bottom_radius_m) {
  const double thickness = atm.top_radius_m - atm.bottom_radius_m;
  const double min_height = binning.min_bin_fraction * thickness;
  std::vector<double> stops = density_kink_altitudes(atm);
  stops.push_back(thickness);
  double lo = 0.0;
  boundaries_m_.push_back(lo);
  for (double stop : stops) {
    while (lo < stop) {
      double hi = stop;
      if (!narrow_enough(atm, binning, lo, hi)) {
        // The criterion is monotone in hi: bisect for the tallest bin.
        double good = std::min(lo + min_height, stop), bad = stop;
        for (int i = 0; i < 60 && bad - good > 1e-3 * min_height; ++i) {
          const double mid = 0.5 * (good + bad);
          (narrow_enough(atm, binning, lo, mid) ? good : bad) = mid;
        }
        hi = good;
        if (stop - hi < min_height) hi = stop;  // no sliver before a stop
      }
      boundaries_m_.push_back(hi);
      lo = hi;
    }
  }
  fill_bounds(atm);
}

void ExtinctionBounds::fill_bounds(const Atmosphere& atm) {
  const size_t n = boundaries_m_.size() - 1;
  lower_.resize(n);
  upper_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const Spread s = extinction_spread(atm, boundaries_m_[k], boundaries_m_[k + 1]);
    lower_[k] = s.lower * (1.0 - 1e-9);
    upper_[k] = s.upper * (1.0 + 1e-9);
  }
}

int ExtinctionBounds::bin_of_altitude(double altitude_m) const {
  // The last boundary not above h, among the floors 0 .. bins() - 1.
  const auto floors_end = boundaries_m_.end() - 1;
  const auto it = std::upper_bound(boundaries_m_.begin(), floors_end, altitude_m);
  return it == boundaries_m_.begin() ? 0 : int(it - boundaries_m_.begin()) - 1;
}

AltitudeBinWalker::AltitudeBinWalker(const ExtinctionBounds& bounds, double r, double mu,
                                     double t_end)
    : bounds_(bounds),
      r_(r),
      mu_(mu),
      t_end_(t_end),
      t_perigee_(std::max(0.0, -r * mu)),
      bin_(bounds.bin_of_altitude(r - bounds.bottom_radius_m())),
      descending_(mu < 0.0) {}

// Distance to the sphere of bin boundary `boundary` (the floor of that
// bin): the first intersection (entering it from outside) or the
// second (leaving it); NaN when the ray misses the sphere.
double AltitudeBinWalker::crossing(int boundary, bool first) const {
  const double radius = bounds_.bottom_radius_m() + bounds_.boundary_altitude_m(boundary);
  const double discriminant = r_ * r_ * mu_ * mu_ + (radius - r_) * (radius + r_);
  if (discriminant < 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double q = std::sqrt(discriminant);
  return first ? -r_ * mu_ - q : -r_ * mu_ + q;
}

// A crossing behind the current point means the point is already past that
// boundary (a rounding error in its altitude): the bin is corrected before
// the segment is emitted, so the bounds always belong to the altitudes the
// segment covers.
bool AltitudeBinWalker::next(double& t0, double& t1, int& bin) {
  while (t_ < t_end_) {
    if (descending_) {
      const double stop = std::min(t_perigee_, t_end_);
      const double down = bin_ > 0 ? crossing(bin_, true) : std::nan("");
      if (down < t_) {  // false for NaN
        --bin_;
        continue;
      }
      t0 = t_;
      bin = bin_;
      if (down < stop) {  // into the bin below
        t1 = down;
        --bin_;
      } else {  // the perigee (or the ground) is inside this bin
        t1 = stop;
        descending_ = false;
      }
    } else {
      const double up = bin_ + 1 < bounds_.bins() ? crossing(bin_ + 1, false) : std::nan("");
      if (up < t_) {
        ++bin_;
        continue;
      }
      t0 = t_;
      bin = bin_;
      if (up < t_end_) {  // into the bin above
        t1 = up;
        ++bin_;
      } else {
        t1 = t_end_;
      }
    }
    t_ = t1;
    if (t1 > t0) return true;  // skip empty segments (at the perigee, on a boundary)
  }
  return false;
}

}  // namespace skybake
