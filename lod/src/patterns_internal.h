/*
 * patterns_internal.h -- layout of tlod_patterns (private to tesslod::lod).
 * Owned by the refinement-pattern code (pattern_refine.c); other modules
 * should prefer the public functions of tesslod/lod.h.
 *
 * This work is based on: Schwarz, Staginski, Stamminger 2006; Boubekeur &
 * Schlick 2005 (generic mesh refinement on GPU).
 */
#ifndef TESSLOD_PATTERNS_INTERNAL_H
#define TESSLOD_PATTERNS_INTERNAL_H

#include "tesslod/lod.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One shape (triangle or quad) at every level 0..max_level. */
typedef struct _tlod_pattern_set {
  uint32_t corner_count; /* 3 or 4 */
  /* Shared vertex array of the finest level, sorted by first level, so
   * level l uses the prefix of length tlod_pattern_vertex_count(shape, l).
   * The first corner_count entries are the corners, in corner order
   * (triangle: i, j, k; quad: 0, 1, 2, 3). */
  tlod_pattern_vertex* vertices;
  uint32_t vertex_count;
  /* One index array per level: CCW triples into vertices. */
  uint32_t* indices[TLOD_MAX_LEVEL + 1];
  uint32_t index_count[TLOD_MAX_LEVEL + 1];
  /* Edge e at the finest level: 2^max_level + 1 vertex indices from corner
   * e to corner (e + 1) % corner_count, stored as corner_count rows.
   * Level l takes every 2^(max_level - l)-th entry. */
  uint32_t* edges;
} _tlod_pattern_set;

struct tlod_patterns {
  tlod_context* ctx;
  uint32_t max_level;
  _tlod_pattern_set sets[TLOD_PATTERN_SHAPE_NUM];
  /* Connection patterns per (la, lb): triangles of point references. */
  uint32_t (*connect[TLOD_MAX_LEVEL + 1][TLOD_MAX_LEVEL + 1])[3];
  uint32_t connect_count[TLOD_MAX_LEVEL + 1][TLOD_MAX_LEVEL + 1];
  /* The same without the triangles degenerate where shared points coincide. */
  uint32_t (*connect_exact[TLOD_MAX_LEVEL + 1][TLOD_MAX_LEVEL + 1])[3];
  uint32_t connect_exact_count[TLOD_MAX_LEVEL + 1][TLOD_MAX_LEVEL + 1];
};

/* pattern_connect.c: builds and frees every (la, lb) connection pattern. */
tlod_result _tlod_patterns_build_connections(tlod_patterns* p);
void _tlod_patterns_free_connections(tlod_patterns* p);

#ifdef __cplusplus
}
#endif
#endif
