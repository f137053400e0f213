/*
 * scheduler_fast.h -- private to tesslod::lod: the fast path of the
 * per-patch stages (silhouette, metric, levels, morph) over
 * structure-of-arrays copies of the mesh and surface (scheduler_soa.c),
 * fused into one pass per vertex and one per patch (scheduler_fast.inc,
 * compiled once per SIMD level by scheduler_fast.c and chosen at create from
 * tlod_context_simd()). Bitwise the reference path's results: the same
 * float and double operations in the same order (docs/design.md 3.13).
 */
#ifndef TESSLOD_SCHEDULER_FAST_H
#define TESSLOD_SCHEDULER_FAST_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/lod.h"

#define FAST_BLOCK 256 /* patches per block of the fused patch pass */

/* cont of a culled patch: no morph history, it appears at its goal. */
#define _TLOD_NO_HISTORY (-1.0f)

/* Inputs the passes read, copied at the first update and again whenever
 * the mesh or surface generation moved. */
typedef struct _tlod_soa {
  uint64_t mesh_generation, surface_generation; /* 0: not built */
  uint32_t patch_count, vertex_count, levels;   /* levels = max_level + 1 */
  float *cx, *cy, *cz, *radius;                 /* bounding spheres */
  float* bound;                                 /* bound[l * patch_count + f] = tlod_patch_error_bound(f, l) */
  uint32_t* corner;                             /* corner[c * patch_count + f]; a triangle repeats corner 0 */
  float *px, *py, *pz, *nx, *ny, *nz;           /* vertex positions and normals */
  /* Per vertex, this frame: the bits of d_i, the sign bit set where
   * n . (eye - p) > 0 (the normal faces the camera). */
  uint32_t* packed;
} _tlod_soa;

/* One view's frame as the kernels see it: constants and arrays. */
typedef struct _tlod_fast_frame {
  const _tlod_soa* soa;
  /* camera */
  float eye[3], forward[3], planes[6][4];
  bool ortho, cull;
  double V[16];            /* the view matrix, widened */
  double f, tx, ty, znear; /* tlod_patch_projection_scale's frame constants */
  float ortho_scale;
  /* level rule */
  float m, eps, log2_relax;
  tlod_lod_policy policy;
  uint32_t max_level;
  bool fuse; /* targets and morph too (no budget, not locked) */
  bool fractional, timed, bounded;
  bool cull_skip; /* _tlod_frame.cull_skip */
  float step;
  /* outputs, one view's arrays */
  float *depth, *scale, *e_max, *contour, *target, *cont;
  uint8_t* visible;
} _tlod_fast_frame;

typedef struct _tlod_fast_kernels {
  void (*vertices)(const _tlod_fast_frame* k, uint32_t begin, uint32_t end);
  void (*patches)(const _tlod_fast_frame* k, uint32_t begin, uint32_t end);
} _tlod_fast_kernels;

/* The kernels of SIMD level simd (never DEFAULT): the best compiled one not above it. */
_tlod_fast_kernels _tlod_fast_kernels_for(tlod_simd simd);

#endif
