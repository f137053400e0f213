/* tesslod::cpu -- a kept frame's positions-only work as flat lists: the
 * patch pass (cpu_fast.c) re-derives, patch by patch, which edges it owns
 * and where its points go, although a kept topology decides the same every
 * frame. The lists hold that once (built at the first kept frame that can
 * use them); each frame then hands them to tlod_surface_eval_edges() and
 * tlod_surface_eval_interiors() in ranges. The same calls with the same
 * points as the patch pass: bitwise its output. */
#include <string.h>

#include "cpu_internal.h"

/* What the patch pass would queue: every drawn patch goes direct (welded,
 * no attributes, no draw list so no blends) and positions only. */
static bool usable(const tess* t) {
  return t->positions_only && !t->out->normals && !t->d.no_weld && !t->na && !t->d.draw_list;
}

static uint32_t patch_key(const tess* t, uint32_t f) {
  return (uint32_t)shape_of(t, f) * (TLOD_MAX_LEVEL + 1) + (uint32_t)level_of(t, f);
}

static bool owns(const tess* t, uint32_t f, uint32_t e) {
  uint32_t slot = f * 4 + e;
  return level_of(t, f) > 0 && t->slot_owner[slot] == slot;
}

/* Entries per level (edges) and per key (patches), as offsets. */
static void count_entries(tess* t, work_lists* w) {
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m.face_corners[f]; e++)
      w->edge_at[level_of(t, f) + 1] += owns(t, f, e);
    if (table_of(t, f)->interior) w->patch_at[patch_key(t, f) + 1]++;
  }
  for (uint32_t l = 0; l <= TLOD_MAX_LEVEL; l++)
    w->edge_at[l + 1] += w->edge_at[l];
  for (uint32_t k = 0; k < 2 * (TLOD_MAX_LEVEL + 1); k++)
    w->patch_at[k + 1] += w->patch_at[k];
}

static void fill_entries(tess* t, work_lists* w) {
  uint32_t e_at[TLOD_MAX_LEVEL + 2], p_at[2 * (TLOD_MAX_LEVEL + 1) + 1];
  memcpy(e_at, w->edge_at, sizeof(e_at));
  memcpy(p_at, w->patch_at, sizeof(p_at));
  for (uint32_t f = 0; f < t->m.face_count; f++) {
    if (level_of(t, f) < 0) continue;
    for (uint32_t e = 0; e < t->m.face_corners[f]; e++) {
      if (!owns(t, f, e)) continue;
      uint32_t k = e_at[level_of(t, f)]++;
      w->edge_patch[k] = f, w->edge[k] = (uint8_t)e, w->edge_first[k] = t->slot_base[f * 4 + e];
    }
    if (!table_of(t, f)->interior) continue;
    uint32_t k = p_at[patch_key(t, f)]++;
    w->patch[k] = f, w->patch_first[k] = t->interior_base[f];
  }
}

static bool build(tess* t) {
  work_lists* w = &t->lists;
  *w = (work_lists){.built = false};
  count_entries(t, w);
  uint32_t ne = w->edge_at[TLOD_MAX_LEVEL + 1], np = w->patch_at[2 * (TLOD_MAX_LEVEL + 1)];
  w->edge_patch = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (ne + 1u));
  w->edge_first = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (ne + 1u));
  w->edge = tlod_context_alloc(t->ctx, ne + 1u);
  w->patch = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (np + 1u));
  w->patch_first = tlod_context_alloc(t->ctx, sizeof(uint32_t) * (np + 1u));
  if (!w->edge_patch || !w->edge_first || !w->edge || !w->patch || !w->patch_first) {
    _tlod_cpu_lists_free(t);
    return false;
  }
  fill_entries(t, w);
  w->built = true;
  return true;
}

/* [begin, end) of the edge list, one call per level it spans. */
static void edges_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tess* t = data;
  const work_lists* w = &t->lists;
  uint32_t param[1u << TLOD_MAX_LEVEL];
  for (uint32_t l = 1; l <= TLOD_MAX_LEVEL; l++) {
    uint32_t lo = w->edge_at[l] > begin ? w->edge_at[l] : begin, hi = w->edge_at[l + 1] < end ? w->edge_at[l + 1] : end;
    if (lo >= hi) continue;
    _tlod_cpu_edge_params(t, l, param);
    tlod_surface_eval_edges(t->s, t->simd, t->lmax, hi - lo, w->edge_patch + lo, w->edge + lo, (1u << l) - 1, param,
                            w->edge_first + lo, t->out->positions);
  }
}

/* [begin, end) of the patch list, one call per shape and level it spans. */
static void patches_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  tess* t = data;
  const work_lists* w = &t->lists;
  for (uint32_t k = 0; k < 2 * (TLOD_MAX_LEVEL + 1); k++) {
    uint32_t lo = w->patch_at[k] > begin ? w->patch_at[k] : begin;
    uint32_t hi = w->patch_at[k + 1] < end ? w->patch_at[k + 1] : end;
    if (lo >= hi) continue;
    const level_table* lt = &t->tables[k / (TLOD_MAX_LEVEL + 1)][k % (TLOD_MAX_LEVEL + 1)];
    tlod_surface_eval_interiors(t->s, t->simd, hi - lo, w->patch + lo, lt->interior, lt->int_u, lt->int_v,
                                w->patch_first + lo, t->out->positions);
  }
}

bool _tlod_cpu_lists_eval(tess* t) {
  if (!usable(t) || (!t->lists.built && !build(t))) return false;
  tlod_context_parallel_for(t->ctx, edges_task, t, t->lists.edge_at[TLOD_MAX_LEVEL + 1]);
  tlod_context_parallel_for(t->ctx, patches_task, t, t->lists.patch_at[2 * (TLOD_MAX_LEVEL + 1)]);
  return true;
}

void _tlod_cpu_lists_free(tess* t) {
  work_lists* w = &t->lists;
  void* arrays[] = {w->edge_patch, w->edge_first, w->edge, w->patch, w->patch_first};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(t->ctx, arrays[i]);
  *w = (work_lists){.built = false};
}
