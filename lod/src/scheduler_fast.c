/* tesslod::lod -- the fast path's kernels, one copy per SIMD level of the
 * one source scheduler_fast.inc (built with -O3 so the loops vectorise; the
 * global -ffp-contract=off keeps FMAs out, so every copy gives bitwise the
 * same results), and the choice among them. */
#include <float.h>
#include <math.h>
#include <string.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "scheduler_fast.h"
#include "scheduler_math.h"

/* SCALAR: no vector instructions chosen by tesslod (GCC would otherwise
 * vectorise the baseline copy with SSE2). */
#if defined(__GNUC__) && !defined(__clang__)
#define FAST_ATTR __attribute__((optimize("no-tree-vectorize")))
#else
#define FAST_ATTR
#endif
#define FAST_NAME(x) x##_scalar
#include "scheduler_fast.inc"
#undef FAST_ATTR
#undef FAST_NAME

#if defined(__x86_64__)
#define FAST_ATTR __attribute__((target("sse2")))
#define FAST_NAME(x) x##_sse2
#include "scheduler_fast.inc"
#undef FAST_ATTR
#undef FAST_NAME

#define FAST_ATTR __attribute__((target("avx2")))
#define FAST_NAME(x) x##_avx2
#include "scheduler_fast.inc"
#undef FAST_ATTR
#undef FAST_NAME

#define FAST_ATTR __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))
#define FAST_NAME(x) x##_avx512
#define FAST_AVX512_KERNELS /* the scales and the ERROR ladder in registers (scales8, error_targets8) */
#include "scheduler_fast.inc"
#undef FAST_AVX512_KERNELS
#undef FAST_ATTR
#undef FAST_NAME
#endif

_tlod_fast_kernels _tlod_fast_kernels_for(tlod_simd simd) {
#if defined(__x86_64__)
  switch (simd) {
  case TLOD_SIMD_AVX512:
    return (_tlod_fast_kernels){vertices_avx512, patches_avx512, classify_avx512};
  case TLOD_SIMD_AVX2:
    return (_tlod_fast_kernels){vertices_avx2, patches_avx2, classify_avx2};
  case TLOD_SIMD_SSE2:
    return (_tlod_fast_kernels){vertices_sse2, patches_sse2, classify_sse2};
  default:
    break;
  }
#else
  (void)simd;
#endif
  return (_tlod_fast_kernels){vertices_scalar, patches_scalar, classify_scalar};
}
