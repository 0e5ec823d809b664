// How far the 4D table's read between mu texels is from the quadrature it
// stands for, measured on the second order while its density is at hand: a
// bake-time check that the table resolves its sky (docs/decisions/warnings.md,
// `coarse_table`). Baked with J_k in the sun's frame only (the default).
//
// Sampled at the r texels 0 and r_size / 2 and every 8th mu_s texel, where
// only mu or only nu is between texels: at the midpoints between adjacent
// mu texels of one half of the axis (never across the horizon) on every
// 4th nu slice, and at every 8th mu texel halfway between each two nu
// slices (each where the midpoint's mu and mu_s allow its nu). DeltaS_2 by
// the ray quadrature over the density (compute_multiple_scattering)
// against the table's read (lookup_scattering_rgb of DeltaS_2); the RMS of
// the relative differences of every channel whose DeltaS_2 is above 1e-3
// of the samples' largest. Earth's 32 x 128 x 32 x 8 table: 0.9 %; the tiny
// planet's: 0.7 %; Mars at 32 x 128 x 64 x 16: 3.2 %; a 10 km shell of
// dust of g = 0.85 (tests/reference/thin_slab_orders_test.cpp), whose
// second order the table reads several times off near the sun: 9.2 %.
#pragma once

#include "atmosphere/medium.hpp"
#include "atmosphere/scattering_lut.hpp"
#include "atmosphere/sun_frame_density.hpp"
#include "core/texture.hpp"

namespace skybake {

// Above this (RMS, relative) a bake warns: coarse_table.
constexpr double kMidTexelErrorLimit = 0.05;

double mid_texel_error(const Atmosphere& atm, const SunFrameDensity& J_per_sigma_s,
                       const Texture& delta, int nodes);

}  // namespace skybake
