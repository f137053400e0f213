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

#define FAST_BLOCK 128 /* patches per block (cluster) of the fused patch pass */
/* A partly culled block with fewer than COMPACT_NUM / COMPACT_DEN of its
 * patches visible measures them gathered densely (the dense loops would
 * spend more on the culled ones than the gather costs). */
#define COMPACT_NUM 3
#define COMPACT_DEN 4
#define FAST_VCHUNK 256 /* vertices per chunk of the vertex pass */

/* A block's frustum state this frame (scheduler_blocks.c). */
enum { _TLOD_BLOCK_PARTIAL = 0, _TLOD_BLOCK_OUT = 1, _TLOD_BLOCK_IN = 2 };

/* A block's bounding sphere, in double: |c_i - c| + r_i <= r for each of
 * its patches i; l1 = sum over the axes of max_i |c_i|, for the rounding
 * margin of the patches' float plane tests. valid: every patch sphere
 * finite with r_i >= 0 (else the block is always tested patch by patch). */
typedef struct _tlod_block {
  double c[3], r, l1;
  bool valid;
} _tlod_block;

/* Relative slack of the blocks' double sums (each well under 1e-15). */
#define _TLOD_BLOCK_SLACK 1e-12

/* The frustum planes' terms of the block test that do not depend on the
 * block, made once a frame (scheduler_blocks.c): per plane p its
 * coefficients, n = |p.xyz| (1 + slack), n1 = max(n, 1), base = max |p_k|
 * and |p3|. */
typedef struct _tlod_plane_terms {
  double p[6][4], n[6], n1[6], base[6], d_abs[6];
} _tlod_plane_terms;

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
  /* Clusters: FAST_BLOCK patches each; per chunk of FAST_VCHUNK vertices
   * the blocks that use one of its vertices, chunk_blocks[chunk_first[j] ..
   * chunk_first[j + 1]) (scheduler_blocks.c). */
  uint32_t block_count, chunk_count, chunk_capacity;
  double *bx, *by, *bz, *br, *bl1; /* the blocks' spheres (_tlod_block), one array a field */
  uint8_t* bvalid;
  uint32_t *chunk_first, *chunk_blocks; /* chunk_capacity entries */
  uint8_t* block_state;                 /* this frame's, one view at a time */
  /* held[v * block_count + b]: view v's visible, e_max, target, cont and
   * draw-list levels of block b hold a culled block's constants (written by
   * a fused frame). seen[v * block_count + b]: view v's block b has a
   * visible patch (written by every fused frame, read by its draw list). */
  uint8_t *held, *seen;
  uint32_t held_views;
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
  uint8_t *held, *seen; /* this view's rows of soa->held and soa->seen */
  int8_t* levels;       /* the view's draw-list levels (-1 culled), for a fused frame's culled blocks */
  /* A block measured gathered (_tlod_fast_local): soa->bound holds its
   * level 0 only, and the ladder gathers a level above it into
   * gather_into (stride FAST_BLOCK) from gather_bound (the whole table,
   * gather_n patches a level) at gather_idx when it first reads the level,
   * so a block stopped at level l reads l + 1 levels. NULL: not gathered. */
  const uint32_t* gather_idx;
  const float* gather_bound;
  float* gather_into;
  uint32_t gather_n;
} _tlod_fast_frame;

/* A partly culled block's visible patches gathered densely (stride
 * FAST_BLOCK), so that the kernels measure only them: soa and frame point
 * at these arrays (scheduler_fast.inc, compact_block). */
typedef struct _tlod_fast_local {
  _tlod_soa soa;
  _tlod_fast_frame k;
  uint32_t idx[FAST_BLOCK];
  float cx[FAST_BLOCK], cy[FAST_BLOCK], cz[FAST_BLOCK], radius[FAST_BLOCK];
  float bound[(TLOD_MAX_LEVEL + 1) * FAST_BLOCK];
  uint32_t corner[4 * FAST_BLOCK];
  float e_max[FAST_BLOCK], target[FAST_BLOCK], cont[FAST_BLOCK];
  uint8_t visible[FAST_BLOCK];
} _tlod_fast_local;

/* Over ranges of clusters: vertex chunks and patch blocks; classify sets
 * a->block_state of blocks [begin, end) against the planes (OUT only if
 * every patch's own float test culls it, IN only if every patch's own
 * test keeps it: scheduler_blocks.c proves the margin). */
typedef struct _tlod_fast_kernels {
  void (*vertices)(const _tlod_fast_frame* k, uint32_t chunk_begin, uint32_t chunk_end);
  void (*patches)(const _tlod_fast_frame* k, uint32_t block_begin, uint32_t block_end);
  void (*classify)(_tlod_soa* a, const _tlod_plane_terms* t, uint32_t begin, uint32_t end);
} _tlod_fast_kernels;

/* scheduler_blocks.c. The block spheres and chunk lists of a (just
 * copied) a: false when out of memory. */
bool _tlod_blocks_build(tlod_context* ctx, _tlod_soa* a);
/* a->held and a->seen for views views (new rows zero: nothing held). */
bool _tlod_blocks_hold(tlod_context* ctx, _tlod_soa* a, uint32_t views);
/* a->block_state of every block against planes; all IN unless cull. OUT
 * only if every patch's own float test culls it, IN only if every
 * patch's own test keeps it. */
void _tlod_blocks_classify(_tlod_soa* a, const _tlod_fast_kernels* kernels, const float planes[6][4], bool cull);
void _tlod_blocks_free(tlod_context* ctx, _tlod_soa* a);

/* The kernels of SIMD level simd (never DEFAULT): the best compiled one not above it. */
_tlod_fast_kernels _tlod_fast_kernels_for(tlod_simd simd);

#endif
