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
/* Where pattern vertex (i, j) (grid coordinates over 2^max_level) lies on its
 * patch: 0..3 a corner (triangle i, j, k; quad 0..3), 4 + e on edge e (from
 * corner e to corner (e + 1) % n; *param = the end corner's weight times
 * 2^max_level), 8 inside (*param untouched). Pure. */
#define TLOD_PATTERN_KIND_EDGE 4u
#define TLOD_PATTERN_KIND_INTERIOR 8u
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
 * out. Patterns are built once per (la, lb) and shared (Schwarz et al.). */
TLOD_API const uint32_t* tlod_patterns_connection(const tlod_patterns* patterns, uint32_t la, uint32_t lb,
                                                  uint32_t* triangle_count);

/* ------------------------------------------------------------------------ */
/* Scheduler                                                                */
/* ------------------------------------------------------------------------ */

typedef enum tlod_lod_policy {
  TLOD_POLICY_DEFAULT = 0, /* == HYBRID */
  /* The smallest l with 4^-l e_max <= epsilon (Schwarz et al.). */
  TLOD_POLICY_ERROR,
  /* Refine only near contours (Boubekeur & Alexa): d_i is a vertex's desired
   * tessellation factor, segments per edge; the patch takes
   * l = ceil(log2(max d_i)) over its corners (0 when max d_i <= 1). */
  TLOD_POLICY_SILHOUETTE,
  /* ERROR with epsilon relaxed away from silhouettes: eps_p = eps *
   * relax^(1 - s), s = max d_i / m over the patch's corners, and s = 1 where
   * the corner normals face both towards and away from the camera (the
   * contour crosses the patch). At contours the bound holds with eps, as
   * for ERROR; a patch facing the camera (s = 0) uses relax * eps, where
   * shading hides the flat geometry. */
  TLOD_POLICY_HYBRID,
  /* Every visible patch at max_level: uniform tessellation, for comparisons. */
  TLOD_POLICY_UNIFORM,
  TLOD_POLICY_NUM,
  _TLOD_POLICY_FORCE_U32 = 0x7FFFFFFF
} tlod_lod_policy;

typedef enum tlod_morph_mode {
  TLOD_MORPH_DEFAULT = 0, /* == TIME */
  TLOD_MORPH_NONE,        /* levels switch at once */
  /* A level change blends over morph_ms of frame time (dt), whatever the
   * frame rate: the patch's continuous level moves 1 per morph_ms. */
  TLOD_MORPH_TIME,
  /* The continuous level is log4(e_max / eps) itself (fractional levels). */
  TLOD_MORPH_CONTINUOUS,
  TLOD_MORPH_NUM,
  _TLOD_MORPH_FORCE_U32 = 0x7FFFFFFF
} tlod_morph_mode;

typedef struct tlod_scheduler_desc {
  float epsilon_px;   /* screen-space error bound, pixels; 0 == 0.5 */
  uint32_t max_level; /* 0 == the patterns' max level */
  tlod_lod_policy policy;
  float silhouette_depth; /* m of d_i = (1 - |n.v|) m, segments per edge; 0 == 2^max_level */
  float hybrid_relax;     /* HYBRID epsilon factor away from contours; 0 == 16 (2 levels) */
  tlod_morph_mode morph;
  float morph_ms;             /* TIME: duration of one level step; 0 == 200 */
  uint32_t triangle_budget;   /* 0 == none; else epsilon is raised until the frame fits */
  float frame_time_target_ms; /* 0 == none; else epsilon follows measured frame times */
  bool no_frustum_cull;       /* keep patches outside the frustum */
  const char* label;
} tlod_scheduler_desc;

/* One camera. Matrices are column-major (OpenGL): clip = proj * view * world. */
typedef struct tlod_view_desc {
  float view[16];
  float proj[16];                           /* perspective or orthographic (proj[15] == 1) */
  uint32_t viewport_width, viewport_height; /* pixels */
  /* Take view 0's levels and morph state (a shadow map or second eye whose
   * silhouettes must match the main view's); culling stays per view. */
  bool lock_to_main;
} tlod_view_desc;

typedef struct tlod_frame_desc {
  const tlod_view_desc* views; /* view 0 is the main view */
  uint32_t view_count;
  float dt_ms;             /* time since the last frame (geomorphs) */
  float measured_frame_ms; /* last frame's measured time (frame_time_target); 0 == unknown */
} tlod_frame_desc;

/* Patches drawn with one refinement pattern. */
typedef struct tlod_draw_bucket {
  tlod_pattern_shape shape;
  uint32_t level;
  uint32_t first, count; /* range of tlod_draw_list.instances */
} tlod_draw_bucket;

typedef struct tlod_draw_instance {
  uint32_t patch;
  uint32_t level;
  /* Blend of the vertices first inserted at `level`: 0 = at their parents'
   * midpoint (the coarser level exactly), 1 = on the surface. */
  float morph;
  float edge_morph[4]; /* the same for the level's new vertices on edge e */
} tlod_draw_instance;

/* A connection strip between edge ea of patch a and edge eb of patch b,
 * drawn with tlod_patterns_connection(la, lb), polyline b reversed. */
typedef struct tlod_draw_strip {
  uint32_t patch_a, patch_b;
  uint8_t edge_a, edge_b;
  uint8_t level_a, level_b;
  bool crease; /* split normals (or alphas), not a level difference */
} tlod_draw_strip;

typedef enum tlod_stage {
  TLOD_STAGE_SILHOUETTE = 0, /* d_i per vertex */
  TLOD_STAGE_METRIC,         /* e_max and culling per patch */
  TLOD_STAGE_LEVELS,         /* levels, budget search */
  TLOD_STAGE_MORPH,          /* geomorph state */
  TLOD_STAGE_STRIPS,         /* buckets and strips */
  TLOD_STAGE_NUM
} tlod_stage;

typedef struct tlod_draw_list {
  uint32_t patch_count;
  const int8_t* levels;                /* per patch: drawn level, -1 when culled */
  const float* e_max;                  /* per patch: projected error bound at level 0, pixels */
  const float* vertex_depth;           /* per mesh vertex: d_i */
  const tlod_draw_instance* instances; /* visible patches, bucket by bucket */
  uint32_t instance_count;
  const tlod_draw_bucket* buckets;
  uint32_t bucket_count;
  const tlod_draw_strip* strips;
  uint32_t strip_count;
  /* Statistics. */
  uint64_t pattern_triangles, strip_triangles;
  uint32_t culled;
  uint32_t level_histogram[TLOD_MAX_LEVEL + 1];
  float e_max_min, e_max_max; /* over visible patches */
  float effective_epsilon;    /* after budget and frame-time control */
  double stage_ms[TLOD_STAGE_NUM];
} tlod_draw_list;

typedef struct tlod_scheduler tlod_scheduler;

/* The surface and patterns must outlive the scheduler. */
TLOD_API tlod_result tlod_scheduler_create(tlod_context* ctx, const tlod_surface* surface,
                                           const tlod_patterns* patterns, const tlod_scheduler_desc* desc,
                                           tlod_scheduler** out);
TLOD_API void tlod_scheduler_destroy(tlod_scheduler* scheduler);
TLOD_API tlod_scheduler_desc tlod_scheduler_query_desc(const tlod_scheduler* scheduler);
/* Plans one frame for every view. The draw lists stay valid until the next
 * update or destroy. Deterministic for the same inputs and history, for
 * any thread count. */
TLOD_API tlod_result tlod_scheduler_update(tlod_scheduler* scheduler, const tlod_frame_desc* frame);
TLOD_API const tlod_draw_list* tlod_scheduler_draw_list(const tlod_scheduler* scheduler, uint32_t view);
/* Forgets the geomorph history (the next update starts at its targets). */
TLOD_API void tlod_scheduler_reset(tlod_scheduler* scheduler);

/* Pure helpers (also used by tests as the reference). */
/* The level rule: 0 when e_max <= eps, else the smallest l with 4^-l e_max <= eps, at most max_level. */
TLOD_API uint32_t tlod_level_for_error(float e_max, float epsilon, uint32_t max_level);
/* Pixels per world unit at view depth z (perspective) or everywhere (orthographic). */
TLOD_API float tlod_projection_scale(const float proj[16], uint32_t viewport_height, float depth);

#ifdef __cplusplus
}
#endif
#endif
