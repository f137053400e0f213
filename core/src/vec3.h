/* Private small-vector helpers. Kept inline and in one evaluation order so
 * that every caller rounds identically (docs/design.md invariant 1). */
#ifndef TESSLOD_VEC3_H
#define TESSLOD_VEC3_H

#include <math.h>

typedef struct v3 {
  float x, y, z;
} v3;

static inline v3 v3_load(const float* p) { return (v3){p[0], p[1], p[2]}; }
static inline void v3_store(float* p, v3 a) {
  p[0] = a.x;
  p[1] = a.y;
  p[2] = a.z;
}
static inline v3 v3_add(v3 a, v3 b) { return (v3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline v3 v3_sub(v3 a, v3 b) { return (v3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline v3 v3_scale(v3 a, float s) { return (v3){a.x * s, a.y * s, a.z * s}; }
static inline float v3_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline v3 v3_cross(v3 a, v3 b) {
  return (v3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline float v3_length(v3 a) { return sqrtf(v3_dot(a, a)); }
/* a * s + b * t, in this order. */
static inline v3 v3_mix2(v3 a, float s, v3 b, float t) { return v3_add(v3_scale(a, s), v3_scale(b, t)); }
static inline v3 v3_mix3(v3 a, float s, v3 b, float t, v3 c, float r) {
  return v3_add(v3_add(v3_scale(a, s), v3_scale(b, t)), v3_scale(c, r));
}
/* Unit vector; a zero vector stays zero (callers fall back on a valid normal).
 * Where the squared length under- or overflows (a cross product of tangents
 * on a tiny or huge patch), the vector is first divided by its largest
 * component, so the result is unit there too; in between, one rounding
 * order as always. */
static inline v3 v3_normalize(v3 a) {
  float len = v3_length(a);
  if (len > 1e-18f && len < 1e18f) return v3_scale(a, 1.0f / len);
  float m = fmaxf(fabsf(a.x), fmaxf(fabsf(a.y), fabsf(a.z)));
  if (!(m > 0.0f) || !isfinite(m)) return a;
  v3 b = {a.x / m, a.y / m, a.z / m};
  return v3_scale(b, 1.0f / v3_length(b));
}
/* normalize(n), or fallback where n is zero (a valid normal, callers' choice). */
static inline v3 v3_normalize_or(v3 n, v3 fallback) {
  v3 u = v3_normalize(n);
  return (u.x == 0.0f && u.y == 0.0f && u.z == 0.0f) ? fallback : u;
}
/* Phong projection of q onto the tangent plane of (p, n). */
static inline v3 v3_project(v3 q, v3 p, v3 n) { return v3_sub(q, v3_scale(n, v3_dot(v3_sub(q, p), n))); }
/* (I - n n^T) d: the derivative of the projection along d. */
static inline v3 v3_reject(v3 d, v3 n) { return v3_sub(d, v3_scale(n, v3_dot(d, n))); }

#endif
