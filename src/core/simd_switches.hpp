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
bool avx2_enabled();
// Turns the AVX2 versions off (false: SSE2 everywhere) or back on where the
// CPU has them. For tests and measurements; not meant to change mid-bake.
void set_avx2_enabled(bool enabled);

// True when the AVX-512 versions of the divider-bound loops run (the
// density's Mie loop): avx2_enabled() is, the CPU has AVX-512 F and DQ, and
// they are not off. Sixteen floats per square root or division, where the
// divider of a CPU with full-width AVX-512 (AMD Zen 5) takes about the time
// of AVX2's eight; each does the same IEEE operations per lane as its AVX2
// twin and adds into the same eight lanes, so the same bits.
bool avx512_enabled();
// Turns them off (false: AVX2 or SSE2) or back on where the CPU has them.
void set_avx512_enabled(bool enabled);

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

// SKYBAKE_AVX512 marks a function built for AVX-512 F and DQ. GCC's
// avx512f target brings FMA with it, and GCC fuses a product and a sum into
// one FMA by default (-ffp-contract=fast), which rounds once where the SSE2
// twin rounds twice: contraction is off in these functions (clang contracts
// only within one expression, never across intrinsics). Its calls of
// functions without the attribute are not inlined (other options).
#if SKYBAKE_HAS_AVX2 && defined(__clang__)
#define SKYBAKE_AVX512 __attribute__((target("avx512f,avx512dq")))
#elif SKYBAKE_HAS_AVX2
#define SKYBAKE_AVX512 __attribute__((target("avx512f,avx512dq"), optimize("fp-contract=off")))
#endif

// Around AVX-512 code: GCC 12's AVX-512 intrinsics start from
// _mm512_undefined_ps, which its -Wmaybe-uninitialized and -Wuninitialized
// report once inlined (false positives); clang does not.
#if defined(__GNUC__) && !defined(__clang__)
#define SKYBAKE_AVX512_WARNINGS_OFF                               \
  _Pragma("GCC diagnostic push")                                  \
  _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")   \
  _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")
#define SKYBAKE_AVX512_WARNINGS_ON _Pragma("GCC diagnostic pop")
#else
#define SKYBAKE_AVX512_WARNINGS_OFF
#define SKYBAKE_AVX512_WARNINGS_ON
#endif
