// Progress of a bake that iterates scattering orders (the 4D orders of
// scattering_orders.hpp, the 3D orders of scattering3d_lut.hpp): order 1,
// orders 2..N and a final stage, each order one unit of work (they cost about
// the same), the final stage `final_units` of them.
//
// With a fixed count N is known and every order gets 1 / (N + final_units) of
// the bake. With a tolerance, N is not known: the residuals of the orders
// decay roughly geometrically (the order-to-order map has a dominant
// eigenvalue, geometric_tail.hpp), so after order k with residual r_k and
// ratio q = r_k / r_{k-1} (r_1 = 1: order 1 is the whole table) about
//   log(tolerance / r_k) / log(q)
// orders remain, at least one and at most up to max_orders. Each order takes
// its share of what is left, (1 - done) / (units left by the estimate, the
// final stage's included, and at least 2 before the cap: an order may turn
// out not to be the last): the fraction never decreases whatever the
// estimate does, and reaches 1 only when the baker reports the end. Before
// the sequence is geometric q grows toward its limit, so early estimates are
// short; later orders then advance less.
#pragma once

#include "core/bake_context.hpp"

namespace skybake {

// Maps a stage's progress in [0, 1] onto [begin, end] of `ctx`. The result
// refers to ctx, which must outlive it.
BakeContext stage_context(const BakeContext& ctx, double begin, double end);

class OrderProgress {
 public:
  // last_order: the order count (tolerance 0) or the cap max_orders
  // (tolerance > 0).
  OrderProgress(const BakeContext& ctx, int last_order, double tolerance, int final_units);

  // The context of order k (k = 1, 2, ... in turn), mapped onto its share.
  BakeContext order_context(int k);
  // After order k >= 2: its residual, for the estimate of the orders left.
  void order_done(int k, double residual);

 private:
  BakeContext next_stage(double units_left);

  const BakeContext& ctx_;
  int last_order_;
  double tolerance_;
  int final_units_;
  int estimated_last_;
  double previous_residual_ = 1.0;
  double end_ = 0.0;
};

}  // namespace skybake
