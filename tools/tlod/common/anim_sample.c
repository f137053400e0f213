/* Sampling of glTF animation channels (glTF 2.0 section 3.11, appendix C
 * "Interpolation"): STEP, LINEAR with slerp for rotations (Shoemake,
 * "Animating rotation with quaternion curves", SIGGRAPH 1985), and the
 * cubic Hermite spline of CUBICSPLINE. Arithmetic in double, rounded once. */
#include <math.h>
#include <stddef.h>

#include "common/anim_sample.h"

uint32_t anim_path_components(anim_path path) { return path == ANIM_PATH_ROTATION ? 4u : 3u; }

/* Values of key k: CUBICSPLINE stores (in-tangent, value, out-tangent). */
static const float* key_value(const anim_channel* c, uint32_t k, uint32_t n) {
  return c->interp == ANIM_INTERP_CUBICSPLINE ? c->values + (size_t)(3 * k + 1) * n : c->values + (size_t)k * n;
}

static void copy_value(const float* v, uint32_t n, float out[4]) {
  for (uint32_t i = 0; i < n; i++)
    out[i] = v[i];
}

/* Unit length (a zero quaternion, which the importer refuses, stays zero). */
static void normalise(double q[4], float out[4]) {
  double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  double s = len > 0.0 ? 1.0 / len : 0.0;
  for (int i = 0; i < 4; i++)
    out[i] = (float)(q[i] * s);
}

/* Slerp from a to b the short way (b negated when the dot is negative);
 * nearly equal rotations lerp, where sin(theta) would lose the digits. */
static void slerp(const float* a, const float* b, double s, float out[4]) {
  double d = 0.0, q[4];
  for (int i = 0; i < 4; i++)
    d += (double)a[i] * b[i];
  double sign = d < 0.0 ? -1.0 : 1.0, wa = 1.0 - s, wb = s;
  d *= sign;
  if (d < 0.9995) {
    double theta = acos(d), st = sin(theta);
    wa = sin((1.0 - s) * theta) / st;
    wb = sin(s * theta) / st;
  }
  for (int i = 0; i < 4; i++)
    q[i] = wa * a[i] + wb * sign * b[i];
  normalise(q, out);
}

/* glTF appendix C: p(s) = (2s^3 - 3s^2 + 1) v_k + td (s^3 - 2s^2 + s) b_k
 * + (-2s^3 + 3s^2) v_k+1 + td (s^3 - s^2) a_k+1, td the key interval,
 * b_k the out-tangent of key k, a_k+1 the in-tangent of key k+1. */
static void hermite(const anim_channel* c, uint32_t k, uint32_t n, double s, double td, float out[4]) {
  const float* v0 = c->values + (size_t)(3 * k + 1) * n;
  const float* b0 = c->values + (size_t)(3 * k + 2) * n;
  const float* a1 = c->values + (size_t)(3 * (k + 1)) * n;
  const float* v1 = c->values + (size_t)(3 * (k + 1) + 1) * n;
  double s2 = s * s, s3 = s2 * s, q[4] = {0, 0, 0, 0};
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = (s3 - 2 * s2 + s) * td, h01 = -2 * s3 + 3 * s2, h11 = (s3 - s2) * td;
  for (uint32_t i = 0; i < n; i++)
    q[i] = h00 * v0[i] + h10 * b0[i] + h01 * v1[i] + h11 * a1[i];
  if (n == 4) {
    normalise(q, out);
  } else {
    for (uint32_t i = 0; i < n; i++)
      out[i] = (float)q[i];
  }
}

/* Last key k with times[k] <= t, for times[0] <= t < times[count - 1]. */
static uint32_t find_key(const float* times, uint32_t count, float t) {
  uint32_t lo = 0, hi = count - 1;
  while (hi - lo > 1) {
    uint32_t mid = lo + (hi - lo) / 2;
    if (times[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

static void interpolate(const anim_channel* c, uint32_t k, uint32_t n, float t, float out[4]) {
  double td = (double)c->times[k + 1] - c->times[k], s = ((double)t - c->times[k]) / td;
  if (c->interp == ANIM_INTERP_CUBICSPLINE) return hermite(c, k, n, s, td, out);
  const float *a = key_value(c, k, n), *b = key_value(c, k + 1, n);
  if (n == 4) return slerp(a, b, s, out);
  for (uint32_t i = 0; i < n; i++)
    out[i] = (float)((1.0 - s) * a[i] + s * (double)b[i]);
}

void anim_channel_sample(const anim_channel* c, float t, float out[4]) {
  uint32_t n = anim_path_components(c->path), last = c->key_count - 1;
  if (!(t > c->times[0]) || last == 0) return copy_value(key_value(c, 0, n), n, out);
  if (t >= c->times[last]) return copy_value(key_value(c, last, n), n, out);
  uint32_t k = find_key(c->times, c->key_count, t);
  if (c->interp == ANIM_INTERP_STEP) return copy_value(key_value(c, k, n), n, out);
  interpolate(c, k, n, t, out);
}

void anim_apply(const anim_channel* channels, uint32_t channel_count, float t, anim_trs* nodes, uint32_t node_count) {
  for (uint32_t i = 0; i < channel_count; i++) {
    const anim_channel* c = &channels[i];
    if (c->node >= node_count || c->key_count == 0) continue;
    anim_trs* trs = &nodes[c->node];
    float* dst = c->path == ANIM_PATH_TRANSLATION ? trs->translation
                 : c->path == ANIM_PATH_ROTATION  ? trs->rotation
                                                  : trs->scale;
    float v[4];
    anim_channel_sample(c, t, v);
    copy_value(v, anim_path_components(c->path), dst);
  }
}

float anim_duration(const anim_channel* channels, uint32_t channel_count) {
  float d = 0.0f;
  for (uint32_t i = 0; i < channel_count; i++)
    if (channels[i].key_count && channels[i].times[channels[i].key_count - 1] > d)
      d = channels[i].times[channels[i].key_count - 1];
  return d;
}
