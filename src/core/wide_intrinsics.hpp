// The intrinsics of the hand-vectorized loops: SSE2's everywhere it exists,
// AVX2's where its twins are built (core/wide_vectors.hpp). For the .cpp
// files that hold such loops only; headers include wide_vectors.hpp, whose
// switch is all their users need.
#pragma once

#include "core/wide_vectors.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if SKYBAKE_HAS_AVX2
#include <immintrin.h>
#endif
