/* tesslod::core -- the face normals and corner angles of the computed
 * vertex normals (mesh_normals.c), in lanes, per instruction set.
 *
 * atan2(y, x) for y >= 0, the angle in [0, pi] between vectors with
 * |a x b| = y (given squared) and a . b = x, without libm (whose atan2
 * differs between libraries, so normals would, and is a call per corner).
 * Octants first (accurate near 0 and pi, where acos is not): lo = min(y,
 * |x|), hi = max, r = lo / hi in [0, 1]. Then atan(r) = k pi/16 + atan(s),
 * s = (r - t) / (1 + r t) = (lo - t hi) / (hi + t lo) with t = tan(k pi/16)
 * the nearest (|s| <= tan(pi/32), one division), and atan(s) by its Taylor
 * series to s^15 (the next term is below 2^-57 |s|): within a few ulps of
 * the exact angle (core/tests/core_angle_test.c). */
#include <math.h>
#include <stdbool.h>

#include "internal.h"

#define PI_D 3.14159265358979323846
/* tan((2k - 1) pi/32): the boundaries between the nearest k. */
#define MID1 0.09849140335716425
#define MID2 0.3033466836073424
#define MID3 0.5345111359507916
#define MID4 0.8206787908286602
/* tan(k pi/16) and k pi/16. */
#define TAN1 0.198912367379658
#define TAN2 0.41421356237309503
#define TAN3 0.6681786379192989
#define AT1 0.19634954084936207
#define AT2 0.39269908169872414
#define AT3 0.5890486225480862
#define AT4 0.7853981633974483

typedef void (*angle_kernel)(const double* y2, const double* x, double* w, uint32_t n);
typedef void (*face_kernel)(_tlod_face_lanes* lanes, uint32_t n);

#define KERNEL_FILE "mesh_angles.inc"
#include "simd_instances.inc"

void _tlod_corner_angles(tlod_simd simd, const double* y2, const double* x, double* w, uint32_t n) {
  angle_kernel k = KERNEL_FOR(angles, simd);
  k(y2, x, w, n);
}

void _tlod_face_normals(tlod_simd simd, _tlod_face_lanes* lanes, uint32_t n) {
  face_kernel k = KERNEL_FOR(faces, simd), c = KERNEL_FOR(corners, simd);
  k(lanes, n);
  c(lanes, n);
}
