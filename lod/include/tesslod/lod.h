/*
 * tesslod/lod.h -- refinement patterns (module tesslod::lod)
 *
 * WHAT IT DOES
 *   Builds the nested refinement patterns of Schwarz, Staginski and
 *   Stamminger ("GPU-based rendering of PN triangle meshes with adaptive
 *   tessellation", 2006): pattern l splits a triangle (or a quad) by l
 *   successive 1-to-4 splits, so it has 2^l - 1 inserted vertices per edge,
 *   4^l triangles (quads: 2 * 4^l triangles on a (2^l + 1)^2 grid).
 *   All levels share one vertex array: the vertices of level l are the
 *   first tlod_pattern_vertex_count(shape, l) entries, and each vertex first
 *   inserted at level l > 0 names its two parents at level l - 1 (the
 *   endpoints of the coarser edge it splits), which geomorphs blend from.
 *
 * DOES NOT
 *   evaluate surfaces (tesslod/core.h) or draw anything (backends).
 *
 * ORIENTATION
 *   Triangles are counter-clockwise in (u, v) for the triangle (u=1 at corner
 *   i, v=1 at corner j, w=1 at corner k), and for the quad (0,0) (1,0) (1,1)
 *   (0,1), so they keep the input face's winding.
 */
#ifndef TESSLOD_LOD_H
#define TESSLOD_LOD_H

#include "tesslod/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TLOD_MAX_LEVEL 10
#define TLOD_DEFAULT_MAX_LEVEL 6

typedef enum tlod_pattern_shape {
  TLOD_PATTERN_TRIANGLE = 0,
  TLOD_PATTERN_QUAD = 1,
  TLOD_PATTERN_SHAPE_NUM,
  _TLOD_PATTERN_SHAPE_FORCE_U32 = 0x7FFFFFFF
} tlod_pattern_shape;

typedef struct tlod_pattern_vertex {
  /* Grid coordinates over 2^max_level: u = i / 2^max_level, v = j / 2^max_level
   * (exact in float, so edge points are exactly on the edge). */
  uint16_t i, j;
  float u, v;
  uint8_t level;      /* level that first inserts it (0: a corner) */
  uint32_t parent[2]; /* vertex indices at level - 1; both UINT32_MAX for corners */
} tlod_pattern_vertex;

typedef struct tlod_patterns tlod_patterns;

typedef struct tlod_patterns_desc {
  uint32_t max_level; /* 0 == TLOD_DEFAULT_MAX_LEVEL (6); at most TLOD_MAX_LEVEL */
} tlod_patterns_desc;

/* Vertices of pattern `level` (pure; no patterns object needed). */
TLOD_API uint32_t tlod_pattern_vertex_count(tlod_pattern_shape shape, uint32_t level);
/* Triangles of pattern `level`: 4^l (triangle), 2 * 4^l (quad). */
TLOD_API uint32_t tlod_pattern_triangle_count(tlod_pattern_shape shape, uint32_t level);

TLOD_API tlod_result tlod_patterns_create(tlod_context* ctx, const tlod_patterns_desc* desc, tlod_patterns** out);
TLOD_API void tlod_patterns_destroy(tlod_patterns* patterns);
TLOD_API uint32_t tlod_patterns_max_level(const tlod_patterns* patterns);
/* The shared vertex array (finest level); *count receives its length. */
TLOD_API const tlod_pattern_vertex* tlod_patterns_vertices(const tlod_patterns* patterns, tlod_pattern_shape shape,
                                                           uint32_t* count);
/* Index triples of pattern `level` into the shared vertex array. */
TLOD_API const uint32_t* tlod_patterns_indices(const tlod_patterns* patterns, tlod_pattern_shape shape, uint32_t level,
                                               uint32_t* index_count);
/* Vertices along edge e of pattern `level`, from corner e to corner (e+1) % n
 * (corners: triangle i, j, k; quad 0..3): 2^level + 1 vertex indices
 * written to out. Returns the count. */
TLOD_API uint32_t tlod_patterns_edge(const tlod_patterns* patterns, tlod_pattern_shape shape, uint32_t level,
                                     uint32_t edge, uint32_t* out);
/* Bytes held by the nested set, and (out) the bytes separate per-level
 * vertex + index arrays would take for the same levels. */
TLOD_API size_t tlod_patterns_memory(const tlod_patterns* patterns, size_t* separate_bytes);

#ifdef __cplusplus
}
#endif
#endif
