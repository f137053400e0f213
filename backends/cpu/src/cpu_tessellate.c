/* tesslod::cpu -- the reference tessellator: surface x refinement patterns
 * (+ connection strips, + geomorphs) -> indexed triangle mesh.
 *
 * This work is based on:
 *   T. Boubekeur, C. Schlick. Generic mesh refinement on GPU. Graphics
 *   Hardware 2005 (one pattern evaluated per patch);
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006.
 *
 * Output vertex numbering (welded): corners by (welded position, normal,
 * alpha); edge points by edge slot, one slot per smooth shared edge whose
 * sides have one level (so both sides use the same vertex), one per face
 * edge otherwise; interior points per patch. Without welding each patch owns
 * its pattern vertices, as a GPU would draw them. */
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "tesslod/cpu.h"

enum { KIND_EDGE = TLOD_GRID_EDGE, KIND_INTERIOR = TLOD_GRID_INTERIOR };

/* Per pattern vertex: what it is on the patch (corner c, edge e, interior)
 * and its parameter (edge: numerator of t_end over N; interior: ordinal). */
typedef struct level_table {
  uint32_t nv, interior;
  uint8_t* kind;
  uint32_t* param;
} level_table;

/* Per worker: pattern vertex -> output id, and the patch's evaluated points. */
typedef struct scratch {
  uint32_t* map;
  float (*pos)[3];
  float (*nrm)[3];
} scratch;

typedef struct tess {
  tlod_context* ctx;
  const tlod_surface* s;
  tlod_mesh_view m;     /* read-only arrays of the surface's mesh */
  tlod_surface_view sv; /* ... and of the surface (per-vertex alpha) */
  const tlod_patterns* pat;
  tlod_cpu_tessellate_desc d;
  uint32_t lmax, n_grid;
  int8_t* level;
  float (*morph)[5]; /* per patch: interior blend, then per edge; NULL: no morph */
  level_table tables[2][TLOD_MAX_LEVEL + 1];
  uint32_t* corner_id;  /* welded: per mesh vertex */
  uint32_t* corner_src; /* welded: output corner -> mesh vertex */
  uint32_t corner_count;
  uint32_t* slot_owner; /* per face * 4 + edge */
  uint8_t* slot_level;
  uint32_t* slot_base;
  uint32_t* interior_base; /* welded: per patch; no_weld: patch base */
  uint32_t* tri_base;
  uint32_t vertex_count, pattern_tris;
  uint32_t (*strip_tris)[3];
  uint32_t strip_count, strip_cap;
  scratch* work;
  uint32_t work_count, work_stride;
  tlod_cpu_mesh* out;
} tess;

static tlod_pattern_shape shape_of(const tess* t, uint32_t f) {
  return t->m.face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

static int level_of(const tess* t, uint32_t f) { return t->level[f]; }

static const level_table* table_of(const tess* t, uint32_t f) { return &t->tables[shape_of(t, f)][level_of(t, f)]; }

static tlod_result build_table(tess* t, tlod_pattern_shape shape, uint32_t level) {
  level_table* lt = &t->tables[shape][level];
  if (lt->kind) return TLOD_SUCCESS;
  uint32_t count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape, &count);
  lt->nv = tlod_pattern_vertex_count(shape, level);
  lt->kind = tlod_context_alloc(t->ctx, lt->nv);
  lt->param = tlod_context_alloc(t->ctx, sizeof(uint32_t) * lt->nv);
  if (!lt->kind || !lt->param) return TLOD_ERROR_OUT_OF_MEMORY;
  lt->interior = 0;
  for (uint32_t x = 0; x < lt->nv; x++) {
    lt->kind[x] =
        (uint8_t)tlod_grid_point_kind(shape == TLOD_PATTERN_QUAD ? 4u : 3u, t->lmax, pv[x].i, pv[x].j, &lt->param[x]);
    if (lt->kind[x] == KIND_INTERIOR) lt->param[x] = lt->interior++;
  }
  return TLOD_SUCCESS;
}

/* ---- welded numbering ---------------------------------------------------- */

/* A corner's identity: welded position, normal and alpha bits. */
typedef struct corner_key {
  uint32_t key[5];
  uint32_t vertex;
} corner_key;

static int cmp_corner(const void* pa, const void* pb) {
  const corner_key *a = pa, *b = pb;
  for (int i = 0; i < 5; i++) {
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  }
  return a->vertex < b->vertex ? -1 : (a->vertex > b->vertex);
}

static tlod_result number_corners(tess* t) {
  const tlod_mesh_view* m = &t->m;
  corner_key* keys = tlod_context_alloc(t->ctx, sizeof(corner_key) * (m->vertex_count ? m->vertex_count : 1));
  t->corner_id = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  t->corner_src = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  if (!keys || !t->corner_id || !t->corner_src) {
    tlod_context_free(t->ctx, keys);
    return TLOD_ERROR_OUT_OF_MEMORY;
  }
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    keys[v].key[0] = m->weld_id[v];
    memcpy(&keys[v].key[1], m->normals[v], sizeof(float) * 3);
    memcpy(&keys[v].key[4], &t->sv.vertex_alpha[v], sizeof(float));
    keys[v].vertex = v;
  }
  qsort(keys, m->vertex_count, sizeof(corner_key), cmp_corner);
  uint32_t id = 0;
  for (uint32_t x = 0; x < m->vertex_count; x++) {
    if (x == 0 || memcmp(keys[x].key, keys[x - 1].key, sizeof(keys[x].key)) != 0) t->corner_src[id++] = keys[x].vertex;
    t->corner_id[keys[x].vertex] = id - 1;
  }
  t->corner_count = id;
  tlod_context_free(t->ctx, keys);
  return TLOD_SUCCESS;
}

static bool linked(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  *link = t->m.links[f][e];
  return link->face != UINT32_MAX && level_of(t, link->face) >= 0;
}

static float edge_blend(const tess* t, uint32_t f, uint32_t e) { return t->morph ? t->morph[f][1 + e] : 1.0f; }

/* Both sides produce the same points on the edge (one curve: smooth), the
 * coarser side's being a subset of the finer side's: equal levels with one
 * blend, or a coarser side whose points are not blending. */
static bool edge_shared(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  if (!linked(t, f, e, link) || !link->smooth) return false;
  int lf = level_of(t, f), lg = level_of(t, link->face);
  if (lf == lg) return edge_blend(t, f, e) == edge_blend(t, link->face, link->edge);
  return lf < lg ? edge_blend(t, f, e) == 1.0f : edge_blend(t, link->face, link->edge) == 1.0f;
}

/* The side that writes a shared edge's points: the finer one (it has them
 * all), or the smaller face at equal levels. */
static bool owns_edge(const tess* t, uint32_t f, tlod_edge_link link) {
  int lf = level_of(t, f), lg = level_of(t, link.face);
  return lf != lg ? lf > lg : f < link.face;
}

static void assign_slots(tess* t) {
  const tlod_mesh_view* m = &t->m;
  uint32_t base = t->corner_count;
  for (uint32_t f = 0; f < m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      uint32_t slot = f * 4 + e;
      tlod_edge_link link;
      if (edge_shared(t, f, e, &link) && !owns_edge(t, f, link)) {
        t->slot_owner[slot] = link.face * 4 + link.edge;
        continue;
      }
      t->slot_owner[slot] = slot;
      t->slot_level[slot] = (uint8_t)level_of(t, f);
      t->slot_base[slot] = base;
      base += (1u << level_of(t, f)) - 1;
    }
  }
  for (uint32_t f = 0; f < m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    t->interior_base[f] = base;
    base += table_of(t, f)->interior;
  }
  t->vertex_count = base;
}

static void assign_unwelded(tess* t) {
  uint32_t base = 0;
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    t->interior_base[f] = base;
    base += table_of(t, f)->nv;
  }
  t->vertex_count = base;
}

/* Output id of every pattern vertex of patch f, with the patch's corner and
 * edge-slot lookups done once. */
static void patch_map(const tess* t, uint32_t f, uint32_t* map) {
  const level_table* lt = table_of(t, f);
  uint32_t ib = t->interior_base[f];
  if (t->d.no_weld) {
    for (uint32_t x = 0; x < lt->nv; x++)
      map[x] = ib + x;
    return;
  }
  uint32_t corner[4] = {0}, ebase[4] = {0}, shift[4] = {0};
  bool erev[4] = {false};
  for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
    uint32_t slot = f * 4 + e, owner = t->slot_owner[slot];
    corner[e] = t->corner_id[t->m.faces[f][e]];
    ebase[e] = t->slot_base[owner] - 1;
    shift[e] = t->lmax - t->slot_level[owner];
    erev[e] = owner != slot;
  }
  for (uint32_t x = 0; x < lt->nv; x++) {
    uint8_t kind = lt->kind[x];
    uint32_t p = lt->param[x];
    if (kind < KIND_EDGE) {
      map[x] = corner[kind];
    } else if (kind == KIND_INTERIOR) {
      map[x] = ib + p;
    } else {
      uint32_t e = kind - KIND_EDGE;
      map[x] = ebase[e] + ((erev[e] ? t->n_grid - p : p) >> shift[e]);
    }
  }
}

/* ---- evaluation ------------------------------------------------------------ */

/* Geomorph: a vertex first inserted at the drawn level starts at its
 * parents' midpoint (the coarser level's surface) and reaches the surface
 * at blend 1. Parents belong to a coarser level and are exact. */
static void morph_vertex(const tess* t, uint32_t f, const tlod_pattern_vertex* pv, uint32_t x, scratch* w) {
  const level_table* lt = table_of(t, f);
  float a = lt->kind[x] == KIND_INTERIOR ? t->morph[f][0] : t->morph[f][1 + lt->kind[x] - KIND_EDGE];
  if (a == 1.0f) return;
  const float *p0 = w->pos[pv[x].parent[0]], *p1 = w->pos[pv[x].parent[1]];
  const float *n0 = w->nrm[pv[x].parent[0]], *n1 = w->nrm[pv[x].parent[1]];
  float len = 0.0f, n[3];
  for (int k = 0; k < 3; k++) {
    float mid = 0.5f * (p0[k] + p1[k]);
    w->pos[x][k] = mid + a * (w->pos[x][k] - mid);
    n[k] = 0.5f * (n0[k] + n1[k]) * (1.0f - a) + w->nrm[x][k] * a;
    len += n[k] * n[k];
  }
  if (len > 0.0f) {
    len = 1.0f / sqrtf(len);
    for (int k = 0; k < 3; k++)
      w->nrm[x][k] = n[k] * len;
  }
}

static void put(tess* t, uint32_t id, const float* pos, const float* nrm) {
  memcpy(t->out->positions + 3 * (size_t)id, pos, sizeof(float) * 3);
  if (t->out->normals) memcpy(t->out->normals + 3 * (size_t)id, nrm, sizeof(float) * 3);
}

/* Whether this patch writes pattern vertex x (welded: corners come from
 * the mesh, shared edge points from the slot's owner). */
static bool writes(const tess* t, uint32_t f, const level_table* lt, uint32_t x) {
  if (t->d.no_weld) return true;
  uint8_t kind = lt->kind[x];
  if (kind < KIND_EDGE) return false;
  if (kind == KIND_INTERIOR) return true;
  uint32_t slot = f * 4 + (kind - KIND_EDGE);
  return t->slot_owner[slot] == slot;
}

static void eval_patches(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  tess* t = data;
  scratch* w = &t->work[worker];
  for (uint32_t f = begin; f < end; f++) {
    int lv = level_of(t, f);
    if (lv < 0) continue;
    uint32_t count;
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, f), &count);
    const level_table* lt = table_of(t, f);
    patch_map(t, f, w->map);
    tlod_surface_eval_grid(t->s, f, t->lmax, &pv[0].i, sizeof(*pv), lt->nv, &w->pos[0][0], &w->nrm[0][0]);
    if (t->morph && lv > 0) {
      for (uint32_t x = tlod_pattern_vertex_count(shape_of(t, f), (uint32_t)lv - 1); x < lt->nv; x++)
        morph_vertex(t, f, pv, x, w);
    }
    for (uint32_t x = 0; x < lt->nv; x++) {
      if (writes(t, f, lt, x)) put(t, w->map[x], w->pos[x], w->nrm[x]);
    }
  }
}

static void eval_corners(tess* t) {
  if (t->d.no_weld) return;
  for (uint32_t c = 0; c < t->corner_count; c++) {
    uint32_t v = t->corner_src[c];
    put(t, c, t->m.positions[v], t->m.normals[v]);
  }
}

static void emit_patches(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  tess* t = data;
  uint32_t* map = t->work[worker].map;
  for (uint32_t f = begin; f < end; f++) {
    int lv = level_of(t, f);
    if (lv < 0) continue;
    uint32_t count;
    const uint32_t* idx = tlod_patterns_indices(t->pat, shape_of(t, f), (uint32_t)lv, &count);
    uint32_t* dst = t->out->indices + 3 * (size_t)t->tri_base[f];
    patch_map(t, f, map);
    for (uint32_t k = 0; k < count; k++)
      dst[k] = map[idx[k]];
    for (uint32_t k = 0; k < count / 3; k++)
      t->out->triangle_patch[t->tri_base[f] + k] = f;
  }
}

/* ---- strips ---------------------------------------------------------------- */

static bool same_position(const tess* t, uint32_t a, uint32_t b) {
  return a == b || !memcmp(t->out->positions + 3 * (size_t)a, t->out->positions + 3 * (size_t)b, sizeof(float) * 3);
}

static tlod_result push_strip_tri(tess* t, const uint32_t tri[3]) {
  if (t->strip_count == t->strip_cap) {
    uint32_t cap = t->strip_cap ? t->strip_cap * 2 : 1024;
    uint32_t(*grown)[3] = tlod_context_alloc(t->ctx, sizeof(*grown) * cap);
    if (!grown) return TLOD_ERROR_OUT_OF_MEMORY;
    if (t->strip_count) memcpy(grown, t->strip_tris, sizeof(*grown) * t->strip_count);
    tlod_context_free(t->ctx, t->strip_tris);
    t->strip_tris = grown;
    t->strip_cap = cap;
  }
  memcpy(t->strip_tris[t->strip_count++], tri, sizeof(uint32_t) * 3);
  return TLOD_SUCCESS;
}

/* Output ids of edge e of patch f, in f's direction or reversed. */
static uint32_t polyline(const tess* t, uint32_t f, uint32_t e, bool reverse, uint32_t* map, uint32_t* ids) {
  uint32_t local[(1u << TLOD_MAX_LEVEL) + 1];
  uint32_t n = tlod_patterns_edge(t->pat, shape_of(t, f), (uint32_t)level_of(t, f), e, local) - 1;
  patch_map(t, f, map);
  for (uint32_t k = 0; k <= n; k++)
    ids[k] = map[local[reverse ? n - k : k]];
  return n;
}

static tlod_result stitch_edge(tess* t, uint32_t f, uint32_t e, uint32_t g, uint32_t eg) {
  uint32_t ids[2 * ((1u << TLOD_MAX_LEVEL) + 1)];
  uint32_t* map = t->work[0].map;
  uint32_t na = polyline(t, f, e, false, map, ids);
  polyline(t, g, eg, true, map, ids + na + 1);
  uint32_t count;
  const uint32_t* tris = tlod_patterns_connection(t->pat, (uint32_t)level_of(t, f), (uint32_t)level_of(t, g), &count);
  t->out->strips++;
  for (uint32_t k = 0; k < count; k++) {
    uint32_t tri[3] = {ids[tris[3 * k]], ids[tris[3 * k + 1]], ids[tris[3 * k + 2]]};
    /* Points the two sides share (a smooth edge's coarser points) make a
     * triangle with no area: leave it out. */
    if (same_position(t, tri[0], tri[1]) || same_position(t, tri[1], tri[2]) || same_position(t, tri[2], tri[0])) {
      t->out->folds_skipped++;
      continue;
    }
    if (push_strip_tri(t, tri) != TLOD_SUCCESS) return TLOD_ERROR_OUT_OF_MEMORY;
  }
  return TLOD_SUCCESS;
}

static tlod_result stitch(tess* t) {
  if (t->d.no_stitch) return TLOD_SUCCESS;
  const tlod_draw_list* dl = t->d.draw_list;
  if (dl) {
    for (uint32_t k = 0; k < dl->strip_count; k++) {
      const tlod_draw_strip* st = &dl->strips[k];
      tlod_result r = stitch_edge(t, st->patch_a, st->edge_a, st->patch_b, st->edge_b);
      if (r != TLOD_SUCCESS) return r;
    }
    return TLOD_SUCCESS;
  }
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
      tlod_edge_link link;
      if (!linked(t, f, e, &link) || link.face < f) continue;
      /* Equal levels on one curve with one blend: the polylines coincide. */
      if (link.smooth && level_of(t, f) == level_of(t, link.face) && edge_shared(t, f, e, &link)) continue;
      tlod_result r = stitch_edge(t, f, e, link.face, link.edge);
      if (r != TLOD_SUCCESS) return r;
    }
  }
  return TLOD_SUCCESS;
}

/* ---- driver ---------------------------------------------------------------- */

static void tess_free(tess* t) {
  for (int sh = 0; sh < 2; sh++) {
    for (int l = 0; l <= TLOD_MAX_LEVEL; l++) {
      tlod_context_free(t->ctx, t->tables[sh][l].kind);
      tlod_context_free(t->ctx, t->tables[sh][l].param);
    }
  }
  for (uint32_t w = 0; t->work && w < t->work_count; w++) {
    tlod_context_free(t->ctx, t->work[w].map);
    tlod_context_free(t->ctx, t->work[w].pos);
    tlod_context_free(t->ctx, t->work[w].nrm);
  }
  void* arrays[] = {t->level,     t->morph,         t->corner_id, t->corner_src, t->slot_owner, t->slot_level,
                    t->slot_base, t->interior_base, t->tri_base,  t->strip_tris, t->work};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(t->ctx, arrays[i]);
}

void tlod_cpu_mesh_destroy(tlod_context* ctx, tlod_cpu_mesh* mesh) {
  if (!ctx || !mesh) return;
  tlod_context_free(ctx, mesh->positions);
  tlod_context_free(ctx, mesh->normals);
  tlod_context_free(ctx, mesh->indices);
  tlod_context_free(ctx, mesh->triangle_patch);
  tlod_context_free(ctx, mesh);
}

/* Strips name edges of drawn patches: stitch() walks their polylines. */
static tlod_result check_strips(const tess* t, const tlod_draw_list* dl) {
  if (dl->strip_count > 0 && !dl->strips)
    return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: draw list strips is NULL");
  for (uint32_t s = 0; s < dl->strip_count; s++) {
    const tlod_draw_strip* st = &dl->strips[s];
    bool ok = st->patch_a < t->m.face_count && st->patch_b < t->m.face_count;
    ok = ok && st->edge_a < t->m.face_corners[st->patch_a] && st->edge_b < t->m.face_corners[st->patch_b];
    if (!ok || level_of(t, st->patch_a) < 0 || level_of(t, st->patch_b) < 0)
      return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "tlod_cpu_tessellate: draw list strip %u: edge %u of patch %u or edge %u of patch %u is "
                               "not an edge of a drawn patch",
                               s, st->edge_a, st->patch_a, st->edge_b, st->patch_b);
  }
  return TLOD_SUCCESS;
}

static tlod_result take_draw_list(tess* t) {
  const tlod_draw_list* dl = t->d.draw_list;
  if (dl->patch_count != t->m.face_count)
    return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_cpu_tessellate: draw list of %u patches for a surface of %u", dl->patch_count,
                             t->m.face_count);
  if (dl->instance_count > 0 && !dl->instances)
    return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: draw list instances is NULL");
  t->morph = tlod_context_alloc(t->ctx, sizeof(*t->morph) * (t->m.face_count + 1u));
  if (!t->morph) return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  for (uint32_t f = 0; f < t->m.face_count; f++)
    for (int k = 0; k < 5; k++)
      t->morph[f][k] = 1.0f;
  for (uint32_t k = 0; k < dl->instance_count; k++) {
    const tlod_draw_instance* in = &dl->instances[k];
    if (in->patch >= t->m.face_count)
      return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "tlod_cpu_tessellate: draw list instance %u: patch %u", k, in->patch);
    t->morph[in->patch][0] = in->morph;
    memcpy(&t->morph[in->patch][1], in->edge_morph, sizeof(float) * 4);
  }
  return check_strips(t, dl);
}

static tlod_result resolve_levels(tess* t) {
  uint32_t faces = t->m.face_count;
  t->level = tlod_context_alloc(t->ctx, faces ? faces : 1);
  if (!t->level) return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  const int8_t* levels = t->d.draw_list ? t->d.draw_list->levels : t->d.levels;
  for (uint32_t f = 0; f < faces; f++) {
    int lv = levels ? levels[f] : (int)t->d.level;
    if (lv > (int)t->lmax || lv < -1)
      return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                               "tlod_cpu_tessellate: patch %u: level %d outside [-1, %u] (patterns max level)", f, lv,
                               t->lmax);
    t->level[f] = (int8_t)lv;
    if (lv >= 0 && build_table(t, shape_of(t, f), (uint32_t)lv) != TLOD_SUCCESS)
      return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  }
  return t->d.draw_list ? take_draw_list(t) : TLOD_SUCCESS;
}

static tlod_result number_vertices(tess* t) {
  uint32_t faces = t->m.face_count;
  t->interior_base = tlod_context_calloc(t->ctx, faces + 1u, sizeof(uint32_t));
  t->tri_base = tlod_context_calloc(t->ctx, faces + 1u, sizeof(uint32_t));
  if (!t->interior_base || !t->tri_base) return TLOD_ERROR_OUT_OF_MEMORY;
  uint64_t tris = 0;
  for (uint32_t f = 0; f < faces; f++) {
    t->tri_base[f] = (uint32_t)tris;
    if (level_of(t, f) >= 0) tris += tlod_pattern_triangle_count(shape_of(t, f), (uint32_t)level_of(t, f));
  }
  if (tris > UINT32_MAX / 4) return TLOD_ERROR_UNSUPPORTED;
  t->pattern_tris = (uint32_t)tris;
  if (t->d.no_weld) {
    assign_unwelded(t);
    return TLOD_SUCCESS;
  }
  t->slot_owner = tlod_context_calloc(t->ctx, (size_t)faces * 4 + 1, sizeof(uint32_t));
  t->slot_level = tlod_context_calloc(t->ctx, (size_t)faces * 4 + 1, 1);
  t->slot_base = tlod_context_calloc(t->ctx, (size_t)faces * 4 + 1, sizeof(uint32_t));
  if (!t->slot_owner || !t->slot_level || !t->slot_base) return TLOD_ERROR_OUT_OF_MEMORY;
  tlod_result r = number_corners(t);
  if (r != TLOD_SUCCESS) return r;
  assign_slots(t);
  return TLOD_SUCCESS;
}

static tlod_result alloc_work(tess* t) {
  for (int sh = 0; sh < 2; sh++)
    for (int l = 0; l <= TLOD_MAX_LEVEL; l++)
      t->work_stride = t->tables[sh][l].nv > t->work_stride ? t->tables[sh][l].nv : t->work_stride;
  t->work_count = tlod_context_worker_count(t->ctx);
  t->work = tlod_context_calloc(t->ctx, t->work_count, sizeof(scratch));
  if (!t->work) return TLOD_ERROR_OUT_OF_MEMORY;
  /* Strips read polylines through the map: it must hold the longest edge. */
  size_t n = (size_t)t->work_stride + (1u << TLOD_MAX_LEVEL) + 1;
  for (uint32_t w = 0; w < t->work_count; w++) {
    t->work[w].map = tlod_context_alloc(t->ctx, sizeof(uint32_t) * n);
    t->work[w].pos = tlod_context_alloc(t->ctx, sizeof(float[3]) * n);
    t->work[w].nrm = tlod_context_alloc(t->ctx, sizeof(float[3]) * n);
    if (!t->work[w].map || !t->work[w].pos || !t->work[w].nrm) return TLOD_ERROR_OUT_OF_MEMORY;
  }
  return TLOD_SUCCESS;
}

/* Grows *p to hold count elements when the capacity is short (a mesh
 * reused frame after frame keeps its pages: no first-touch faults). */
static bool ensure(const tlod_context* ctx, void** p, size_t elem, uint32_t count, uint32_t capacity) {
  if (*p && count <= capacity) return true;
  tlod_context_free(ctx, *p);
  *p = tlod_context_alloc(ctx, elem * ((size_t)count + 1));
  return *p != NULL;
}

static tlod_result alloc_output(tess* t, bool indices) {
  tlod_cpu_mesh* o = t->out;
  if (!indices) {
    uint32_t cap = o->vertex_capacity, n = t->vertex_count;
    bool ok = ensure(t->ctx, (void**)&o->positions, sizeof(float) * 3, n, cap);
    if (t->d.no_normals) {
      tlod_context_free(t->ctx, o->normals);
      o->normals = NULL;
    } else {
      ok = ensure(t->ctx, (void**)&o->normals, sizeof(float) * 3, n, o->normals ? cap : 0) && ok;
    }
    o->vertex_capacity = ok && n > cap ? n : (ok ? cap : 0);
    o->vertex_count = n;
    return ok ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
  }
  o->pattern_triangles = t->pattern_tris;
  o->strip_triangles = t->strip_count;
  o->triangle_count = t->pattern_tris + t->strip_count;
  uint32_t cap = o->triangle_capacity, n = o->triangle_count;
  bool ok = ensure(t->ctx, (void**)&o->indices, sizeof(uint32_t) * 3, n, cap);
  ok = ensure(t->ctx, (void**)&o->triangle_patch, sizeof(uint32_t), n, cap) && ok;
  o->triangle_capacity = ok && n > cap ? n : (ok ? cap : 0);
  return ok ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
}

static tlod_result run(tess* t) {
  tlod_result r = resolve_levels(t);
  if (r != TLOD_SUCCESS) return r;
  if ((r = number_vertices(t)) != TLOD_SUCCESS || (r = alloc_output(t, false)) != TLOD_SUCCESS ||
      (r = alloc_work(t)) != TLOD_SUCCESS)
    return r == TLOD_ERROR_UNSUPPORTED
               ? tlod_context_fail(t->ctx, r, "tlod_cpu_tessellate: output would exceed 2^30 triangles")
               : tlod_context_fail(t->ctx, r, "tlod_cpu_tessellate: out of memory for %u vertices", t->vertex_count);
  eval_corners(t);
  tlod_context_parallel_for(t->ctx, eval_patches, t, t->m.face_count);
  if (stitch(t) != TLOD_SUCCESS || alloc_output(t, true) != TLOD_SUCCESS)
    return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory for triangles");
  tlod_context_parallel_for(t->ctx, emit_patches, t, t->m.face_count);
  if (t->strip_count) {
    memcpy(t->out->indices + 3 * (size_t)t->pattern_tris, t->strip_tris, sizeof(uint32_t) * 3 * t->strip_count);
    for (uint32_t k = 0; k < t->strip_count; k++)
      t->out->triangle_patch[t->pattern_tris + k] = UINT32_MAX;
  }
  return TLOD_SUCCESS;
}

tlod_result tlod_cpu_tessellate_into(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                     const tlod_cpu_tessellate_desc* desc, tlod_cpu_mesh* mesh) {
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!mesh || !surface || !patterns || !desc)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: NULL argument");
  tess t = {.ctx = ctx,
            .s = surface,
            .m = tlod_mesh_query_view(tlod_surface_mesh(surface)),
            .sv = tlod_surface_query_view(surface),
            .pat = patterns,
            .d = *desc,
            .out = mesh};
  t.lmax = tlod_patterns_max_level(patterns);
  t.n_grid = 1u << t.lmax;
  mesh->vertex_count = mesh->triangle_count = 0;
  mesh->pattern_triangles = mesh->strip_triangles = mesh->strips = mesh->folds_skipped = 0;
  tlod_result r = run(&t);
  tess_free(&t);
  if (r != TLOD_SUCCESS) mesh->vertex_count = mesh->triangle_count = 0;
  return r;
}

tlod_result tlod_cpu_tessellate(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                const tlod_cpu_tessellate_desc* desc, tlod_cpu_mesh** out) {
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out) return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: NULL argument");
  *out = NULL;
  tlod_cpu_mesh* mesh = tlod_context_calloc(ctx, 1, sizeof(tlod_cpu_mesh));
  if (!mesh) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
  tlod_result r = tlod_cpu_tessellate_into(ctx, surface, patterns, desc, mesh);
  if (r != TLOD_SUCCESS) {
    tlod_cpu_mesh_destroy(ctx, mesh);
    return r;
  }
  *out = mesh;
  return TLOD_SUCCESS;
}
