// Whether the loops still written per instruction set take their AVX2
// versions (four doubles per instruction instead of SSE2's two): where the
// CPU has AVX2 and the loops were built for x86-64 by GCC or clang, unless
// turned off. Each does the same IEEE operations on the same operands in the
// same order as its SSE2 twin, without FMA, so the bits are the same either
// way; only the time changes. The kernels of atmosphere/kernels/ are
// dispatched by Highway instead (docs/architecture.md "Kernels").
#pragma once

namespace skybake {

// True when the AVX2 versions run: the CPU has AVX2 and they are not off.
bool avx2_enabled();
// Turns the AVX2 versions off (false: SSE2 everywhere) or back on where the
// CPU has them. For tests and measurements; not meant to change mid-bake.
void set_avx2_enabled(bool enabled);

}  // namespace skybake

// SKYBAKE_AVX2 marks a function built for AVX2 (without FMA: an FMA rounds
// once where the SSE2 twin rounds twice). SKYBAKE_HAS_AVX2 is 1 where such
// functions are built at all.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SKYBAKE_HAS_AVX2 1
#define SKYBAKE_AVX2 __attribute__((target("avx2")))
#else
#define SKYBAKE_HAS_AVX2 0
#define SKYBAKE_AVX2
#endif
