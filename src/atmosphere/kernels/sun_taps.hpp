// The sun-angle taps of a whole texel row at once, for the bakers' hottest
// loops: the orders' mu_s taps (MuSAxis::taps, the mu_s mapping of Bruneton
// 2017 GetScatteringTextureUvwzFromRMuMuSNu) and single scattering's
// transmittance to the sun (TransmittanceReader::add_sun_products, Bruneton
// 2017 GetTransmittanceToSun), several cosines in the lanes of one group.
// Every value equals the one-at-a-time function's (tests/atmosphere/
// kernels_test.cpp).
#pragma once

#include "atmosphere/scattering_lut.hpp"

namespace skybake {

// What the sun taps read of the transmittance table: its top radius, width
// in texels and floats per texel.
struct SunTapTable {
  double rt;
  int width, stride;
};

// MuSAxis::tap(mu_s[k]) for k < n: i0[k] and w[k] (i1 = i0 + 1).
void mu_s_taps(const MuSAxis::Constants& c, const double* mu_s, int n, int* i0, double* w);

// sums[c][k] += a_rayleigh[c] T_k and sums[3 + c][k] += a_mie[c] T_k for
// k < n, T_k = TransmittanceReader::to_sun(row, mu_s_k), mu_s_k sun k's
// zenith cosine at the node (NodeSuns, clamp_cosine as min / max: the same
// value); the work arrays are the caller's, reused.
void add_sun_products(const SunTapTable& table, const TransmittanceReader::Row& row,
                      const NodeSuns& suns, int n, const glm::dvec3& a_rayleigh,
                      const glm::dvec3& a_mie, double* const sums[6], SunTapScratch& scratch);

}  // namespace skybake
