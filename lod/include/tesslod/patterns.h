/*
 * tesslod/patterns.h -- refinement and connection patterns (module tesslod::lod)
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
 *   Connection patterns are the strips that join two patches' edges drawn
 *   at different levels (or across a crease), one per level pair.
 *
 * DOES NOT
 *   - evaluate surfaces (tesslod/core.h: tlod_surface_eval_grid() takes the
 *     pattern vertices as they are) or draw anything (backends);
 *   - choose levels (the scheduler in tesslod/lod.h does).
 *
 * STEP BY STEP
 *   1. tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 6}, &pat)
 *   2. per shape and level: tlod_patterns_vertices(), tlod_patterns_indices()
 *      (upload once: every level indexes the one vertex array);
 *      tlod_patterns_edge() for the vertices along an edge;
 *   3. per level pair: tlod_patterns_connection() for the strips (or
 *      tlod_patterns_connection_exact(); tlod_draw_strip_connection() picks);
 *   4. tlod_patterns_destroy(pat) after everything drawing with it.
 *
 * THREADING AND ALLOCATION
 *   Creation allocates every pattern at once through the context's
 *   allocator; the queries never allocate and may run on many threads at
 *   once. The pure functions (counts, tlod_pattern_vertex_kind) need no
 *   patterns object.
 *
 * CONTRACT (the policy of tesslod/core.h; what this header checks)
 *   - tlod_patterns_create(): NULL ctx or out, max_level > TLOD_MAX_LEVEL:
 *     TLOD_ERROR_INVALID_ARGUMENT (desc NULL: defaults).
 *   - Queries: NULL patterns, a shape outside the enum, a level above the
 *     set's max level, an edge >= the shape's corner count: NULL / 0, and
 *     *count / *index_count / *triangle_count set to 0; nothing written.
 *     The pure counts return 0 for a bad shape or a level > TLOD_MAX_LEVEL.
 *   Undefined: tlod_patterns_edge()'s out shorter than 2^level + 1; the
 *   patterns destroyed while a scheduler or device uses them.
 *
 * ORIENTATION
 *   Triangles are counter-clockwise in (u, v) for the triangle (u=1 at corner
 *   i, v=1 at corner j, w=1 at corner k), and for the quad (0,0) (1,0) (1,1)
 *   (0,1), so they keep the input face's winding.
 */
#ifndef TESSLOD_PATTERNS_H
#define TESSLOD_PATTERNS_H

#include "tesslod/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TLOD_MAX_LEVEL 10
#define TLOD_DEFAULT_MAX_LEVEL 6

typedef enum tlod_pattern_shape {
  TLOD_PATTERN_TRIANGLE = 0, /* the zero value is a real shape, not a default */
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
  /* Finest level built, at most TLOD_MAX_LEVEL. 0 == TLOD_DEFAULT_MAX_LEVEL
   * (6): a set of level 0 alone would hold nothing worth building (level 0
   * is every shape's own corners; the scheduler's TLOD_POLICY_FLAT draws
   * it from any set). */
  uint32_t max_level;
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
/* Where pattern vertex (i, j) (grid coordinates over 2^max_level) lies on its
 * patch: tlod_grid_point_kind() of tesslod/core.h for the shape's corner
 * count, kept under this name for the backends; TLOD_PATTERN_KIND_OFF for a
 * bad shape, a point off the grid or max_level > TLOD_GRID_MAX_LOG2. */
#define TLOD_PATTERN_KIND_EDGE TLOD_GRID_EDGE
#define TLOD_PATTERN_KIND_INTERIOR TLOD_GRID_INTERIOR
#define TLOD_PATTERN_KIND_OFF TLOD_GRID_OFF
TLOD_API uint32_t tlod_pattern_vertex_kind(tlod_pattern_shape shape, uint32_t max_level, uint32_t i, uint32_t j,
                                           uint32_t* param);
/* Bytes held by the nested set, and (out) the bytes separate per-level
 * vertex + index arrays would take for the same levels. */
TLOD_API size_t tlod_patterns_memory(const tlod_patterns* patterns, size_t* separate_bytes);

/* ------------------------------------------------------------------------ */
/* Connection patterns                                                      */
/* ------------------------------------------------------------------------ */

/* A strip joining edge polyline a (level la: points 0..2^la) to polyline b
 * (level lb, given in a's direction), zipped by parameter: triangles as
 * point references, r <= 2^la is a[r], else b[r - 2^la - 1]. Oriented so a
 * is traversed backwards (a bounds the face on the strip's left). The two
 * triangles at the shared corners, degenerate by construction, are left
 * out (so la = lb = 0 has no triangle). Patterns are built once per
 * (la, lb) and shared (Schwarz et al.). */
TLOD_API const uint32_t* tlod_patterns_connection(const tlod_patterns* patterns, uint32_t la, uint32_t lb,
                                                  uint32_t* triangle_count);
/* The same strip for polylines whose points at equal parameters (i / 2^la
 * == j / 2^lb) are the same point: tlod_patterns_connection() without every
 * triangle that has such a pair, as they have no area there. What is left
 * fills the gaps between the coarser side's chords and the finer polyline:
 * |2^la - 2^lb| triangles (none for la == lb). Valid only where both sides
 * put the shared points at the same position: a smooth edge whose coarser
 * side draws its edge points exact (tlod_draw_strip.exact). */
TLOD_API const uint32_t* tlod_patterns_connection_exact(const tlod_patterns* patterns, uint32_t la, uint32_t lb,
                                                        uint32_t* triangle_count);

/* ------------------------------------------------------------------------ */
/* Enum names                                                               */
/* ------------------------------------------------------------------------ */

/* (value, name), the same shape as core's tables (tesslod/core.h). */
#define TLOD_PATTERN_SHAPE_NAMES(X) X(TLOD_PATTERN_TRIANGLE, "triangle") X(TLOD_PATTERN_QUAD, "quad")
/* Name of a shape; NULL for a value outside the enum. */
TLOD_API const char* tlod_pattern_shape_name(tlod_pattern_shape shape);
/* Value of a name (exact, case-sensitive); false (and *out untouched) when unknown. */
TLOD_API bool tlod_pattern_shape_from_name(const char* name, tlod_pattern_shape* out);

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_PATTERNS_H */
