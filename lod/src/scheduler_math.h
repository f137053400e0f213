/*
 * scheduler_math.h -- private to tesslod::lod: the few functions of the
 * level rule that both the reference path and the fast kernels
 * (scheduler_fast.inc) evaluate, written once so that both give bitwise the
 * same result at every SIMD level: plain float operations in a fixed order
 * (no libm call, no FMA: the build has -ffp-contract=off), bit tricks
 * instead of frexp/ldexp/nextafter, so GCC and Clang vectorise them.
 */
#ifndef TESSLOD_SCHEDULER_MATH_H
#define TESSLOD_SCHEDULER_MATH_H

#include <stdint.h>
#include <string.h>

static inline uint32_t _tlod_bits(float x) {
  uint32_t u;
  memcpy(&u, &x, sizeof(u));
  return u;
}

static inline float _tlod_from_bits(uint32_t u) {
  float x;
  memcpy(&x, &u, sizeof(x));
  return x;
}

/* The smallest float >= x, for x >= 0 below FLT_MAX: the nearest float, one
 * ulp up when rounding went down (nextafterf of a non-negative float). */
static inline float _tlod_float_up(double x) {
  float f = (float)x;
  return _tlod_from_bits(_tlod_bits(f) + (uint32_t)((double)f < x)); /* branch-free: vectorises */
}

/* 2^x for 0 <= x (HYBRID's relax^(1-s) = 2^((1-s) log2 relax)): 2^n exactly
 * from the exponent bits, 2^f on [0, 1) by its Taylor polynomial of degree 7
 * (relative error below 2e-6: the relaxation is a heuristic factor, it need
 * not be correctly rounded, only the same everywhere). Infinity past 2^127. */
static inline float _tlod_exp2(float x) {
  int32_t n = (int32_t)(x < 128.0f ? x : 128.0f); /* x >= 0: truncation is floor */
  float f = x - (float)n;
  float p = 1.5252733804e-5f;
  p = p * f + 1.5403530393e-4f;
  p = p * f + 1.3333558146e-3f;
  p = p * f + 9.6181291076e-3f;
  p = p * f + 5.5504108665e-2f;
  p = p * f + 2.4022650696e-1f;
  p = p * f + 6.9314718056e-1f;
  p = p * f + 1.0f;
  float scale = n < 128 ? _tlod_from_bits((uint32_t)(n + 127) << 23) : (float)INFINITY;
  return p * scale;
}

/* log2 x for x >= 1, finite: the exponent plus log2 of the mantissa m in
 * [1, 2) by the atanh series of t = (m - 1) / (m + 1), |t| <= 1/3 (error
 * below 1e-6); exact 0 at m = 1, so powers of two give their exponent. */
static inline float _tlod_log2(float x) {
  uint32_t u = _tlod_bits(x);
  float e = (float)((int32_t)(u >> 23) - 127);
  float m = _tlod_from_bits((u & 0x007FFFFFu) | 0x3F800000u);
  float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  float p = 2.0f / 9.0f;
  p = p * t2 + 2.0f / 7.0f;
  p = p * t2 + 2.0f / 5.0f;
  p = p * t2 + 2.0f / 3.0f;
  p = p * t2 + 2.0f;
  return e + p * t * 1.4426950409f;
}

/* The smallest k >= 0 with 2^k >= x (SILHOUETTE's integral level for x
 * segments), as a float: ceil(log2 x) without rounding at the powers of
 * two. 0 for x <= 1 or NaN, 128 for infinity. */
static inline float _tlod_ceil_log2(float x) {
  if (!(x > 1.0f)) return 0.0f;
  uint32_t u = _tlod_bits(x);
  int32_t e = (int32_t)(u >> 23) - 127;
  return (float)(e + ((u & 0x007FFFFFu) != 0u));
}

#endif
