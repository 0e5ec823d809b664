// The three functions of Highway's run-time dispatch (hwy/targets.h) that the
// kernels call: which SIMD targets this CPU runs, the chosen-target cache,
// and the tests' override. Defined here instead of linking libhwy, whose
// load-time initialiser calibrates a timer for about 3 ms of CPU in every
// process, `skybake --version` included (docs/decisions/one-source-kernels.md).
//
// A target is supported when the CPU (and the OS, for the AVX state) has every
// feature Highway compiles that target with (hwy/ops/set_macros-inl.h,
// HWY_TARGET_STR_*); __builtin_cpu_supports checks the OS's XSAVE state for
// the AVX and AVX-512 features. Clang's builtin does not know "f16c", so that
// one bit is read from CPUID leaf 1 (ECX bit 29) on both compilers; the AVX
// state it needs is the one the "avx" test already checked.
#include <atomic>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

#include <hwy/targets.h>

namespace hwy {
namespace {

std::atomic<int64_t> targets_for_test{0};

bool has_sse4_features() {
  return __builtin_cpu_supports("sse2") && __builtin_cpu_supports("ssse3") &&
         __builtin_cpu_supports("sse4.1") && __builtin_cpu_supports("sse4.2") &&
         __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("aes");
}

#if defined(__x86_64__) || defined(__i386__)
bool has_f16c() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  return (ecx & (1u << 29)) != 0;
}
#endif

bool has_avx2_features() {
  return has_sse4_features() && __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
         __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
         __builtin_cpu_supports("fma") && has_f16c();
}

bool has_avx3_features() {
  return has_avx2_features() && __builtin_cpu_supports("avx512f") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512bw");
}

int64_t cpu_targets() {
  int64_t bits = HWY_SCALAR | HWY_EMU128;
#if HWY_ARCH_X86
  __builtin_cpu_init();
  if (has_sse4_features()) bits |= HWY_SSSE3 | HWY_SSE4;
  if (has_avx2_features()) bits |= HWY_AVX2;
  if (has_avx3_features()) bits |= HWY_AVX3;
#endif
  return bits;
}

}  // namespace

int64_t SupportedTargets() {
  static const int64_t detected = cpu_targets();
  const int64_t for_test = targets_for_test.load();
  const int64_t bits = for_test != 0 ? for_test : detected;
  // Never empty: the target the file was compiled for always runs.
  return bits != 0 ? bits : HWY_STATIC_TARGET;
}

void SetSupportedTargetsForTest(int64_t targets) {
  targets_for_test.store(targets);
  GetChosenTarget().DeInit();  // the next dispatch chooses again
}

ChosenTarget& GetChosenTarget() {
  static ChosenTarget chosen;
  return chosen;
}

}  // namespace hwy
