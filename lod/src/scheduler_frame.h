/*
 * scheduler_frame.h -- private to tesslod::lod: the scheduler's state and
 * one frame's stages, one file each, in the order an update runs them:
 *   scheduler_metric.c    camera, silhouette depth d_i, culling, e_max,
 *                         contour, and the level rule (every form of it)
 *   scheduler_levels.c    target level per patch, triangle budget,
 *                         frame-time control
 *   scheduler_morph.c     geomorph state (continuous level per patch)
 *   scheduler_draw_list.c instances, buckets, strips, statistics
 *   scheduler_up_edges.c  the edges a strip is counted from (at create)
 *   scheduler_coherence.c whether an update can keep the last draw lists
 *   scheduler.c           create / update / destroy: the stages in order
 * lod reads core through its public views only (tesslod/core.h).
 */
#ifndef TESSLOD_SCHEDULER_FRAME_H
#define TESSLOD_SCHEDULER_FRAME_H

#include "patterns_internal.h"
#include "scheduler_fast.h"
#include "tesslod/lod.h"

#define _TLOD_NO_FACE UINT32_MAX /* tlod_edge_link.face of an edge with no neighbour */
#define _TLOD_BUCKETS (TLOD_PATTERN_SHAPE_NUM * (TLOD_MAX_LEVEL + 1))

typedef struct _tlod_camera {
  float eye[3], forward[3];
  float planes[6][4]; /* normalised, inside >= 0 */
  float near_z;       /* 0 when unknown or orthographic */
  bool ortho;
} _tlod_camera;

/* Patches per chunk of the draw-list build: fixed, so that the chunks (and
 * the order they are summed in) never depend on the thread count. */
#define _TLOD_LIST_CHUNK 4096u

/* The mesh's up edges (scheduler_up_edges.c): the edges towards a
 * neighbour of higher index, the only ones a strip is counted from, in
 * slots: slot[k * patch_count + f] is patch f's k-th up edge (in edge
 * order), the whole strip but the levels: the neighbour, the patch's edge,
 * the neighbour's edge and the crease bit; or f itself (smooth) where f has
 * fewer than k + 1 up edges: a patch never strips to itself, so the strip
 * test needs no count. */
#define _TLOD_UP_FACE 0x07FFFFFFu   /* bits 0-26: the neighbour (patches stay below 2^27) */
#define _TLOD_UP_EDGE_B_SHIFT 27    /* bits 27-28: the neighbour's edge */
#define _TLOD_UP_EDGE_SHIFT 29      /* bits 29-30: the patch's edge */
#define _TLOD_UP_CREASE 0x80000000u /* bit 31: the edge is not smooth */
typedef struct _tlod_up_edges {
  uint32_t* slot;             /* _TLOD_UP_SLOTS slots per patch, slot-major */
  uint8_t* block_slots;       /* per block of FAST_BLOCK patches: the most up edges of a patch in it */
  uint64_t smooth_generation; /* of the mesh whose smooth flags slot[] holds */
} _tlod_up_edges;
#define _TLOD_UP_SLOTS 4

/* The draw list's per-block kernels (scheduler_list_kernels.c), over the
 * patches [begin, end) of one block with a visible patch:
 *   strip_edges: per patch the bit k of each slot k whose up edge needs a
 *     strip (0 for a culled patch) into edges; returns the bits set. slots: the
 *     block's block_slots. visible is read 4 bytes at a time (3 bytes
 *     readable past the last patch).
 *   count: levels (drawn level, -1 culled), counts[bucket] += instances,
 *     the tally's culled patches and e_max range.
 *   write: each visible patch's instance at instances[slots[bucket]++]
 *     (after count: levels set).
 *   strips: the strips of the slots strip_edges marked, in patch and edge
 *     order, at out; returns how many (after count: levels set). */
typedef struct _tlod_list_in {
  const uint32_t* slot; /* _tlod_up_edges */
  uint32_t patch_count; /* the slot stride */
  uint32_t levels_n;    /* buckets per shape */
  const uint8_t* visible;
  const float* cont;
  const float* e_max;
  const uint8_t* corners;
  int8_t* levels;
  uint8_t* edges;
  tlod_draw_instance* instances;
} _tlod_list_in;
typedef struct _tlod_list_tally {
  float e_min, e_max; /* the first of equal values kept, NaN never taken */
  uint32_t culled;
} _tlod_list_tally;
typedef struct _tlod_list_kernels {
  uint32_t (*strip_edges)(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t slots);
  void (*count)(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* counts, _tlod_list_tally* t);
  void (*write)(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* slots);
  uint32_t (*strips)(const _tlod_list_in* in, uint32_t begin, uint32_t end, tlod_draw_strip* out);
} _tlod_list_kernels;
/* The kernels of SIMD level simd (never DEFAULT): the best built not above it. */
_tlod_list_kernels _tlod_list_kernels_for(tlod_simd simd);

/* One chunk's part of the draw list: counted in pass 1, summed in chunk
 * order, written in pass 2 (scheduler_draw_list.c). */
typedef struct _tlod_list_chunk {
  uint32_t counts[_TLOD_BUCKETS]; /* instances per bucket; then the chunk's first slot */
  uint32_t strips, strip_first;
  uint64_t strip_triangles;
  uint32_t culled;
  float e_max_min, e_max_max;
  /* Bit k: block k (FAST_BLOCK patches from the chunk's first) has a
   * visible patch; the other blocks are culled and never read again. */
  uint64_t blocks; /* bit k: block k; _TLOD_LIST_CHUNK / FAST_BLOCK <= 64 (scheduler_draw_list.c) */
} _tlod_list_chunk;

/* What the draw list of one view was made from (scheduler_coherence.c). */
typedef struct _tlod_view_key {
  float view[16], proj[16];
  uint32_t viewport_width, viewport_height;
  bool lock_to_main;
  uint64_t mesh_generation, surface_generation;
  float eps; /* epsilon_px times the frame-time factor, before any budget */
} _tlod_view_key;

/* What one view keeps between and within frames. */
typedef struct _tlod_view_state {
  tlod_draw_list list;
  _tlod_camera cam;
  int8_t* levels;
  float* e_max;
  float* scale;   /* per patch pixels per world unit (tlod_patch_projection_scale) */
  float* depth;   /* per vertex d_i */
  float* contour; /* per patch s = max d_i / m */
  float* target;  /* per patch target level (continuous) */
  float* cont;    /* per patch current continuous level */
  uint8_t* visible;
  tlod_draw_instance* instances;
  tlod_draw_strip* strips;
  uint32_t strip_cap;
  tlod_draw_bucket buckets[_TLOD_BUCKETS];
  _tlod_list_chunk* chunks; /* one per _TLOD_LIST_CHUNK patches */
  uint8_t* strip_edges;     /* per visible patch: bit k when up edge slot k has a strip (this frame) */
  _tlod_view_key key;       /* valid while key_valid */
  bool key_valid;
  /* The last draw list's morphs were all at rest: checked only when a
   * frame's key matches (a moving view never needs it), then kept. */
  bool settled, settled_known;
  bool has_history;
  /* The chunks with a visible patch, this frame (in the chunks' block). */
  uint32_t* busy;
  uint32_t busy_count;
} _tlod_view_state;

/* One view's frame: what every stage task reads. The mesh and surface views
 * are queried once per update (their arrays move on tlod_mesh_update and
 * tlod_surface_refresh), never kept across frames. */
typedef struct _tlod_frame {
  tlod_scheduler* s;
  _tlod_view_state* vs;
  const tlod_view_desc* view;
  tlod_mesh_view mesh;
  tlod_surface_view surface;
  float eps;                    /* effective epsilon of this frame */
  float level_cap;              /* budget cap (SILHOUETTE, UNIFORM) */
  float step;                   /* TIME morph: level change this frame */
  const _tlod_view_state* main; /* locked views: view 0 */
  uint32_t budget;              /* triangles: the scheduler's own or its group's; 0 == none */
  double t[TLOD_STAGE_NUM + 1]; /* stage boundaries, ms */
  bool fused;                   /* fast path: levels and morph done with the metric */
  /* Culled patches get e_max 0, target 0 and cont _TLOD_NO_HISTORY
   * (docs/design.md 3.13); false when the frame has a locked view, which
   * copies view 0's targets and levels for patches view 0 may cull. */
  bool cull_skip;
} _tlod_frame;

struct tlod_scheduler {
  tlod_context* ctx;
  const tlod_surface* surface;
  const tlod_mesh* mesh;
  const tlod_patterns* patterns;
  tlod_scheduler_desc desc; /* resolved */
  char label[64];
  uint32_t patch_count, vertex_count;
  _tlod_view_state* views;
  uint32_t view_count;
  float eps_scale;   /* frame-time control */
  float smoothed_ms; /* EMA of measured frame times */
  _tlod_frame group; /* view 0 between the stages of a group update */
  /* Index + 1 of this scheduler in the group being validated, 0 outside
   * validation: finds a scheduler given twice in one pass, not count^2. */
  uint32_t group_slot;
  /* Fast path (desc.reference_path false): kernels of the context's SIMD
   * level and their structure-of-arrays inputs (scheduler_fast.h). */
  bool fast_path;
  _tlod_fast_kernels fast;
  _tlod_soa soa;
  _tlod_up_edges up;
  _tlod_list_kernels list; /* the scalar ones on the reference path */
};

/* scheduler_metric.c */
void _tlod_camera_from_view(const float view[16], const float proj[16], _tlod_camera* cam);
/* Per vertex: d_i into vs->depth. */
void _tlod_silhouette_task(void* frame, uint32_t begin, uint32_t end, uint32_t worker);
/* Per patch: visibility, e_max and contour s. */
void _tlod_metric_task(void* frame, uint32_t begin, uint32_t end, uint32_t worker);
/* The level rule, every form of it (policy, discrete or continuous): the
 * target level of patch info projected at scale pixels per world unit,
 * contour s, at epsilon eps under level cap cap. ceil() of the result is
 * always the discrete rule's level. ERROR and HYBRID return the fractional
 * level whose blended bound meets eps (docs/design.md 3.9): the morph stage
 * never draws a patch below it. */
float _tlod_level_rule(const tlod_scheduler_desc* d, const tlod_patch_info* info, float scale, float contour, float eps,
                       float cap);

/* scheduler_levels.c */
/* Targets of every patch, with epsilon (or the cap) raised until the
 * triangle budget holds. */
void _tlod_fit_budget(_tlod_frame* fr);
/* Targets of view 0 (member->group, metric done) of count schedulers under
 * one shared budget: one epsilon raised for all members that follow
 * epsilon (ERROR, HYBRID) until the sum fits. */
void _tlod_fit_group(tlod_scheduler* const* members, uint32_t count, uint32_t budget);
void _tlod_control_frame_time(tlod_scheduler* s, float measured_ms);

/* scheduler_morph.c */
void _tlod_morph_task(void* frame, uint32_t begin, uint32_t end, uint32_t worker);
/* The level a patch at continuous level cont draws: ceil(cont), 0 when
 * cont is not positive (no history, NaN). Inline, per patch and edge in
 * the draw list; ceil without a libm call: truncation is exact below 2^32,
 * where (uint32_t) is defined at all. */
static inline uint32_t _tlod_drawn_level(float cont) {
  if (!(cont > 0.0f)) return 0u;
  uint32_t i = (uint32_t)cont;
  return i + ((float)i < cont);
}
/* Blend of the vertices new at `level`: 0 at their parents' midpoint, 1 on
 * the surface; level 0 has no new vertices and is always exact. */
static inline float _tlod_morph_of(float cont, uint32_t level) {
  if (level == 0) return 1.0f;
  float m = cont - (float)(level - 1);
  return m < 0.0f ? 0.0f : (m > 1.0f ? 1.0f : m);
}
/* Whether edge e of visible patch f gets a strip when patches sit at
 * continuous levels cont[]: counted once, from the lower patch index, and
 * only towards a visible neighbour. */
bool _tlod_strip_needed(const _tlod_frame* fr, const float* cont, uint32_t f, uint32_t e);

/* scheduler_soa.c, scheduler_fast_frame.c: the fast path */
void _tlod_soa_free(tlod_context* ctx, _tlod_soa* soa);
/* Copies the inputs again when the mesh or surface generation moved. */
tlod_result _tlod_soa_update(tlod_scheduler* s, const tlod_mesh_view* mesh, const tlod_surface_view* surface);
/* Silhouette and metric stages of fr (t[1] set), fused with levels and
 * morph (fr->fused) when may_fuse and the frame has no budget and is not locked. */
void _tlod_fast_begin(_tlod_frame* fr, bool may_fuse);

/* scheduler_up_edges.c: s->up from the mesh's links (on failure the
 * caller frees what was made). */
tlod_result _tlod_up_edges_build(tlod_scheduler* s);
/* The crease bits again when the mesh's smooth flags moved (an update). */
void _tlod_up_edges_refresh(tlod_scheduler* s, const tlod_mesh_view* mesh);
void _tlod_up_edges_free(tlod_context* ctx, _tlod_up_edges* u);

/* scheduler_draw_list.c */
/* The view's chunk and strip-edge arrays (freed with its other arrays). */
tlod_result _tlod_list_alloc(tlod_scheduler* s, _tlod_view_state* vs);
tlod_result _tlod_fill_draw_list(_tlod_frame* fr);

/* scheduler_coherence.c */
/* Whether frame would rebuild exactly the draw lists s holds: every view's
 * inputs bitwise as last time, the mesh and surface generations unchanged,
 * every morph at rest. */
bool _tlod_lists_unchanged(const tlod_scheduler* s, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                           const tlod_surface_view* surface);
/* Records what the views of frame were just built from. */
void _tlod_lists_remember(tlod_scheduler* s, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                          const tlod_surface_view* surface);

#endif
