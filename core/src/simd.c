/* tesslod::core -- which instruction set this processor has, and the one a
 * context's hot loops use (the lower of that and the desc's cap). Asked of
 * the processor each time (a few instructions): no process-global state. */
#include "internal.h"

tlod_simd _tlod_simd_best(void) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return TLOD_SIMD_AVX512;
  if (__builtin_cpu_supports("avx2")) return TLOD_SIMD_AVX2;
  if (__builtin_cpu_supports("sse2")) return TLOD_SIMD_SSE2;
#endif
  return TLOD_SIMD_SCALAR;
}

tlod_simd _tlod_simd_resolve(tlod_simd wanted) {
  tlod_simd best = _tlod_simd_best();
  return wanted == TLOD_SIMD_DEFAULT || wanted > best ? best : wanted;
}

tlod_simd tlod_context_simd(const tlod_context* ctx) { return ctx ? ctx->desc.simd : _tlod_simd_best(); }
