/* Private to tesslod::cpu: the tessellator's working state, shared by the
 * pattern pass (cpu_tessellate.c) and the connection strips (cpu_strips.c). */
#ifndef TESSLOD_CPU_INTERNAL_H
#define TESSLOD_CPU_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/cpu.h"

enum { KIND_EDGE = TLOD_GRID_EDGE, KIND_INTERIOR = TLOD_GRID_INTERIOR };

/* Per pattern vertex: what it is on the patch (corner c, edge e, interior)
 * and its parameter (edge: numerator of t_end over N; interior: ordinal). */
typedef struct level_table {
  uint32_t nv, interior;
  uint8_t* kind;
  uint32_t* param;
  /* The fast path's (cpu_fast.c; NULL on the reference path): interior
   * vertices in ordinal order (their output ids are consecutive) with
   * (u, v) as tlod_surface_eval_grid() computes them and as vertex_uv
   * holds them; the boundary vertices sorted by kind (corners, then edge
   * e's at [edge_at[e], edge_at[e + 1])) with their grid points; the index
   * template (interior ordinal per index) and the indices naming a
   * boundary vertex, the only ones the welded remap touches. */
  uint32_t* int_x;
  float *int_u, *int_v;
  float (*int_uv)[2];
  uint32_t nb, edge_at[5];
  uint32_t *bnd_x, *bnd_param;
  uint16_t (*bnd_ij)[2];
  uint32_t *tmpl, *slot_k, nslot;
} level_table;

/* Per worker, the fast path's positions-only points waiting for one call
 * per level (cpu_fast.c): edges for tlod_surface_eval_edges() (patch, edge,
 * output id of the first point) and, per shape, patches for
 * tlod_surface_eval_interiors() (patch, output id of the first interior
 * point). */
enum { LANE_QUEUE = 128 };
typedef struct lane_queue {
  uint32_t edges[TLOD_MAX_LEVEL + 1];
  uint32_t edge_patch[TLOD_MAX_LEVEL + 1][LANE_QUEUE], edge_first[TLOD_MAX_LEVEL + 1][LANE_QUEUE];
  uint8_t edge[TLOD_MAX_LEVEL + 1][LANE_QUEUE];
  uint32_t patches[2][TLOD_MAX_LEVEL + 1];
  uint32_t patch[2][TLOD_MAX_LEVEL + 1][LANE_QUEUE], patch_first[2][TLOD_MAX_LEVEL + 1][LANE_QUEUE];
} lane_queue;

/* A kept frame's positions-only work as two flat lists (cpu_lists.c): the
 * owned edges by level and the patches with interior points by shape and
 * level (key shape * (TLOD_MAX_LEVEL + 1) + level), each entry with the
 * output id of its first point. Built at the first kept frame that can use
 * them; the topology they follow is the kept one. */
typedef struct work_lists {
  bool built;
  uint32_t edge_at[TLOD_MAX_LEVEL + 2], patch_at[2 * (TLOD_MAX_LEVEL + 1) + 1];
  uint32_t *edge_patch, *edge_first, *patch, *patch_first;
  uint8_t* edge;
} work_lists;

/* Per worker: pattern vertex -> output id, the patch's evaluated points and
 * (with attributes) their attribute vec4s; worker 0's attr also serves the
 * strips (one edge polyline). */
typedef struct scratch {
  uint32_t* map;
  float (*pos)[3];
  float (*nrm)[3];
  float (*cpos)[3], (*cnrm)[3]; /* fast path: points in evaluation order */
  float (*attr)[4];             /* NULL without attributes */
  lane_queue* queue;            /* fast path */
} scratch;

/* A strip vertex of b's polyline carrying a's attributes (cpu_strips.c):
 * the output vertex whose position, normal, patch and (u, v) it copies. */
typedef struct strip_vertex {
  uint32_t src;
} strip_vertex;

typedef struct tess {
  tlod_context* ctx;
  const tlod_surface* s;
  const tlod_mesh* mesh;
  tlod_mesh_view m;     /* read-only arrays of the surface's mesh */
  tlod_surface_view sv; /* ... and of the surface (per-vertex alpha) */
  const tlod_patterns* pat;
  tlod_cpu_tessellate_desc d;
  tlod_simd simd; /* the context's: the interior kernels' instruction set */
  uint32_t lmax, n_grid;
  uint32_t na; /* the mesh's attribute count */
  int8_t* level;
  float (*morph)[5];     /* per patch: interior blend, then per edge; NULL: no morph */
  float (*morph_buf)[5]; /* morph's array, kept when there is no draw list */
  level_table tables[2][TLOD_MAX_LEVEL + 1];
  uint32_t* corner_id;  /* welded: per mesh vertex */
  uint32_t* corner_src; /* welded: output corner -> mesh vertex */
  uint32_t corner_count;
  /* Welded: the vertices of weld groups with more than one vertex (creases,
   * seams) in their sorted order, and whether each has the key of the one
   * before it (one corner): what the numbering took from normals and
   * alphas, checked by a kept topology (cpu_keep.c). */
  uint32_t* group;
  uint8_t* group_same;
  uint32_t group_count;
  uint32_t* slot_owner; /* per face * 4 + edge */
  uint8_t* slot_level;
  uint32_t* slot_base;
  uint32_t* interior_base; /* welded: per patch; no_weld: patch base */
  uint32_t* tri_base;
  uint32_t vertex_count, pattern_tris;
  uint32_t pattern_verts; /* vertex_count before the strip vertices */
  bool positions_only;    /* a kept topology: write positions and normals only */
  /* The walk over all edges (no draw list) found none to stitch: a kept
   * topology (same levels and links, no blends) finds none again. */
  bool walk_found_none;
  work_lists lists;
  uint32_t (*strip_tris)[3];
  uint32_t strip_count, strip_cap;
  /* Strip vertices with side a's attributes, numbered from vertex_count. */
  strip_vertex* strip_verts;
  float (*strip_attr)[4]; /* na per strip vertex */
  uint32_t strip_vert_count, strip_vert_cap;
  scratch* work;
  uint32_t work_count, work_stride;
  tlod_cpu_mesh* out;
} tess;

/* The state a tlod_cpu_mesh keeps beside its public struct (cpu_keep.c):
 * the last call's numbering and work arrays (t) and a copy of everything
 * of the mesh the topology was decided from, compared exactly. */
typedef struct tlod_cpu_keep {
  bool valid, no_weld, morph; /* morph: the kept slots were decided with blends */
  uint32_t lmax, work_count, face_count, vertex_count;
  uint32_t (*faces)[4];
  uint8_t* face_corners;
  tlod_edge_link (*links)[4];
  uint32_t* weld_id;
  tess t;
} cpu_keep;

static inline tlod_pattern_shape shape_of(const tess* t, uint32_t f) {
  return t->m.face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

static inline int level_of(const tess* t, uint32_t f) { return t->level[f]; }

static inline const level_table* table_of(const tess* t, uint32_t f) {
  return &t->tables[shape_of(t, f)][level_of(t, f)];
}

static inline bool linked(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  *link = t->m.links[f][e];
  return link->face != UINT32_MAX && level_of(t, link->face) >= 0;
}

static inline float edge_blend(const tess* t, uint32_t f, uint32_t e) { return t->morph ? t->morph[f][1 + e] : 1.0f; }

/* Welded: a patch's corner ids and edge slots, looked up once per patch;
 * the output id of a boundary vertex from its kind and parameter. */
typedef struct patch_lookup {
  uint32_t corner[4], ebase[4], shift[4];
  bool erev[4];
} patch_lookup;

void _tlod_cpu_lookup(const tess* t, uint32_t f, patch_lookup* lk);
static inline uint32_t boundary_id(const tess* t, const patch_lookup* lk, uint8_t kind, uint32_t p) {
  if (kind < KIND_EDGE) return lk->corner[kind];
  uint32_t e = kind - KIND_EDGE;
  return lk->ebase[e] + ((lk->erev[e] ? t->n_grid - p : p) >> lk->shift[e]);
}

/* cpu_tessellate.c: output id of every pattern vertex of patch f. */
void _tlod_cpu_patch_map(const tess* t, uint32_t f, uint32_t* map);
/* cpu_tessellate.c: after patch f's points are in w->pos / w->nrm (by
 * pattern vertex): its attributes, geomorphs and output vertices. */
void _tlod_cpu_finish_patch(tess* t, uint32_t f, scratch* w);
/* Whether patch f has a geomorph blend below 1 (it needs its parents). */
bool _tlod_cpu_morphs(const tess* t, uint32_t f);
/* cpu_fast.c: the params of a level-l edge's points, k << (lmax - l). */
void _tlod_cpu_edge_params(const tess* t, uint32_t l, uint32_t* param);
/* cpu_lists.c: a kept frame's positions through the work lists, when it
 * can (positions only, welded, no draw list, no attributes); false: the
 * caller runs the patch pass. */
bool _tlod_cpu_lists_eval(tess* t);
void _tlod_cpu_lists_free(tess* t);
/* cpu_fast.c: the fast path's tables, patch pass and index pass. */
tlod_result _tlod_cpu_fast_table(tess* t, tlod_pattern_shape shape, uint32_t level);
void _tlod_cpu_fast_free(tess* t, level_table* lt);
void _tlod_cpu_fast_eval(void* data, uint32_t begin, uint32_t end, uint32_t worker);
void _tlod_cpu_fast_emit(void* data, uint32_t begin, uint32_t end, uint32_t worker);
/* cpu_tessellate.c: both sides of edge e of f evaluate the same points
 * (smooth geometry, one level and blend, or a non-blending coarser side). */
bool _tlod_cpu_edge_coincides(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link);
/* cpu_tessellate.c: every array of t freed (t's fields left dangling). */
void _tlod_cpu_tess_free(tess* t);
/* cpu_tessellate.c: the draw list's blends into t->morph, checked. */
tlod_result _tlod_cpu_take_draw_list(tess* t);
/* cpu_tessellate.c: the slot patch f's edge e names (welded numbering). */
uint32_t _tlod_cpu_slot_owner(const tess* t, uint32_t f, uint32_t e);
/* cpu_tessellate.c: whether the weld groups still sort as t->group says. */
bool _tlod_cpu_corners_same(const tess* t);
/* cpu_keep.c: adopts the kept arrays into t when the topology they encode
 * is still t's (exactly); false leaves t as it was. Stores t's arrays and
 * keys after a full call (or frees them when they cannot be kept). */
bool _tlod_cpu_keep_take(cpu_keep* k, tess* t); /* k may be NULL */
bool _tlod_cpu_keep_store(cpu_keep* k, tess* t);
void _tlod_cpu_keep_free(tlod_context* ctx, cpu_keep* k);
/* cpu_strips.c: the connection strips, into t->strip_tris, after the
 * pattern vertices are written (folds compare output positions); with
 * attributes also the strip vertices carrying side a's (strip_verts). */
tlod_result _tlod_cpu_stitch(tess* t);

#endif
