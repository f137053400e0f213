/* tesslod::lod -- temporal coherence: an update whose inputs are bitwise
 * those of the last one (views, viewports, effective epsilon, mesh and
 * surface generations), with every geomorph at rest, would rebuild the
 * same draw lists; it keeps them, and their generation, instead. */
#include <string.h>

#include "scheduler_frame.h"

/* Sub-blocks of the settled scan: long enough to vectorise, short enough
 * that a scan stops soon after the first unsettled patch. */
#define SETTLED_RUN 512u

/* A culled patch (cont _TLOD_NO_HISTORY) is settled: the same inputs cull
 * it again. The untimed path of _tlod_morph_task puts a patch at its goal: the
 * target (CONTINUOUS) or its ceil; its clamps (at least the target, at most
 * the ceil) never move that goal. A ceil is checked without calling ceilf:
 * c == ceil(t) exactly when c is integral and c - 1 < t <= c (levels are
 * small integers, so every step is exact). */
static bool run_settled(const float* target, const float* cont, bool continuous, uint32_t begin, uint32_t end) {
  bool settled = true;
  if (continuous) {
    for (uint32_t f = begin; f < end; f++)
      settled &= cont[f] == target[f] || cont[f] == _TLOD_NO_HISTORY;
    return settled;
  }
  for (uint32_t f = begin; f < end; f++) {
    float c = cont[f], t = target[f];
    settled &= (c == (float)(int32_t)c && c - 1.0f < t && t <= c) || c == _TLOD_NO_HISTORY;
  }
  return settled;
}

/* Whether every patch has its continuous level where an update without
 * history puts it for its current target: then the same inputs give the
 * same levels, whatever dt_ms. Reads the arrays the last update left
 * (nothing else writes them). */
static bool morphs_settled(const tlod_scheduler* s, const _tlod_view_state* vs) {
  bool continuous = s->desc.morph == TLOD_MORPH_CONTINUOUS;
  for (uint32_t f = 0; f < s->patch_count; f += SETTLED_RUN) {
    uint32_t stop = s->patch_count - f > SETTLED_RUN ? f + SETTLED_RUN : s->patch_count;
    if (!run_settled(vs->target, vs->cont, continuous, f, stop)) return false;
  }
  return true;
}

static _tlod_view_key key_of(const tlod_scheduler* s, const tlod_view_desc* v, const tlod_mesh_view* mesh,
                             const tlod_surface_view* surface) {
  _tlod_view_key k;
  memset(&k, 0, sizeof(k)); /* padding too: keys compare with memcmp */
  memcpy(k.view, v->view, sizeof(k.view));
  memcpy(k.proj, v->proj, sizeof(k.proj));
  k.viewport_width = v->viewport_width;
  k.viewport_height = v->viewport_height;
  k.lock_to_main = v->lock_to_main;
  k.mesh_generation = mesh->generation;
  k.surface_generation = surface->generation;
  k.eps = s->desc.epsilon_px * s->eps_scale;
  return k;
}

bool _tlod_lists_unchanged(const tlod_scheduler* s, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                           const tlod_surface_view* surface) {
  if (frame->view_count > s->view_count) return false;
  for (uint32_t v = 0; v < frame->view_count; v++) {
    _tlod_view_state* vs = &s->views[v];
    _tlod_view_key k = key_of(s, &frame->views[v], mesh, surface);
    if (!vs->key_valid || memcmp(&k, &vs->key, sizeof(k)) != 0) return false;
    if (!vs->settled_known) vs->settled = morphs_settled(s, vs), vs->settled_known = true;
    if (!vs->settled) return false;
  }
  return true;
}

void _tlod_lists_remember(tlod_scheduler* s, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                          const tlod_surface_view* surface) {
  for (uint32_t v = 0; v < frame->view_count; v++) {
    s->views[v].key = key_of(s, &frame->views[v], mesh, surface);
    s->views[v].key_valid = true;
  }
}
