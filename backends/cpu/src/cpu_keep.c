/* tesslod::cpu -- a kept topology (cpu.h KEPT TOPOLOGY): tlod_cpu_mesh
 * keeps the last call's numbering and work arrays beside its public struct
 * with a copy of what decided them. A call whose levels, blends-as-they-
 * decide-edge-sharing, mesh topology (faces, links: splits, creases, seams,
 * smooth flags; weld ids; the sorted order of each weld group's normals and
 * alphas), options and pattern grid are those of the kept call rewrites
 * only positions and normals (and redoes the strips, whose folds compare
 * positions). Everything is compared exactly: no hash. */
#include <string.h>

#include "cpu_internal.h"

static bool links_same(const tlod_edge_link (*a)[4], const tlod_edge_link (*b)[4], uint32_t faces) {
  for (uint32_t f = 0; f < faces; f++) {
    for (int e = 0; e < 4; e++) {
      const tlod_edge_link *x = &a[f][e], *y = &b[f][e];
      if (x->face != y->face || x->edge != y->edge || x->smooth != y->smooth || x->seam != y->seam) return false;
    }
  }
  return true;
}

/* The mesh's arrays and the call's grid, workers and weld mode. */
static bool keys_same(const cpu_keep* k, const tess* t) {
  const tlod_mesh_view* m = &t->m;
  if (!k->valid || t->na || k->no_weld != t->d.no_weld || k->lmax != t->lmax) return false;
  if (k->work_count != tlod_context_worker_count(t->ctx)) return false;
  if (k->face_count != m->face_count || k->vertex_count != m->vertex_count) return false;
  return !memcmp(k->faces, m->faces, sizeof(*m->faces) * m->face_count) &&
         !memcmp(k->face_corners, m->face_corners, m->face_count) &&
         !memcmp(k->weld_id, m->weld_id, sizeof(uint32_t) * m->vertex_count) &&
         links_same(k->links, m->links, m->face_count);
}

static bool levels_same(const tess* t) {
  const int8_t* levels = t->d.draw_list ? t->d.draw_list->levels : t->d.levels;
  if (t->d.draw_list && t->d.draw_list->patch_count != t->m.face_count) return false;
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    int lv = levels ? levels[f] : (int)t->d.level;
    if (lv != t->level[f]) return false;
  }
  return true;
}

static bool slots_same(const tess* t) {
  if (t->d.no_weld) return true;
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m.face_corners[f]; e++)
      if (_tlod_cpu_slot_owner(t, f, e) != t->slot_owner[f * 4 + e]) return false;
  }
  return true;
}

/* t with the kept arrays and its own call's inputs. */
static void adopt(cpu_keep* k, tess* t) {
  tess call = *t;
  *t = k->t;
  k->t = (tess){0};
  k->valid = false;
  t->ctx = call.ctx, t->s = call.s, t->mesh = call.mesh, t->m = call.m, t->sv = call.sv, t->pat = call.pat;
  t->d = call.d, t->simd = call.simd, t->lmax = call.lmax, t->n_grid = call.n_grid, t->na = call.na;
  t->out = call.out;
  t->morph = NULL;
  t->vertex_count = t->pattern_verts;
  t->strip_count = t->strip_vert_count = 0;
  t->positions_only = false;
}

static void keep_drop(cpu_keep* k);

bool _tlod_cpu_keep_take(cpu_keep* k, tess* t) {
  if (!k) return false;
  if (t->d.reference || !keys_same(k, t)) {
    keep_drop(k); /* the full call about to run may move the mesh's arrays */
    return false;
  }
  tess call = *t;
  bool kept_morph = k->morph;
  adopt(k, t);
  /* Without blends on either side the slots follow from the levels and
   * links alone, both already equal. */
  bool same = levels_same(t) && (!t->d.draw_list || _tlod_cpu_take_draw_list(t) == TLOD_SUCCESS) &&
              ((!kept_morph && !t->morph) || slots_same(t)) && (t->d.no_weld || _tlod_cpu_corners_same(t));
  if (same) return true;
  _tlod_cpu_tess_free(t);
  *t = call;
  return false;
}

/* Drops the kept arrays (the key copies stay for the next store). */
static void keep_drop(cpu_keep* k) {
  if (k->valid) _tlod_cpu_tess_free(&k->t);
  k->t = (tess){0};
  k->valid = false;
}

static void free_keys(tlod_context* ctx, cpu_keep* k) {
  tlod_context_free(ctx, k->faces);
  tlod_context_free(ctx, k->face_corners);
  tlod_context_free(ctx, k->links);
  tlod_context_free(ctx, k->weld_id);
  k->faces = NULL, k->face_corners = NULL, k->links = NULL, k->weld_id = NULL;
  k->face_count = k->vertex_count = 0;
}

static bool copy_keys(cpu_keep* k, const tess* t) {
  const tlod_mesh_view* m = &t->m;
  tlod_context* ctx = t->ctx;
  if (k->face_count != m->face_count || k->vertex_count != m->vertex_count || !k->faces) {
    free_keys(ctx, k);
    k->faces = tlod_context_alloc(ctx, sizeof(*m->faces) * (m->face_count + 1u));
    k->face_corners = tlod_context_alloc(ctx, m->face_count + 1u);
    k->links = tlod_context_alloc(ctx, sizeof(*m->links) * (m->face_count + 1u));
    k->weld_id = tlod_context_alloc(ctx, sizeof(uint32_t) * (m->vertex_count + 1u));
    if (!k->faces || !k->face_corners || !k->links || !k->weld_id) return false;
  }
  memcpy(k->faces, m->faces, sizeof(*m->faces) * m->face_count);
  memcpy(k->face_corners, m->face_corners, m->face_count);
  memcpy(k->links, m->links, sizeof(*m->links) * m->face_count);
  memcpy(k->weld_id, m->weld_id, sizeof(uint32_t) * m->vertex_count);
  k->face_count = m->face_count, k->vertex_count = m->vertex_count;
  return true;
}

bool _tlod_cpu_keep_store(cpu_keep* k, tess* t) {
  keep_drop(k);
  if (t->d.reference || t->na) {
    _tlod_cpu_tess_free(t);
    return true;
  }
  if (!copy_keys(k, t)) {
    _tlod_cpu_tess_free(t);
    return false;
  }
  k->t = *t;
  k->valid = true;
  k->no_weld = t->d.no_weld;
  k->morph = t->morph != NULL;
  k->lmax = t->lmax;
  k->work_count = t->work_count;
  return true;
}

void _tlod_cpu_keep_free(tlod_context* ctx, cpu_keep* k) {
  if (!k) return;
  keep_drop(k);
  free_keys(ctx, k);
}
