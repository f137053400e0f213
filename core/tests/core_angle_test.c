/* White-box: the corner angles of the normals (mesh_angles.c) against libm's
 * atan2 in double, at every simd level the processor has, and bitwise equal
 * across the levels. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "internal.h"
#include "test.h"

enum { LANES = 4099 }; /* not a multiple of any vector width: the tails run too */

/* A deterministic spread of (|a x b|, a . b): every octant, magnitudes over
 * 2^-40..2^40, near 0, pi/2 and pi. */
static void make_inputs(double* y2, double* x) {
  uint64_t r = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < LANES; i++) {
    r = r * 6364136223846793005ull + 1442695040888963407ull;
    double u = (double)(r >> 11) * 0x1p-53, v = (double)((r >> 3) & 0xFFFFF) * 0x1p-20;
    double scale = ldexp(1.0, (int)(r % 81) - 40), y = u * scale, xx = (2.0 * v - 1.0) * scale;
    if (i % 5 == 1) xx = y * (1.0 + 1e-9 * v); /* near pi/4 */
    if (i % 7 == 2) y = 1e-9 * fabs(xx);       /* near 0 or pi */
    if (i % 11 == 3) xx = 1e-12 * y;           /* near pi/2 */
    y2[i] = y * y;
    x[i] = xx;
  }
  y2[0] = 0.0, x[0] = 0.0;  /* degenerate: 0 */
  y2[1] = 0.0, x[1] = 2.0;  /* 0 */
  y2[2] = 0.0, x[2] = -2.0; /* pi */
  y2[3] = 4.0, x[3] = 0.0;  /* pi/2 */
  y2[4] = 4.0, x[4] = 2.0;  /* pi/4 */
}

TEST(angles_match_atan2) {
  static double y2[LANES], x[LANES], w[LANES], ref[LANES];
  make_inputs(y2, x);
  _tlod_corner_angles(TLOD_SIMD_SCALAR, y2, x, ref, LANES);
  double worst = 0.0;
  for (int i = 0; i < LANES; i++) {
    double exact = atan2(sqrt(y2[i]), x[i]);
    double err = fabs(ref[i] - exact) / (exact > 1e-300 ? exact : 1.0);
    worst = fmax(worst, err);
  }
  CHECK_MSG(worst <= 8.0 * 0x1p-53, "worst relative error %.3g", worst);
  CHECK(ref[0] == 0.0 && ref[1] == 0.0);
  CHECK_NEAR(ref[2], 3.14159265358979323846, 4e-16);
  CHECK_NEAR(ref[3], 1.57079632679489661923, 4e-16);
  CHECK_NEAR(ref[4], 0.78539816339744830962, 4e-16);
  /* The levels this processor has (a default context takes the best). */
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  int best = (int)tlod_context_simd(ctx);
  tlod_context_destroy(ctx);
  for (int level = TLOD_SIMD_SSE2; level <= best; level++) {
    memset(w, 0, sizeof(w));
    _tlod_corner_angles((tlod_simd)level, y2, x, w, LANES);
    CHECK_MSG(memcmp(w, ref, sizeof(w)) == 0, "level %d", level);
  }
}

/* Random triangles and quads (float corners) in the lanes of the face kernel. */
static void make_faces(_tlod_face_lanes* l) {
  uint64_t r = 0x2545F4914F6CDD1Dull;
  for (int i = 0; i < _TLOD_FACE_LANES; i++) {
    for (int c = 0; c < 4; c++)
      for (int d = 0; d < 3; d++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        l->p[3 * c + d][i] = (double)(float)(ldexp((double)(r >> 11), -53) * 8.0 - 4.0);
      }
    l->quad[i] = i % 3 == 0 ? 0.0 : 1.0;
    for (int d = 0; l->quad[i] == 0.0 && d < 3; d++) /* a triangle repeats corner 0 */
      l->p[9 + d][i] = l->p[d][i];
  }
}

/* The flat corners' |a x b|^2 and a . b (a = e_c, b = -e_prev, e_i = p_next
 * - p_i) written out per face, against the lanes at every level, bitwise. */
TEST(flat_corners_match_their_tangents) {
  static _tlod_face_lanes l;
  make_faces(&l);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  int best = (int)tlod_context_simd(ctx), bad = 0;
  tlod_context_destroy(ctx);
  for (int level = TLOD_SIMD_SCALAR; level <= best; level++) {
    _tlod_face_normals((tlod_simd)level, &l, _TLOD_FACE_LANES - 3);
    for (int i = 0; i < _TLOD_FACE_LANES - 3; i++) {
      int k = l.quad[i] != 0.0 ? 4 : 3;
      for (int c = 0; c < k; c++) {
        int next = (c + 1) % k, prev = (c + k - 1) % k, pp = (prev + 1) % k;
        double a[3], b[3];
        for (int d = 0; d < 3; d++)
          a[d] = l.p[3 * next + d][i] - l.p[3 * c + d][i], b[d] = -(l.p[3 * pp + d][i] - l.p[3 * prev + d][i]);
        double x0 = a[1] * b[2] - a[2] * b[1], x1 = a[2] * b[0] - a[0] * b[2], x2 = a[0] * b[1] - a[1] * b[0];
        double y2 = x0 * x0 + x1 * x1 + x2 * x2, x = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        bad += memcmp(&y2, &l.y2[c][i], sizeof y2) != 0 || memcmp(&x, &l.x[c][i], sizeof x) != 0;
      }
    }
  }
  CHECK_MSG(bad == 0, "%d corners differ", bad);
}

int main(void) {
  RUN(angles_match_atan2);
  RUN(flat_corners_match_their_tangents);
  TEST_END();
}
