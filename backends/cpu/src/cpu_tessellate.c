/* tesslod::cpu -- the reference tessellator: surface x refinement patterns
 * (+ geomorphs) -> indexed triangle mesh; the connection strips are in
 * cpu_strips.c.
 *
 * This work is based on:
 *   T. Boubekeur, C. Schlick. Generic mesh refinement on GPU. Graphics
 *   Hardware 2005 (one pattern evaluated per patch);
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006.
 *
 * Output vertex numbering (welded): corners by (welded position, normal,
 * alpha, attributes); edge points by edge slot, one slot per smooth shared
 * edge that is no attribute seam and whose sides have one level (so both
 * sides use the same vertex), one per face edge otherwise; interior points
 * per patch; then the strips' vertices carrying side a's attributes.
 * Without welding each patch owns its pattern vertices, as a GPU would draw
 * them. */
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "cpu_internal.h"

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
  return t->d.reference ? TLOD_SUCCESS : _tlod_cpu_fast_table(t, shape, level);
}

/* ---- welded numbering ---------------------------------------------------- */

/* A corner's identity: welded position, normal and alpha bits, and its
 * attribute vec4s (bitwise: a seam keeps one vertex per side). */
typedef struct corner_key {
  uint32_t key[5];
  uint32_t vertex;
  const float (*attr)[4];
  uint32_t na;
} corner_key;

static int cmp_key(const corner_key* a, const corner_key* b) {
  for (int i = 0; i < 5; i++) {
    if (a->key[i] != b->key[i]) return a->key[i] < b->key[i] ? -1 : 1;
  }
  return a->na ? memcmp(a->attr, b->attr, sizeof(*a->attr) * a->na) : 0;
}

static int cmp_corner(const void* pa, const void* pb) {
  const corner_key *a = pa, *b = pb;
  int c = cmp_key(a, b);
  return c ? c : (a->vertex < b->vertex ? -1 : (a->vertex > b->vertex));
}

/* The order qsort(cmp_corner) gives, cheaper: key[0] is a weld id (a
 * vertex index), so a counting sort by it does most of the work and only
 * groups sharing a weld id (seams, creases) are sorted by the rest. */
static bool sort_corners(tess* t, corner_key* keys) {
  uint32_t nv = t->m.vertex_count;
  uint32_t* at = tlod_context_calloc(t->ctx, (size_t)nv + 1, sizeof(uint32_t));
  corner_key* sorted = tlod_context_alloc(t->ctx, sizeof(corner_key) * (nv ? nv : 1));
  if (!at || !sorted) {
    tlod_context_free(t->ctx, at);
    tlod_context_free(t->ctx, sorted);
    return false;
  }
  for (uint32_t v = 0; v < nv; v++)
    at[keys[v].key[0] + 1]++;
  for (uint32_t w = 0; w < nv; w++)
    at[w + 1] += at[w];
  for (uint32_t v = 0; v < nv; v++)
    sorted[at[keys[v].key[0]]++] = keys[v];
  memcpy(keys, sorted, sizeof(corner_key) * nv);
  for (uint32_t b = 0, e; b < nv; b = e) {
    for (e = b + 1; e < nv && keys[e].key[0] == keys[b].key[0];)
      e++;
    if (e - b > 1) qsort(keys + b, e - b, sizeof(corner_key), cmp_corner);
  }
  tlod_context_free(t->ctx, at);
  tlod_context_free(t->ctx, sorted);
  return true;
}

static void key_of(const tess* t, uint32_t v, corner_key* key) {
  const tlod_mesh_view* m = &t->m;
  key->key[0] = m->weld_id[v];
  memcpy(&key->key[1], m->normals[v], sizeof(float) * 3);
  memcpy(&key->key[4], &t->sv.vertex_alpha[v], sizeof(float));
  key->vertex = v;
  key->attr = t->na ? m->attributes + (size_t)v * t->na : NULL;
  key->na = t->na;
}

/* The sorted vertices sharing a weld id with a neighbour in that order. */
static void record_groups(tess* t, const corner_key* keys) {
  uint32_t nv = t->m.vertex_count;
  t->group_count = 0;
  for (uint32_t x = 0; x < nv; x++) {
    bool before = x > 0 && keys[x - 1].key[0] == keys[x].key[0];
    if (!before && !(x + 1 < nv && keys[x + 1].key[0] == keys[x].key[0])) continue;
    t->group[t->group_count] = keys[x].vertex;
    t->group_same[t->group_count++] = before && cmp_key(&keys[x - 1], &keys[x]) == 0;
  }
}

bool _tlod_cpu_corners_same(const tess* t) {
  for (uint32_t x = 1; x < t->group_count; x++) {
    if (t->m.weld_id[t->group[x]] != t->m.weld_id[t->group[x - 1]]) continue;
    corner_key a, b;
    key_of(t, t->group[x - 1], &a);
    key_of(t, t->group[x], &b);
    if (cmp_corner(&a, &b) >= 0 || (cmp_key(&a, &b) == 0) != (t->group_same[x] != 0)) return false;
  }
  return true;
}

static tlod_result number_corners(tess* t) {
  const tlod_mesh_view* m = &t->m;
  corner_key* keys = tlod_context_alloc(t->ctx, sizeof(corner_key) * (m->vertex_count ? m->vertex_count : 1));
  t->corner_id = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  t->corner_src = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  t->group = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (m->vertex_count + 1));
  t->group_same = tlod_context_alloc(t->ctx, m->vertex_count + 1);
  if (!keys || !t->corner_id || !t->corner_src || !t->group || !t->group_same) {
    tlod_context_free(t->ctx, keys);
    return TLOD_ERROR_OUT_OF_MEMORY;
  }
  for (uint32_t v = 0; v < m->vertex_count; v++)
    key_of(t, v, &keys[v]);
  if (!sort_corners(t, keys)) {
    tlod_context_free(t->ctx, keys);
    return TLOD_ERROR_OUT_OF_MEMORY;
  }
  uint32_t id = 0;
  for (uint32_t x = 0; x < m->vertex_count; x++) {
    if (x == 0 || cmp_key(&keys[x], &keys[x - 1]) != 0) t->corner_src[id++] = keys[x].vertex;
    t->corner_id[keys[x].vertex] = id - 1;
  }
  t->corner_count = id;
  record_groups(t, keys);
  tlod_context_free(t->ctx, keys);
  return TLOD_SUCCESS;
}

bool _tlod_cpu_edge_coincides(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  if (!linked(t, f, e, link) || !link->smooth) return false;
  int lf = level_of(t, f), lg = level_of(t, link->face);
  if (lf == lg) return edge_blend(t, f, e) == edge_blend(t, link->face, link->edge);
  return lf < lg ? edge_blend(t, f, e) == 1.0f : edge_blend(t, link->face, link->edge) == 1.0f;
}

/* Both sides use one set of vertices: the same points (the coarser side's
 * a subset of the finer side's) with the same attributes (no seam). */
static bool edge_shared(const tess* t, uint32_t f, uint32_t e, tlod_edge_link* link) {
  return _tlod_cpu_edge_coincides(t, f, e, link) && !link->seam;
}

/* The side that writes a shared edge's points: the finer one (it has them
 * all), or the smaller face at equal levels. */
static bool owns_edge(const tess* t, uint32_t f, tlod_edge_link link) {
  int lf = level_of(t, f), lg = level_of(t, link.face);
  return lf != lg ? lf > lg : f < link.face;
}

uint32_t _tlod_cpu_slot_owner(const tess* t, uint32_t f, uint32_t e) {
  tlod_edge_link link;
  return edge_shared(t, f, e, &link) && !owns_edge(t, f, link) ? link.face * 4 + link.edge : f * 4 + e;
}

static void assign_slots(tess* t) {
  const tlod_mesh_view* m = &t->m;
  uint32_t base = t->corner_count;
  for (uint32_t f = 0; f < m->face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      uint32_t slot = f * 4 + e;
      t->slot_owner[slot] = _tlod_cpu_slot_owner(t, f, e);
      if (t->slot_owner[slot] != slot) continue;
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

void _tlod_cpu_lookup(const tess* t, uint32_t f, patch_lookup* lk) {
  for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
    uint32_t slot = f * 4 + e, owner = t->slot_owner[slot];
    lk->corner[e] = t->corner_id[t->m.faces[f][e]];
    lk->ebase[e] = t->slot_base[owner] - 1;
    lk->shift[e] = t->lmax - t->slot_level[owner];
    lk->erev[e] = owner != slot;
  }
}

/* Output id of every pattern vertex of patch f, with the patch's corner and
 * edge-slot lookups done once. */
void _tlod_cpu_patch_map(const tess* t, uint32_t f, uint32_t* map) {
  const level_table* lt = table_of(t, f);
  uint32_t ib = t->interior_base[f];
  if (t->d.no_weld) {
    for (uint32_t x = 0; x < lt->nv; x++)
      map[x] = ib + x;
    return;
  }
  patch_lookup lk = {.corner = {0}};
  _tlod_cpu_lookup(t, f, &lk);
  for (uint32_t x = 0; x < lt->nv; x++) {
    uint8_t kind = lt->kind[x];
    map[x] = kind == KIND_INTERIOR ? ib + lt->param[x] : boundary_id(t, &lk, kind, lt->param[x]);
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

/* Vertex k's attributes in a vertex-major array of na vec4s; NULL without
 * attributes (no arithmetic on a NULL array). */
static const float (*attr_at(const float (*base)[4], size_t k, uint32_t na))[4] { return na ? base + k * na : NULL; }

/* An output vertex: position, normal, where it lies, and (with attributes)
 * its attribute vec4s. */
static void put(tess* t, uint32_t id, const float* pos, const float* nrm, uint32_t patch, float u, float v,
                const float (*attr)[4]) {
  tlod_cpu_mesh* o = t->out;
  memcpy(o->positions + 3 * (size_t)id, pos, sizeof(float) * 3);
  if (o->normals) memcpy(o->normals + 3 * (size_t)id, nrm, sizeof(float) * 3);
  o->vertex_patch[id] = patch;
  o->vertex_uv[id][0] = u;
  o->vertex_uv[id][1] = v;
  if (t->na) memcpy(o->attributes + (size_t)id * t->na, attr, sizeof(*attr) * t->na);
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

bool _tlod_cpu_morphs(const tess* t, uint32_t f) {
  if (!t->morph || level_of(t, f) <= 0) return false;
  for (int k = 0; k < 5; k++)
    if (t->morph[f][k] != 1.0f) return true;
  return false;
}

void _tlod_cpu_finish_patch(tess* t, uint32_t f, scratch* w) {
  int lv = level_of(t, f);
  uint32_t count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, f), &count);
  const level_table* lt = table_of(t, f);
  _tlod_cpu_patch_map(t, f, w->map);
  if (t->na) tlod_mesh_eval_attributes_grid(t->mesh, f, t->lmax, &pv[0].i, sizeof(*pv), lt->nv, w->attr);
  if (t->morph && lv > 0) {
    for (uint32_t x = tlod_pattern_vertex_count(shape_of(t, f), (uint32_t)lv - 1); x < lt->nv; x++)
      morph_vertex(t, f, pv, x, w);
  }
  for (uint32_t x = 0; x < lt->nv; x++) {
    if (writes(t, f, lt, x)) put(t, w->map[x], w->pos[x], w->nrm[x], f, pv[x].u, pv[x].v, attr_at(w->attr, x, t->na));
  }
}

static void eval_patches(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  tess* t = data;
  scratch* w = &t->work[worker];
  for (uint32_t f = begin; f < end; f++) {
    if (level_of(t, f) < 0) continue;
    uint32_t count;
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, f), &count);
    tlod_surface_eval_grid(t->s, f, t->lmax, &pv[0].i, sizeof(*pv), table_of(t, f)->nv, &w->pos[0][0], &w->nrm[0][0]);
    _tlod_cpu_finish_patch(t, f, w);
  }
}

/* (u, v) of corner c of a triangle (i, j, k) or a quad (core.h PARAMETERS). */
static const float corner_uv[2][4][2] = {{{1, 0}, {0, 1}, {0, 0}, {0, 0}}, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

/* Welded corners come from the mesh; their patch is the first drawn one
 * having them (a sequential pass: the result is the same for any thread
 * count). */
static void eval_corners(tess* t) {
  if (t->d.no_weld) return;
  tlod_cpu_mesh* o = t->out;
  if (t->positions_only) {
    for (uint32_t c = 0; c < t->corner_count; c++) {
      uint32_t v = t->corner_src[c];
      memcpy(o->positions + 3 * (size_t)c, t->m.positions[v], sizeof(float[3]));
      if (o->normals) memcpy(o->normals + 3 * (size_t)c, t->m.normals[v], sizeof(float[3]));
    }
    return;
  }
  for (uint32_t c = 0; c < t->corner_count; c++) {
    uint32_t v = t->corner_src[c];
    put(t, c, t->m.positions[v], t->m.normals[v], UINT32_MAX, 0.0f, 0.0f, attr_at(t->m.attributes, v, t->na));
  }
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    uint32_t n = t->m.face_corners[f];
    for (uint32_t k = 0; k < n; k++) {
      uint32_t id = t->corner_id[t->m.faces[f][k]];
      if (o->vertex_patch[id] != UINT32_MAX) continue;
      o->vertex_patch[id] = f;
      memcpy(o->vertex_uv[id], corner_uv[n == 4][k], sizeof(o->vertex_uv[id]));
    }
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
    _tlod_cpu_patch_map(t, f, map);
    for (uint32_t k = 0; k < count; k++)
      dst[k] = map[idx[k]];
    for (uint32_t k = 0; k < count / 3; k++)
      t->out->triangle_patch[t->tri_base[f] + k] = f;
  }
}

/* ---- driver ---------------------------------------------------------------- */

void _tlod_cpu_tess_free(tess* t) {
  _tlod_cpu_lists_free(t);
  for (int sh = 0; sh < 2; sh++) {
    for (int l = 0; l <= TLOD_MAX_LEVEL; l++) {
      tlod_context_free(t->ctx, t->tables[sh][l].kind);
      tlod_context_free(t->ctx, t->tables[sh][l].param);
      _tlod_cpu_fast_free(t, &t->tables[sh][l]);
    }
  }
  for (uint32_t w = 0; t->work && w < t->work_count; w++) {
    tlod_context_free(t->ctx, t->work[w].map);
    tlod_context_free(t->ctx, t->work[w].pos);
    tlod_context_free(t->ctx, t->work[w].nrm);
    tlod_context_free(t->ctx, t->work[w].attr);
    tlod_context_free(t->ctx, t->work[w].cpos);
    tlod_context_free(t->ctx, t->work[w].cnrm);
    tlod_context_free(t->ctx, t->work[w].queue);
  }
  void* arrays[] = {t->level,      t->morph_buf,   t->corner_id,     t->corner_src, t->slot_owner,
                    t->slot_level, t->slot_base,   t->interior_base, t->tri_base,   t->strip_tris,
                    t->work,       t->strip_verts, t->strip_attr,    t->group,      t->group_same};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(t->ctx, arrays[i]);
}

void tlod_cpu_mesh_destroy(tlod_context* ctx, tlod_cpu_mesh* mesh) {
  if (!ctx || !mesh) return;
  tlod_context_free(ctx, mesh->positions);
  tlod_context_free(ctx, mesh->normals);
  tlod_context_free(ctx, mesh->indices);
  tlod_context_free(ctx, mesh->triangle_patch);
  tlod_context_free(ctx, mesh->attributes);
  tlod_context_free(ctx, mesh->vertex_patch);
  tlod_context_free(ctx, mesh->vertex_uv);
  _tlod_cpu_keep_free(ctx, mesh->keep);
  tlod_context_free(ctx, mesh->keep);
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

tlod_result _tlod_cpu_take_draw_list(tess* t) {
  const tlod_draw_list* dl = t->d.draw_list;
  if (dl->patch_count != t->m.face_count)
    return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_cpu_tessellate: draw list of %u patches for a surface of %u", dl->patch_count,
                             t->m.face_count);
  if (dl->instance_count > 0 && !dl->instances)
    return tlod_context_fail(t->ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: draw list instances is NULL");
  if (!t->morph_buf) t->morph_buf = tlod_context_alloc(t->ctx, sizeof(*t->morph) * (t->m.face_count + 1u));
  t->morph = t->morph_buf;
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
    for (uint32_t e = 0; e < t->m.face_corners[in->patch]; e++)
      t->morph[in->patch][1 + e] = in->morph; /* edges blend with their patch */
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
  return t->d.draw_list ? _tlod_cpu_take_draw_list(t) : TLOD_SUCCESS;
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
    if (!t->d.reference && (!(t->work[w].cpos = tlod_context_alloc(t->ctx, sizeof(float[3]) * n)) ||
                            !(t->work[w].cnrm = tlod_context_alloc(t->ctx, sizeof(float[3]) * n)) ||
                            !(t->work[w].queue = tlod_context_calloc(t->ctx, 1, sizeof(lane_queue)))))
      return TLOD_ERROR_OUT_OF_MEMORY;
    if (t->na && !(t->work[w].attr = tlod_context_alloc(t->ctx, sizeof(float[4]) * t->na * n)))
      return TLOD_ERROR_OUT_OF_MEMORY;
  }
  return TLOD_SUCCESS;
}

/* Grows *p to hold count elements when the capacity is short (a mesh
 * reused frame after frame keeps its pages: no first-touch faults); the
 * first keep elements are copied over. */
static bool grow_keep(const tlod_context* ctx, void** p, size_t elem, uint32_t count, uint32_t capacity,
                      uint32_t keep) {
  if (*p && count <= capacity) return true;
  void* grown = tlod_context_alloc(ctx, elem * ((size_t)count + 1));
  if (grown && *p && keep) memcpy(grown, *p, elem * keep);
  tlod_context_free(ctx, *p);
  *p = grown;
  return grown != NULL;
}

/* The per-vertex arrays for n vertices; keep: vertices [0, keep) survive a
 * growth (the strip vertices come after the pattern vertices are written). */
static bool vertex_arrays(tess* t, uint32_t n, uint32_t keep) {
  tlod_cpu_mesh* o = t->out;
  /* An array made afresh (normals after a no_normals call) gets the whole
   * capacity: the next call may use up to it without growing. */
  uint32_t cap = o->positions ? o->vertex_capacity : 0, full = n > cap ? n : cap;
  bool ok = grow_keep(t->ctx, (void**)&o->positions, sizeof(float) * 3, full, cap, keep);
  ok = grow_keep(t->ctx, (void**)&o->vertex_patch, sizeof(uint32_t), full, o->vertex_patch ? cap : 0, keep) && ok;
  ok = grow_keep(t->ctx, (void**)&o->vertex_uv, sizeof(float) * 2, full, o->vertex_uv ? cap : 0, keep) && ok;
  if (t->d.no_normals) {
    tlod_context_free(t->ctx, o->normals);
    o->normals = NULL;
  } else {
    ok = grow_keep(t->ctx, (void**)&o->normals, sizeof(float) * 3, full, o->normals ? cap : 0, keep) && ok;
  }
  /* The attribute array's capacity counts vectors of the last call's count. */
  uint32_t acap = o->attributes && o->attribute_count == t->na ? cap : 0;
  if (t->na == 0) {
    tlod_context_free(t->ctx, o->attributes);
    o->attributes = NULL;
  } else {
    ok = grow_keep(t->ctx, (void**)&o->attributes, sizeof(float[4]) * t->na, full, acap, keep) && ok;
  }
  o->attribute_count = t->na;
  o->vertex_capacity = ok ? full : 0;
  o->vertex_count = n;
  return ok;
}

static tlod_result alloc_output(tess* t, bool indices) {
  tlod_cpu_mesh* o = t->out;
  if (!indices) return vertex_arrays(t, t->vertex_count, 0) ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
  o->pattern_triangles = t->pattern_tris;
  o->strip_triangles = t->strip_count;
  o->triangle_count = t->pattern_tris + t->strip_count;
  uint32_t cap = o->triangle_capacity, n = o->triangle_count, keep = t->positions_only ? t->pattern_tris : 0;
  bool ok = grow_keep(t->ctx, (void**)&o->indices, sizeof(uint32_t) * 3, n, cap, keep);
  ok = grow_keep(t->ctx, (void**)&o->triangle_patch, sizeof(uint32_t), n, cap, keep) && ok;
  o->triangle_capacity = ok && n > cap ? n : (ok ? cap : 0);
  return ok ? TLOD_SUCCESS : TLOD_ERROR_OUT_OF_MEMORY;
}

/* The strips' vertices carrying side a's attributes, after the pattern
 * vertices: b's position, normal, patch and (u, v), a's attributes. */
static tlod_result emit_strip_vertices(tess* t) {
  uint32_t n = t->strip_vert_count, base = t->vertex_count;
  if (n == 0) return TLOD_SUCCESS;
  if (!vertex_arrays(t, base + n, base)) return TLOD_ERROR_OUT_OF_MEMORY;
  tlod_cpu_mesh* o = t->out;
  for (uint32_t k = 0; k < n; k++) {
    uint32_t src = t->strip_verts[k].src;
    put(t, base + k, o->positions + 3 * (size_t)src, o->normals ? o->normals + 3 * (size_t)src : NULL,
        o->vertex_patch[src], o->vertex_uv[src][0], o->vertex_uv[src][1], attr_at(t->strip_attr, k, t->na));
  }
  t->vertex_count = base + n;
  return TLOD_SUCCESS;
}

/* After the pattern vertices: the strips, and (topology not kept) the
 * pattern triangles. */
static tlod_result finish(tess* t) {
  if (_tlod_cpu_stitch(t) != TLOD_SUCCESS || emit_strip_vertices(t) != TLOD_SUCCESS ||
      alloc_output(t, true) != TLOD_SUCCESS)
    return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory for triangles");
  if (!t->positions_only)
    tlod_context_parallel_for(t->ctx, t->d.reference ? emit_patches : _tlod_cpu_fast_emit, t, t->m.face_count);
  if (t->strip_count) {
    memcpy(t->out->indices + 3 * (size_t)t->pattern_tris, t->strip_tris, sizeof(uint32_t) * 3 * t->strip_count);
    for (uint32_t k = 0; k < t->strip_count; k++)
      t->out->triangle_patch[t->pattern_tris + k] = UINT32_MAX;
  }
  return TLOD_SUCCESS;
}

static tlod_result run(tess* t) {
  tlod_result r = resolve_levels(t);
  if (r != TLOD_SUCCESS) return r;
  if ((r = number_vertices(t)) != TLOD_SUCCESS || (r = alloc_output(t, false)) != TLOD_SUCCESS ||
      (r = alloc_work(t)) != TLOD_SUCCESS)
    return r == TLOD_ERROR_UNSUPPORTED
               ? tlod_context_fail(t->ctx, r, "tlod_cpu_tessellate: output would exceed 2^30 triangles")
               : tlod_context_fail(t->ctx, r, "tlod_cpu_tessellate: out of memory for %u vertices", t->vertex_count);
  t->pattern_verts = t->vertex_count;
  eval_corners(t);
  tlod_context_parallel_for(t->ctx, t->d.reference ? eval_patches : _tlod_cpu_fast_eval, t, t->m.face_count);
  return finish(t);
}

/* A kept topology (cpu_keep.c): the last call's numbering, indices and
 * (patch, u, v) stand; positions and normals are rewritten and the strips
 * redone. */
static tlod_result run_kept(tess* t) {
  t->positions_only = true;
  if (!vertex_arrays(t, t->vertex_count, t->vertex_count))
    return tlod_context_fail(t->ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory for %u vertices",
                             t->vertex_count);
  eval_corners(t);
  if (!_tlod_cpu_lists_eval(t)) tlod_context_parallel_for(t->ctx, _tlod_cpu_fast_eval, t, t->m.face_count);
  return finish(t);
}

/* After a successful call: t's arrays kept for the next (made on first
 * use), or freed where they cannot be kept. */
static tlod_result keep_arrays(tlod_context* ctx, tlod_cpu_mesh* mesh, tess* t) {
  if (!mesh->keep && !t->d.reference && t->na == 0) mesh->keep = tlod_context_calloc(ctx, 1, sizeof(cpu_keep));
  if (!mesh->keep) _tlod_cpu_tess_free(t);
  bool wanted = !t->d.reference && t->na == 0;
  if (mesh->keep ? _tlod_cpu_keep_store(mesh->keep, t) : !wanted) return TLOD_SUCCESS;
  return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "tlod_cpu_tessellate: out of memory");
}

tlod_result tlod_cpu_tessellate_into(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                     const tlod_cpu_tessellate_desc* desc, tlod_cpu_mesh* mesh) {
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!mesh || !surface || !patterns || !desc)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_cpu_tessellate: NULL argument");
  tess t = {.ctx = ctx,
            .s = surface,
            .mesh = tlod_surface_mesh(surface),
            .m = tlod_mesh_query_view(tlod_surface_mesh(surface)),
            .sv = tlod_surface_query_view(surface),
            .pat = patterns,
            .d = *desc,
            .out = mesh};
  t.simd = tlod_context_simd(ctx);
  t.lmax = tlod_patterns_max_level(patterns);
  t.n_grid = 1u << t.lmax;
  t.na = t.m.attribute_count;
  mesh->vertex_count = mesh->triangle_count = 0;
  mesh->pattern_triangles = mesh->strip_triangles = mesh->strips = mesh->folds_skipped = 0;
  bool kept = _tlod_cpu_keep_take(mesh->keep, &t);
  tlod_result r = kept ? run_kept(&t) : run(&t);
  if (r == TLOD_SUCCESS)
    r = keep_arrays(ctx, mesh, &t);
  else
    _tlod_cpu_tess_free(&t);
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
