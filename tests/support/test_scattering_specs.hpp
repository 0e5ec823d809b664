// Small precomputed-scattering tables for the tests of the Bruneton bakers
// (tests/atmosphere/scattering_*_test.cpp, irradiance_lut_test.cpp,
// tests/reference/extreme_bruneton_test.cpp): sizes that bake in a fraction
// of a second on Earth, so that a test can afford several bakes, and a
// suite hundreds of orders in a dense medium. Header only.
#pragma once

#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/scattering_orders.hpp"

namespace skybake::fixtures {

// The smallest 4D table of the tests: 8 r x 32 mu x 8 mu_s x 4 nu.
inline ScatteringShape tiny_scattering_shape() {
  return {8, 32, 8, 4, kBrunetonMuSMin};
}

// A bake of the table `shape` (its sizes and mu_s_min) with `orders`
// orders and coarse quadratures: 30 nodes per view ray, 8 zenith bands for
// the scattering density, a 16 x 4 irradiance table gathered over 8 bands.
// Callers change what their test needs on top.
inline BrunetonSpec small_bruneton_spec(const ScatteringShape& shape, int orders = 4) {
  BrunetonSpec spec;
  spec.r_size = shape.r_size;
  spec.mu_size = shape.mu_size;
  spec.mu_s_size = shape.mu_s_size;
  spec.nu_size = shape.nu_size;
  spec.mu_s_min = shape.mu_s_min;
  spec.orders = orders;
  spec.ray_nodes = 30;
  spec.density_directions = 8;
  spec.irradiance_width = 16;
  spec.irradiance_height = 4;
  spec.irradiance_directions = 8;
  return spec;
}

// The table of the orders' tests: 12 r x 48 mu x 12 mu_s x 4 nu.
inline ScatteringShape small_scattering_shape() {
  return {12, 48, 12, 4, kBrunetonMuSMin};
}

// small_bruneton_spec of small_scattering_shape() with a finer irradiance
// table, 32 x 8 gathered over 16 bands.
inline BrunetonSpec orders_test_spec(int orders) {
  BrunetonSpec spec = small_bruneton_spec(small_scattering_shape(), orders);
  spec.irradiance_width = 32;
  spec.irradiance_height = 8;
  spec.irradiance_directions = 16;
  return spec;
}

// Smaller still, for dense media that need hundreds of orders: the tiny
// table, 21 nodes per view ray, 6 density bands.
inline BrunetonSpec dense_medium_spec() {
  BrunetonSpec spec = small_bruneton_spec(tiny_scattering_shape());
  spec.ray_nodes = 21;
  spec.density_directions = 6;
  return spec;
}

}  // namespace skybake::fixtures
