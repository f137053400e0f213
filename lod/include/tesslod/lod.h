/*
 * tesslod/lod.h -- the level-of-detail scheduler (module tesslod::lod)
 *
 * WHAT IT DOES
 *   Plans every frame of an adaptively tessellated surface, for one or more
 *   cameras: per mesh vertex the silhouette depth d_i (Boubekeur & Alexa),
 *   per patch the frustum test and the projection scale (pixels per world
 *   unit over the patch's bounding sphere), then a refinement level per
 *   patch by policy from the patch's per-level error table (tesslod/core.h
 *   tlod_patch_error_bound(); Schwarz, Staginski & Stamminger 2006),
 *   under an optional triangle budget or frame-time target, with geomorph
 *   state so that level changes blend in over time (within epsilon).
 *   The result is a draw list: instances bucketed by (shape, level),
 *   connection strips where neighbouring patches differ, and statistics.
 *   Includes tesslod/patterns.h (the refinement and connection patterns the
 *   draw list refers to).
 *
 * DOES NOT
 *   - evaluate the surface or build vertex data (tesslod/core.h and the
 *     backends do, from the draw list);
 *   - draw anything or talk to a GPU;
 *   - keep the view arrays of the mesh or surface across frames: each update
 *     reads them afresh, so tlod_mesh_update() + tlod_surface_refresh()
 *     between frames are picked up by the next update.
 *
 * STEP BY STEP
 *   1. tlod_patterns_create(ctx, &(tlod_patterns_desc){0}, &pat)
 *   2. tlod_scheduler_create(ctx, surface, pat, &(tlod_scheduler_desc){0}, &sch)
 *      (every zero field is a documented default: epsilon 0.5 px, HYBRID
 *      policy, TIME geomorphs over 200 ms);
 *   3. every frame: tlod_scheduler_update(sch, &(tlod_frame_desc){.views = ...,
 *      .view_count = n, .dt_ms = ...}), then tlod_scheduler_draw_list(sch, v)
 *      per view, valid until the next update;
 *   4. tlod_scheduler_destroy(sch); tlod_patterns_destroy(pat).
 *
 * THREADING AND ALLOCATION
 *   A scheduler belongs to one thread at a time (its context's). Each stage
 *   of an update runs over vertices or patches on the context's
 *   parallel-for; every worker writes only its own entries and the
 *   reductions run afterwards in a fixed order, so draw lists are bitwise
 *   the same for any thread count. Allocation goes through the context's
 *   allocator: at create the mesh's up edges (the edges a connection
 *   strip is counted from: 16 bytes per patch), per view arrays on the
 *   first update with that many views, and the strip array when a frame
 *   needs more strips than any before; otherwise an update does not
 *   allocate. A scheduler takes meshes of fewer than 2^27 patches
 *   (TLOD_ERROR_INVALID_ARGUMENT above: split such a mesh in objects).
 *
 * CONTRACT (the policy of tesslod/core.h; what this header checks)
 *   - NULL handles: create and update return TLOD_ERROR_INVALID_ARGUMENT,
 *     destroy and reset do nothing, the queries return zero / NULL; a NULL
 *     surface, patterns or out pointer at create: TLOD_ERROR_INVALID_ARGUMENT.
 *   - Every desc field outside its documented range, and a max_level above
 *     the patterns': TLOD_ERROR_INVALID_ARGUMENT naming the field.
 *   - Frames: NULL or no views, dt_ms negative or not finite, a view with
 *     non-finite matrices, proj[5] == 0 or an empty viewport:
 *     TLOD_ERROR_INVALID_ARGUMENT naming the view; nothing is planned.
 *   - tlod_scheduler_draw_list() of a view the last update did not plan: NULL.
 *   Undefined: frame.views shorter than view_count; the surface or patterns
 *   destroyed before the scheduler; a draw list read after the next update;
 *   NULL pointers given to the pure helpers below.
 */
#ifndef TESSLOD_LOD_H
#define TESSLOD_LOD_H

#include "tesslod/core.h"
#include "tesslod/patterns.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Scheduler                                                                */
/* ------------------------------------------------------------------------ */

typedef enum tlod_lod_policy {
  TLOD_POLICY_DEFAULT = 0, /* == HYBRID */
  /* The smallest l with tlod_patch_error_bound(info, l) * scale <= epsilon,
   * scale = tlod_patch_projection_scale() (Schwarz et al., with the per-level
   * tables). Geomorphs included: a blending patch stays within epsilon. */
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
  /* Every visible patch at max_level (lowered only by a triangle budget):
   * uniform tessellation, for comparisons. Culling still applies. */
  TLOD_POLICY_UNIFORM,
  /* Every visible patch at level 0 (the input faces on the curved corners),
   * no refinement, no strips, whatever epsilon, budget or max_level say:
   * the untessellated baseline. Culling, e_max (of visible patches) and
   * d_i are still computed for the statistics. */
  TLOD_POLICY_FLAT,
  TLOD_POLICY_NUM,
  _TLOD_POLICY_FORCE_U32 = 0x7FFFFFFF
} tlod_lod_policy;

typedef enum tlod_morph_mode {
  TLOD_MORPH_DEFAULT = 0, /* == TIME */
  TLOD_MORPH_NONE,        /* levels switch at once */
  /* A level change blends over morph_ms of frame time (dt), whatever the
   * frame rate: the patch's continuous level moves 1 per morph_ms. ERROR and
   * HYBRID never blend below the fractional level of CONTINUOUS (a rising
   * level may jump there at once), so the blended mesh meets epsilon. */
  TLOD_MORPH_TIME,
  /* ERROR and HYBRID: the continuous level is L - 1 + a with the smallest
   * blend a whose mesh (1 - a) P_{L-1} + a P_L is within epsilon:
   * (1 - a) b_{L-1} + a b_L = eps, b the projected bounds, L the discrete
   * level (its ceil). SILHOUETTE: log2 of the segments asked for. */
  TLOD_MORPH_CONTINUOUS,
  TLOD_MORPH_NUM,
  _TLOD_MORPH_FORCE_U32 = 0x7FFFFFFF
} tlod_morph_mode;

/* Every zero field is a default. Where zero would also be a value, the
 * value it stands for has its own spelling, named here. */
typedef struct tlod_scheduler_desc {
  /* Screen-space error bound, pixels, > 0. 0 == 0.5 (an error of 0 px
   * cannot be met by any level). */
  float epsilon_px;
  /* Finest level drawn. 0 == the patterns' max level; level 0 everywhere
   * is TLOD_POLICY_FLAT. */
  uint32_t max_level;
  tlod_lod_policy policy; /* 0 == HYBRID */
  /* m of d_i = (1 - |n.v|) m, segments per edge, > 0. 0 == 2^max_level
   * (no m of 0: the contour measure s = max d_i / m divides by it). */
  float silhouette_depth;
  /* HYBRID epsilon factor away from contours, >= 1 (1: HYBRID is ERROR).
   * 0 == 16 (2 levels); values below 1 are rejected. */
  float hybrid_relax;
  tlod_morph_mode morph; /* 0 == TIME */
  /* TIME: frame time of one level step, > 0. 0 == 200; switching at once
   * is TLOD_MORPH_NONE. */
  float morph_ms;
  /* Most triangles (patterns + strips) per frame; epsilon is raised (the
   * level cap lowered for SILHOUETTE and UNIFORM) until the frame fits,
   * level 0 being the floor. 0 == none. */
  uint32_t triangle_budget;
  /* Frame-time target; epsilon follows the measured frame times. 0 == none. */
  float frame_time_target_ms;
  bool no_frustum_cull; /* keep patches outside the frustum; default false (cull) */
  /* The straightforward path, one stage at a time: slow, kept as the oracle
   * the fast path is tested against (their draw lists are bitwise equal, at
   * every SIMD level and thread count). The default fast path fuses the
   * silhouette, metric, level and morph stages into SIMD passes over copies
   * of the mesh and surface it makes at the first update and again when
   * their generations move (docs/design.md 3.13): 32 + 4 (max_level + 1)
   * bytes per patch and 28 per vertex, from the context's allocator. */
  bool reference_path;
  const char* label; /* default "scheduler" */
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
  float morph; /* the level's new vertices on the patch's edges blend the same (edges blend with their patch) */
} tlod_draw_instance;

/* A connection strip between edge ea of patch a and edge eb of patch b,
 * drawn with tlod_draw_strip_connection() (la, lb), polyline b reversed. */
typedef struct tlod_draw_strip {
  uint32_t patch_a, patch_b;
  uint8_t edge_a, edge_b;
  uint8_t level_a, level_b;
  bool crease; /* split normals (or alphas), not a level difference */
  /* A smooth edge between different levels whose coarser side draws its
   * edge points exact (morph 1, or level 0): the points the two sides share
   * coincide, so the strip is tlod_patterns_connection_exact() (only the
   * |2^la - 2^lb| triangles that fill gaps); else tlod_patterns_connection(). */
  bool exact;
} tlod_draw_strip;

/* The connection pattern a strip is drawn with (see exact), its triangle
 * count in *triangle_count; NULL (count 0) for a NULL strip or patterns,
 * or levels above the patterns' max level. */
TLOD_API const uint32_t* tlod_draw_strip_connection(const tlod_patterns* patterns, const tlod_draw_strip* strip,
                                                    uint32_t* triangle_count);

typedef enum tlod_stage {
  TLOD_STAGE_SILHOUETTE = 0, /* d_i per vertex */
  TLOD_STAGE_METRIC,         /* e_max and culling per patch */
  TLOD_STAGE_LEVELS,         /* levels, budget search */
  TLOD_STAGE_MORPH,          /* geomorph state */
  TLOD_STAGE_STRIPS,         /* buckets and strips */
  TLOD_STAGE_NUM,
  _TLOD_STAGE_FORCE_U32 = 0x7FFFFFFF
} tlod_stage;

typedef struct tlod_draw_list {
  uint32_t patch_count;
  const int8_t* levels; /* per patch: drawn level, -1 when culled */
  /* per patch: projected error bound at level 0, pixels:
   * tlod_patch_error_bound(info, 0) * tlod_patch_projection_scale();
   * 0 for a culled patch, unless the frame has a view with lock_to_main
   * (then computed for every patch: the locked views use view 0's levels) */
  const float* e_max;
  /* per mesh vertex: d_i, for every vertex of a patch in view (of every
   * vertex with frustum culling off or a lock_to_main view); a vertex only
   * culled patches use may keep an older frame's value on the fast path */
  const float* vertex_depth;
  /* The order is fixed whatever the thread count: buckets (the non-empty
   * ones only) by shape, then level; a bucket's instances by patch index;
   * strips by patch_a, then edge_a (a strip is listed from its lower patch). */
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
  /* Equal generations, equal draw lists (a backend need not re-send it).
   * An update whose views (bitwise), effective epsilon and mesh and surface
   * generations are the last update's, with every geomorph at rest, keeps
   * the list and its generation (no stage runs: stage_ms all 0); any other
   * update, a group update and the first one after tlod_scheduler_reset
   * build the list anew with a new generation. */
  uint64_t generation;
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
/* Plans one frame for count schedulers (e.g. the objects of a scene, one
 * scheduler per instance) under ONE triangle budget shared by all: the
 * triangles go where the screen error is, not split evenly. frames[i] is
 * scheduler i's frame (each instance has its own view). View 0 of every
 * scheduler is the group's: silhouette and metric per scheduler, then one
 * search raising one shared epsilon (from the largest of the members'
 * epsilon_px * frame-time factor) until the members' summed targets
 * (patterns + strips) fit triangle_budget, then geomorph and draw list per
 * scheduler; every member's view 0 draw list reports that
 * effective_epsilon. The group budget replaces each member's own
 * desc.triangle_budget for view 0, and the budget is a hard cap in the
 * geomorph stage as for one scheduler. A frame that fits unconstrained
 * keeps each member's own epsilon. Views after the first are planned as
 * tlod_scheduler_update does (locked views copy view 0). Only ERROR and
 * HYBRID members follow epsilon: SILHOUETTE, UNIFORM and FLAT members keep
 * their unbudgeted levels, counted in the sum (so the budget may not hold
 * when they alone exceed it). triangle_budget 0: each scheduler updated on
 * its own, exactly tlod_scheduler_update in order. Level 0 everywhere is
 * the floor, as for one scheduler. Deterministic for the same inputs and
 * histories, any thread count; no allocation after each member's first
 * update. Threading: members run one after another on the calling thread,
 * each stage through its context's parallel-for; no member may be used
 * from another thread meanwhile. Checks: schedulers or frames NULL (with
 * count > 0), a NULL member, a scheduler given twice, and each frame as
 * tlod_scheduler_update does (stopping at the first that fails: members
 * before it may have been updated); count 0 does nothing and succeeds.
 * Members of different contexts: undefined. */
TLOD_API tlod_result tlod_scheduler_update_group(tlod_scheduler* const* schedulers, const tlod_frame_desc* frames,
                                                 uint32_t count, uint32_t triangle_budget);
TLOD_API const tlod_draw_list* tlod_scheduler_draw_list(const tlod_scheduler* scheduler, uint32_t view);
/* Forgets the geomorph history (the next update starts at its targets). */
TLOD_API void tlod_scheduler_reset(tlod_scheduler* scheduler);

/* Pure helpers (also used by tests as the reference). */
/* The level rule of a patch whose level-l bound is e_max 4^-l (the rule
 * before the per-level tables): 0 when e_max <= eps, else the smallest l
 * with 4^-l e_max <= eps, at most max_level (the scheduler's own ladder
 * run on that table, not a copy of it). */
TLOD_API uint32_t tlod_level_for_error(float e_max, float epsilon, uint32_t max_level);
/* Pixels per world unit at view depth z (perspective) or everywhere (orthographic). */
TLOD_API float tlod_projection_scale(const float proj[16], uint32_t viewport_height, float depth);
/* Pixels per world unit of any displacement between two points of the
 * sphere (center, radius) that are in front of the near plane and inside
 * the frustum (a rigid view): max(W |proj[0]|, H |proj[5]|) / 2 / z *
 * sqrt(1 + rx^2 + ry^2), z the sphere's nearest view depth (at least the
 * near plane), rx, ry bounds of |x/z|, |y/z| over the sphere, at most the
 * frustum's; orthographic: the pixel scale. What the scheduler multiplies
 * the error table with (docs/design.md 3.6). Pure. */
TLOD_API float tlod_patch_projection_scale(const tlod_view_desc* view, const float center[3], float radius);

/* ------------------------------------------------------------------------ */
/* Enum names                                                               */
/* ------------------------------------------------------------------------ */

/* (value, name), the same shape as core's tables (tesslod/core.h): the
 * names tools parse and print. DEFAULT has no name of its own; *_name()
 * gives its resolved value's. */
#define TLOD_LOD_POLICY_NAMES(X)                                                                                       \
  X(TLOD_POLICY_ERROR, "error")                                                                                        \
  X(TLOD_POLICY_SILHOUETTE, "silhouette")                                                                              \
  X(TLOD_POLICY_HYBRID, "hybrid") X(TLOD_POLICY_UNIFORM, "uniform") X(TLOD_POLICY_FLAT, "flat")
#define TLOD_MORPH_MODE_NAMES(X)                                                                                       \
  X(TLOD_MORPH_NONE, "none") X(TLOD_MORPH_TIME, "time") X(TLOD_MORPH_CONTINUOUS, "continuous")
#define TLOD_STAGE_NAMES(X)                                                                                            \
  X(TLOD_STAGE_SILHOUETTE, "silhouette")                                                                               \
  X(TLOD_STAGE_METRIC, "metric")                                                                                       \
  X(TLOD_STAGE_LEVELS, "levels") X(TLOD_STAGE_MORPH, "morph") X(TLOD_STAGE_STRIPS, "strips")

/* Name of a value ("hybrid"); NULL for a value outside the enum. */
TLOD_API const char* tlod_lod_policy_name(tlod_lod_policy policy);
TLOD_API const char* tlod_morph_mode_name(tlod_morph_mode mode);
TLOD_API const char* tlod_stage_name(tlod_stage stage);
/* Value of a name (exact, case-sensitive); false (and *out untouched) when
 * the name is none of the table's. */
TLOD_API bool tlod_lod_policy_from_name(const char* name, tlod_lod_policy* out);
TLOD_API bool tlod_morph_mode_from_name(const char* name, tlod_morph_mode* out);
TLOD_API bool tlod_stage_from_name(const char* name, tlod_stage* out);

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_LOD_H */
