// Scratch arrays kept from call to call (per thread) by loops that run
// thousands of times with varying lengths: the error records' marches
// (atmosphere/sky_integrator.cpp, verify/psi_ms_reference.cpp).
#pragma once

#include <cstddef>
#include <vector>

namespace skybake {

// The first n entries of `v`, which grows to hold them but never shrinks:
// std::vector::resize value-initializes every entry it adds, so an array cut
// to a short march and grown back for a long one would be zeroed each time.
// The entries hold what the last writer left: the caller writes before it reads.
template <class T>
T* scratch_entries(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return v.data();
}

}  // namespace skybake
