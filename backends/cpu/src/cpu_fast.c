/* tesslod::cpu -- the fast path of the tessellator (cpu.h FAST PATH): per
 * level table the interior list, the boundary list by kind and the index
 * template; per patch the interior points in one vectorised call
 * (tlod_surface_eval_interior), written straight into the output (their
 * ids are consecutive), the patch's owned edges through the canonical edge
 * function (tlod_surface_eval_edge: PN control points once per edge),
 * nothing else. Bitwise the reference (cpu_tessellate.c): the
 * same functions give every value, only who computes what and how often
 * changes. */
#include <string.h>

#include "cpu_internal.h"

static bool alloc_table(tess* t, level_table* lt, uint32_t idx_count) {
  size_t ni = lt->interior ? lt->interior : 1, nb = lt->nb ? lt->nb : 1;
  lt->int_x = tlod_context_alloc(t->ctx, sizeof(uint32_t) * ni);
  lt->int_u = tlod_context_alloc(t->ctx, sizeof(float) * ni);
  lt->int_v = tlod_context_alloc(t->ctx, sizeof(float) * ni);
  lt->int_uv = tlod_context_alloc(t->ctx, sizeof(float[2]) * ni);
  lt->bnd_x = tlod_context_alloc(t->ctx, sizeof(uint32_t) * nb);
  lt->bnd_param = tlod_context_alloc(t->ctx, sizeof(uint32_t) * nb);
  lt->bnd_ij = tlod_context_alloc(t->ctx, sizeof(uint16_t[2]) * nb);
  lt->tmpl = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (idx_count + 1u));
  lt->slot_k = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (idx_count + 1u));
  return lt->int_x && lt->int_u && lt->int_v && lt->int_uv && lt->bnd_x && lt->bnd_param && lt->bnd_ij && lt->tmpl &&
         lt->slot_k;
}

/* Boundary vertices by kind (a counting sort: corners 0..3, edges 0..3). */
static void sort_boundary(level_table* lt, const tlod_pattern_vertex* pv) {
  uint32_t at[KIND_INTERIOR + 1] = {0};
  for (uint32_t x = 0; x < lt->nv; x++)
    if (lt->kind[x] != KIND_INTERIOR) at[lt->kind[x] + 1]++;
  for (uint32_t k = 1; k <= KIND_INTERIOR; k++)
    at[k] += at[k - 1];
  for (uint32_t e = 0; e <= 4; e++)
    lt->edge_at[e] = at[KIND_EDGE + e];
  for (uint32_t x = 0; x < lt->nv; x++) {
    if (lt->kind[x] == KIND_INTERIOR) continue;
    uint32_t k = at[lt->kind[x]]++;
    lt->bnd_x[k] = x;
    lt->bnd_param[k] = lt->param[x];
    lt->bnd_ij[k][0] = pv[x].i;
    lt->bnd_ij[k][1] = pv[x].j;
  }
}

tlod_result _tlod_cpu_fast_table(tess* t, tlod_pattern_shape shape, uint32_t level) {
  level_table* lt = &t->tables[shape][level];
  uint32_t count, idx_count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape, &count);
  const uint32_t* idx = tlod_patterns_indices(t->pat, shape, level, &idx_count);
  lt->nb = lt->nv - lt->interior;
  if (!alloc_table(t, lt, idx_count)) return TLOD_ERROR_OUT_OF_MEMORY;
  float nn = (float)t->n_grid; /* as tlod_surface_eval_grid divides */
  for (uint32_t x = 0; x < lt->nv; x++) {
    if (lt->kind[x] != KIND_INTERIOR) continue;
    uint32_t k = lt->param[x];
    lt->int_x[k] = x;
    lt->int_u[k] = (float)pv[x].i / nn;
    lt->int_v[k] = (float)pv[x].j / nn;
    lt->int_uv[k][0] = pv[x].u;
    lt->int_uv[k][1] = pv[x].v;
  }
  sort_boundary(lt, pv);
  lt->nslot = 0;
  for (uint32_t k = 0; k < idx_count; k++) {
    bool inside = lt->kind[idx[k]] == KIND_INTERIOR;
    lt->tmpl[k] = inside ? lt->param[idx[k]] : 0;
    if (!inside) lt->slot_k[lt->nslot++] = k;
  }
  return TLOD_SUCCESS;
}

void _tlod_cpu_fast_free(tess* t, level_table* lt) {
  void* arrays[] = {lt->int_x,     lt->int_u,  lt->int_v, lt->int_uv, lt->bnd_x,
                    lt->bnd_param, lt->bnd_ij, lt->tmpl,  lt->slot_k};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(t->ctx, arrays[i]);
}

static void fill(uint32_t* restrict dst, uint32_t count, uint32_t value) {
  for (uint32_t k = 0; k < count; k++)
    dst[k] = value;
}

/* Positions only: the queued edges of level l in one
 * tlod_surface_eval_edges() call, point k of an edge at param k << (lmax -
 * l), id first + k - 1 (an owner's slot has its own level). */
void _tlod_cpu_edge_params(const tess* t, uint32_t l, uint32_t* param) {
  for (uint32_t k = 0; k + 1 < (1u << l); k++)
    param[k] = (k + 1) << (t->lmax - l);
}

static void flush_edges(tess* t, lane_queue* q, uint32_t l) {
  uint32_t count = (1u << l) - 1, param[1u << TLOD_MAX_LEVEL];
  _tlod_cpu_edge_params(t, l, param);
  tlod_surface_eval_edges(t->s, t->simd, t->lmax, q->edges[l], q->edge_patch[l], q->edge[l], count, param,
                          q->edge_first[l], t->out->positions);
  q->edges[l] = 0;
}

/* ... and the queued patches of shape sh and level l: their interior
 * points in ordinal order from interior_base. */
static void flush_patches(tess* t, lane_queue* q, uint32_t sh, uint32_t l) {
  const level_table* lt = &t->tables[sh][l];
  tlod_surface_eval_interiors(t->s, t->simd, q->patches[sh][l], q->patch[sh][l], lt->interior, lt->int_u, lt->int_v,
                              q->patch_first[sh][l], t->out->positions);
  q->patches[sh][l] = 0;
}

static void flush_queue(tess* t, lane_queue* q) {
  for (uint32_t l = 0; l <= TLOD_MAX_LEVEL; l++) {
    if (q->edges[l]) flush_edges(t, q, l);
    for (uint32_t sh = 0; sh < 2; sh++)
      if (q->patches[sh][l]) flush_patches(t, q, sh, l);
  }
}

static void queue_edge(tess* t, lane_queue* q, uint32_t f, uint32_t e, uint32_t slot) {
  uint32_t l = (uint32_t)level_of(t, f), at = q->edges[l]++;
  q->edge_patch[l][at] = f, q->edge[l][at] = (uint8_t)e, q->edge_first[l][at] = t->slot_base[slot];
  if (q->edges[l] == LANE_QUEUE) flush_edges(t, q, l);
}

static void queue_patch(tess* t, lane_queue* q, uint32_t f) {
  uint32_t sh = shape_of(t, f), l = (uint32_t)level_of(t, f), at = q->patches[sh][l]++;
  q->patch[sh][l][at] = f, q->patch_first[sh][l][at] = t->interior_base[f];
  if (q->patches[sh][l] == LANE_QUEUE) flush_patches(t, q, sh, l);
}

/* Edge e's points with normals, through w's compact arrays. */
static void eval_edge_normals(tess* t, uint32_t f, uint32_t e, const level_table* lt, scratch* w) {
  tlod_cpu_mesh* o = t->out;
  uint32_t slot = f * 4 + e, a = lt->edge_at[e], n = lt->edge_at[e + 1] - a;
  tlod_surface_eval_edge(t->s, f, e, t->lmax, n, lt->bnd_param + a, &w->cpos[0][0], &w->cnrm[0][0]);
  uint32_t base = t->slot_base[slot] - 1, shift = t->lmax - t->slot_level[slot];
  for (uint32_t k = 0; k < n; k++) {
    uint32_t id = base + (lt->bnd_param[a + k] >> shift);
    memcpy(o->positions + 3 * (size_t)id, w->cpos[k], sizeof(float[3]));
    memcpy(o->normals + 3 * (size_t)id, w->cnrm[k], sizeof(float[3]));
  }
}

/* Where edge e's points lie: patch f, the pattern's (u, v). */
static void edge_places(tess* t, uint32_t f, uint32_t e, const level_table* lt) {
  tlod_cpu_mesh* o = t->out;
  uint32_t count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, f), &count);
  uint32_t slot = f * 4 + e, a = lt->edge_at[e], n = lt->edge_at[e + 1] - a;
  uint32_t base = t->slot_base[slot] - 1, shift = t->lmax - t->slot_level[slot];
  for (uint32_t k = 0; k < n; k++) {
    uint32_t x = lt->bnd_x[a + k], id = base + (lt->param[x] >> shift);
    o->vertex_patch[id] = f;
    o->vertex_uv[id][0] = pv[x].u;
    o->vertex_uv[id][1] = pv[x].v;
  }
}

/* Welded, no geomorph, no attributes: interior points straight into the
 * output, then the edges this patch owns (positions only: both queued). */
static void eval_direct(tess* t, uint32_t f, const level_table* lt, scratch* w) {
  tlod_cpu_mesh* o = t->out;
  uint32_t ib = t->interior_base[f], ni = lt->interior;
  if (o->normals)
    tlod_surface_eval_interior(t->s, f, t->simd, ni, lt->int_u, lt->int_v, o->positions + 3 * (size_t)ib,
                               o->normals + 3 * (size_t)ib);
  else if (ni)
    queue_patch(t, w->queue, f);
  if (!t->positions_only) {
    fill(o->vertex_patch + ib, ni, f);
    memcpy(o->vertex_uv + ib, lt->int_uv, sizeof(float[2]) * ni);
  }
  for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
    uint32_t slot = f * 4 + e;
    if (t->slot_owner[slot] != slot || lt->edge_at[e + 1] == lt->edge_at[e]) continue;
    if (o->normals)
      eval_edge_normals(t, f, e, lt, w);
    else
      queue_edge(t, w->queue, f, e, slot);
    if (!t->positions_only) edge_places(t, f, e, lt);
  }
}

/* Every point into w->pos / w->nrm by pattern vertex (geomorphs read the
 * parents; no_weld writes them all), then the reference's write. */
static void eval_all(tess* t, uint32_t f, const level_table* lt, scratch* w) {
  tlod_surface_eval_interior(t->s, f, t->simd, lt->interior, lt->int_u, lt->int_v, &w->cpos[0][0], &w->cnrm[0][0]);
  for (uint32_t k = 0; k < lt->interior; k++) {
    memcpy(w->pos[lt->int_x[k]], w->cpos[k], sizeof(float[3]));
    memcpy(w->nrm[lt->int_x[k]], w->cnrm[k], sizeof(float[3]));
  }
  tlod_surface_eval_grid(t->s, f, t->lmax, lt->bnd_ij[0], sizeof(lt->bnd_ij[0]), lt->nb, &w->cpos[0][0],
                         &w->cnrm[0][0]);
  for (uint32_t k = 0; k < lt->nb; k++) {
    memcpy(w->pos[lt->bnd_x[k]], w->cpos[k], sizeof(float[3]));
    memcpy(w->nrm[lt->bnd_x[k]], w->cnrm[k], sizeof(float[3]));
  }
  _tlod_cpu_finish_patch(t, f, w);
}

void _tlod_cpu_fast_eval(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  tess* t = data;
  scratch* w = &t->work[worker];
  for (uint32_t f = begin; f < end; f++) {
    if (level_of(t, f) < 0) continue;
    const level_table* lt = table_of(t, f);
    if (t->d.no_weld || t->na || _tlod_cpu_morphs(t, f))
      eval_all(t, f, lt, w);
    else
      eval_direct(t, f, lt, w);
  }
  flush_queue(t, w->queue);
}

/* The pattern's indices plus the patch's offset; welded, the template holds
 * interior ordinals and only boundary entries are remapped. */
static void add_offset(uint32_t* restrict dst, const uint32_t* restrict src, uint32_t count, uint32_t offset) {
  for (uint32_t k = 0; k < count; k++)
    dst[k] = src[k] + offset;
}

static void emit_one(const tess* t, uint32_t f, const level_table* lt, uint32_t* dst) {
  uint32_t count, ib = t->interior_base[f];
  const uint32_t* idx = tlod_patterns_indices(t->pat, shape_of(t, f), (uint32_t)level_of(t, f), &count);
  add_offset(dst, t->d.no_weld ? idx : lt->tmpl, count, ib);
  if (t->d.no_weld) return;
  patch_lookup lk = {.corner = {0}};
  _tlod_cpu_lookup(t, f, &lk);
  for (uint32_t s = 0; s < lt->nslot; s++) {
    uint32_t k = lt->slot_k[s], x = idx[k];
    dst[k] = boundary_id(t, &lk, lt->kind[x], lt->param[x]);
  }
}

void _tlod_cpu_fast_emit(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tess* t = data;
  for (uint32_t f = begin; f < end; f++) {
    if (level_of(t, f) < 0) continue;
    const level_table* lt = table_of(t, f);
    uint32_t tb = t->tri_base[f], tris = tlod_pattern_triangle_count(shape_of(t, f), (uint32_t)level_of(t, f));
    emit_one(t, f, lt, t->out->indices + 3 * (size_t)tb);
    fill(t->out->triangle_patch + tb, tris, f);
  }
}
