/* tesslod::cpu -- connection strips: the two edge polylines of an edge whose
 * sides differ (levels, blends, split normals) zipped by the connection
 * patterns of tesslod/patterns.h. Every strip triangle takes its attributes
 * from side a: a point of b's polyline whose attributes differ from a's at
 * the same edge point gets a strip vertex of its own (b's position, a's
 * attributes), so a strip never blends the two sides of a seam.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006 (connection
 *   patterns). */
#include <string.h>

#include "cpu_internal.h"

static bool same_position(const tess* t, uint32_t a, uint32_t b) {
  return a == b || !memcmp(t->out->positions + 3 * (size_t)a, t->out->positions + 3 * (size_t)b, sizeof(float) * 3);
}

/* Doubles *p (elem bytes an entry, used entries kept) when it is full. */
static bool grow(const tlod_context* ctx, void** p, size_t elem, uint32_t used, uint32_t cap, uint32_t new_cap) {
  if (used < cap) return true;
  void* grown = tlod_context_alloc(ctx, elem * new_cap);
  if (!grown) return false;
  if (used) memcpy(grown, *p, elem * used);
  tlod_context_free(ctx, *p);
  *p = grown;
  return true;
}

static tlod_result push_strip_tri(tess* t, const uint32_t tri[3]) {
  uint32_t cap = t->strip_cap ? t->strip_cap * 2 : 1024;
  if (!grow(t->ctx, (void**)&t->strip_tris, sizeof(*t->strip_tris), t->strip_count, t->strip_cap, cap))
    return TLOD_ERROR_OUT_OF_MEMORY;
  if (t->strip_count == t->strip_cap) t->strip_cap = cap;
  memcpy(t->strip_tris[t->strip_count++], tri, sizeof(uint32_t) * 3);
  return TLOD_SUCCESS;
}

/* A new strip vertex copying output vertex src, with attributes attr. */
static tlod_result push_strip_vertex(tess* t, uint32_t src, const float (*attr)[4], uint32_t* id) {
  uint32_t n = t->strip_vert_count, cap = t->strip_vert_cap ? t->strip_vert_cap * 2 : 256;
  if (!grow(t->ctx, (void**)&t->strip_verts, sizeof(*t->strip_verts), n, t->strip_vert_cap, cap) ||
      !grow(t->ctx, (void**)&t->strip_attr, sizeof(*t->strip_attr) * t->na, n, t->strip_vert_cap, cap))
    return TLOD_ERROR_OUT_OF_MEMORY;
  if (n == t->strip_vert_cap) t->strip_vert_cap = cap;
  if ((uint64_t)t->vertex_count + n >= UINT32_MAX) return TLOD_ERROR_OUT_OF_MEMORY;
  t->strip_verts[n].src = src;
  memcpy(t->strip_attr + (size_t)n * t->na, attr, sizeof(*attr) * t->na);
  *id = t->vertex_count + n;
  t->strip_vert_count++;
  return TLOD_SUCCESS;
}

/* Pattern vertices of edge e of patch f, in f's direction; returns the
 * segment count. */
static uint32_t edge_vertices(const tess* t, uint32_t f, uint32_t e, uint32_t* local) {
  return tlod_patterns_edge(t->pat, shape_of(t, f), (uint32_t)level_of(t, f), e, local) - 1;
}

/* Grid point of edge e at end-corner weight q over N = 2^lmax, as
 * tlod_grid_point_kind() classifies it (tesslod/core.h). */
static void edge_grid_point(uint32_t corners, uint32_t e, uint32_t nn, uint32_t q, uint16_t ij[2]) {
  static const int tri[3][4] = {{1, -1, 0, 1}, {0, 0, 1, -1}, {0, 1, 0, 0}}; /* i = a N + b q, j = c N + d q */
  static const int quad[4][4] = {{0, 1, 0, 0}, {1, 0, 0, 1}, {1, -1, 1, 0}, {0, 0, 1, -1}};
  const int* r = corners == 3 ? tri[e] : quad[e];
  ij[0] = (uint16_t)((int)nn * r[0] + r[1] * (int)q);
  ij[1] = (uint16_t)((int)nn * r[2] + r[3] * (int)q);
}

/* End-corner weight on edge eg of patch g of pattern vertex x (on that edge). */
static uint32_t edge_weight(const tess* t, uint32_t g, uint32_t eg, const tlod_pattern_vertex* pv) {
  uint32_t param = 0, kind = tlod_grid_point_kind(t->m.face_corners[g], t->lmax, pv->i, pv->j, &param);
  if (kind < KIND_EDGE) return kind == eg ? 0 : t->n_grid;
  return param;
}

/* b's polyline (ids in a's direction, nb segments): every point whose
 * output attributes differ from a's at the same edge point is replaced by
 * a strip vertex with a's. local: b's pattern vertices in b's direction. */
static tlod_result take_side_a(tess* t, uint32_t f, uint32_t e, uint32_t g, uint32_t eg, const uint32_t* local,
                               uint32_t nb, uint32_t* ids) {
  uint16_t ij[(1u << TLOD_MAX_LEVEL) + 1][2];
  uint32_t count;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(t->pat, shape_of(t, g), &count);
  for (uint32_t k = 0; k <= nb; k++) {
    uint32_t q = t->n_grid - edge_weight(t, g, eg, &pv[local[nb - k]]);
    edge_grid_point(t->m.face_corners[f], e, t->n_grid, q, ij[k]);
  }
  float(*a)[4] = t->work[0].attr;
  tlod_mesh_eval_attributes_grid(t->mesh, f, t->lmax, &ij[0][0], sizeof(ij[0]), nb + 1, a);
  for (uint32_t k = 0; k <= nb; k++) {
    const float(*have)[4] = t->out->attributes + (size_t)ids[k] * t->na;
    if (!memcmp(have, a + (size_t)k * t->na, sizeof(*a) * t->na)) continue;
    tlod_result r = push_strip_vertex(t, ids[k], (const float(*)[4])a + (size_t)k * t->na, &ids[k]);
    if (r != TLOD_SUCCESS) return r;
  }
  return TLOD_SUCCESS;
}

/* ids[0..na] a's polyline, then b's reversed (so both run in a's
 * direction); attr_ids the same with b's points carrying a's attributes. */
static tlod_result polylines(tess* t, uint32_t f, uint32_t e, uint32_t g, uint32_t eg, uint32_t* ids,
                             uint32_t* attr_ids, uint32_t* na_out) {
  uint32_t local[(1u << TLOD_MAX_LEVEL) + 1];
  uint32_t* map = t->work[0].map;
  uint32_t na = edge_vertices(t, f, e, local);
  _tlod_cpu_patch_map(t, f, map);
  for (uint32_t k = 0; k <= na; k++)
    ids[k] = map[local[k]];
  uint32_t nb = edge_vertices(t, g, eg, local);
  _tlod_cpu_patch_map(t, g, map);
  for (uint32_t k = 0; k <= nb; k++)
    ids[na + 1 + k] = map[local[nb - k]];
  *na_out = na;
  memcpy(attr_ids, ids, sizeof(uint32_t) * (na + nb + 2));
  return t->na ? take_side_a(t, f, e, g, eg, local, nb, attr_ids + na + 1) : TLOD_SUCCESS;
}

/* st: the draw list's strip (its connection, exact or not, as the GPU draws
 * it), or NULL: the full connection of the two levels. */
static tlod_result stitch_edge(tess* t, uint32_t f, uint32_t e, uint32_t g, uint32_t eg, const tlod_draw_strip* st) {
  uint32_t ids[2 * ((1u << TLOD_MAX_LEVEL) + 1)], attr_ids[2 * ((1u << TLOD_MAX_LEVEL) + 1)], na;
  tlod_result r = polylines(t, f, e, g, eg, ids, attr_ids, &na);
  if (r != TLOD_SUCCESS) return r;
  uint32_t count;
  const uint32_t* tris =
      st ? tlod_draw_strip_connection(t->pat, st, &count)
         : tlod_patterns_connection(t->pat, (uint32_t)level_of(t, f), (uint32_t)level_of(t, g), &count);
  t->out->strips++;
  for (uint32_t k = 0; k < count; k++) {
    const uint32_t* c = tris + 3 * k;
    uint32_t tri[3] = {ids[c[0]], ids[c[1]], ids[c[2]]};
    /* Points the two sides share (a smooth edge's coarser points) make a
     * triangle with no area: leave it out. */
    if (same_position(t, tri[0], tri[1]) || same_position(t, tri[1], tri[2]) || same_position(t, tri[2], tri[0])) {
      t->out->folds_skipped++;
      continue;
    }
    uint32_t drawn[3] = {attr_ids[c[0]], attr_ids[c[1]], attr_ids[c[2]]};
    if (push_strip_tri(t, drawn) != TLOD_SUCCESS) return TLOD_ERROR_OUT_OF_MEMORY;
  }
  return TLOD_SUCCESS;
}

tlod_result _tlod_cpu_stitch(tess* t) {
  if (t->d.no_stitch) return TLOD_SUCCESS;
  const tlod_draw_list* dl = t->d.draw_list;
  if (dl) {
    for (uint32_t k = 0; k < dl->strip_count; k++) {
      const tlod_draw_strip* st = &dl->strips[k];
      tlod_result r = stitch_edge(t, st->patch_a, st->edge_a, st->patch_b, st->edge_b, st);
      if (r != TLOD_SUCCESS) return r;
    }
    return TLOD_SUCCESS;
  }
  if (t->positions_only && t->walk_found_none) return TLOD_SUCCESS;
  bool found = false;
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
      tlod_edge_link link;
      if (!linked(t, f, e, &link) || link.face < f) continue;
      /* Equal levels on one curve with one blend: the polylines coincide
       * (on a seam too: there each side keeps its own vertices). */
      if (level_of(t, f) == level_of(t, link.face) && _tlod_cpu_edge_coincides(t, f, e, &link)) continue;
      found = true;
      tlod_result r = stitch_edge(t, f, e, link.face, link.edge, NULL);
      if (r != TLOD_SUCCESS) return r;
    }
  }
  t->walk_found_none = !found;
  return TLOD_SUCCESS;
}
