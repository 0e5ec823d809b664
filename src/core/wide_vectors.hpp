// Whether the bakers' hand-vectorized loops take their AVX2 versions (eight
// floats or four doubles per instruction instead of SSE2's four or two):
// where the CPU has AVX2 and the loops were built for x86-64 by GCC or
// clang, unless turned off. Each AVX2 loop does the same IEEE operations on
// the same operands in the same order as its SSE2 twin, without FMA, so the
// bits are the same either way (the tests bake both and compare); only the
// time changes. The AVX2 functions are written out, not generated from one
// template: a 256-bit value passed between functions built for different
// targets changes the calling convention, which an unoptimized build does not
// inline away.
#pragma once

namespace skybake {

// True when the AVX2 versions run: the CPU has AVX2 and they are not off.
bool wide_vectors();
// Turns the AVX2 versions off (false: SSE2 everywhere) or back on where the
// CPU has them. For tests and measurements; not meant to change mid-bake.
void set_wide_vectors(bool enabled);

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
