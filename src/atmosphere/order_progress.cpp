// Progress over scattering orders. See the header for the estimate.
#include "atmosphere/order_progress.hpp"

#include <algorithm>
#include <cmath>

namespace skybake {

BakeContext stage_context(const BakeContext& ctx, double begin, double end) {
  BakeContext sub;
  if (ctx.on_progress)
    sub.on_progress = [&ctx, begin, end](double f) { ctx.on_progress(begin + (end - begin) * f); };
  return sub;
}

OrderProgress::OrderProgress(const BakeContext& ctx, int last_order, double tolerance,
                             int final_units)
    : ctx_(ctx),
      last_order_(last_order),
      tolerance_(tolerance),
      final_units_(final_units),
      estimated_last_(last_order) {}

BakeContext OrderProgress::next_stage(double units_left) {
  const double begin = end_;
  end_ = units_left > 1.0 ? begin + (1.0 - begin) / units_left : 1.0;
  return stage_context(ctx_, begin, end_);
}

BakeContext OrderProgress::order_context(int k) {
  int units = std::max(estimated_last_ - k + 1, 1) + final_units_;
  // Until the cap, an order of a tolerance bake may not be the last, so it
  // leaves room for one more.
  if (tolerance_ > 0.0 && k < last_order_) units = std::max(units, 2);
  return next_stage(double(units));
}

void OrderProgress::order_done(int k, double residual) {
  const double previous = previous_residual_;
  previous_residual_ = residual;
  if (!(tolerance_ > 0.0)) return;
  if (residual < tolerance_ || k >= last_order_) {
    estimated_last_ = k;
    return;
  }
  // Geometric decay at this order's ratio (header); no decay: up to the cap.
  const double ratio = previous > 0.0 ? residual / previous : 1.0;
  double left = double(last_order_ - k);
  if (ratio > 0.0 && ratio < 1.0)
    left = std::min(left, std::ceil(std::log(tolerance_ / residual) / std::log(ratio)));
  estimated_last_ = k + int(std::max(left, 1.0));
}

}  // namespace skybake
