/* tesslod::lod -- temporal coherence: an update whose inputs are bitwise
 * those of the last one (views, viewports, effective epsilon, mesh and
 * surface generations), with every geomorph at rest, would rebuild the
 * same draw lists; it keeps them, and their generation, instead. */
#include <math.h>
#include <string.h>

#include "scheduler_frame.h"

bool _tlod_morph_settled(const _tlod_frame* fr, uint32_t f) {
  const tlod_scheduler_desc* d = &fr->s->desc;
  float t = fr->vs->target[f], rest = d->morph == TLOD_MORPH_CONTINUOUS ? t : ceilf(t);
  /* The untimed path of _tlod_morph_task: the goal, at least the target of
   * a bounded policy, at most the budget's level. */
  bool bounded = d->policy == TLOD_POLICY_ERROR || d->policy == TLOD_POLICY_HYBRID;
  if (bounded && rest < t) rest = t;
  if (fr->budget && rest > ceilf(t)) rest = ceilf(t);
  return fr->vs->cont[f] == rest;
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
    const _tlod_view_state* vs = &s->views[v];
    _tlod_view_key k = key_of(s, &frame->views[v], mesh, surface);
    if (!vs->key_valid || !vs->settled || memcmp(&k, &vs->key, sizeof(k)) != 0) return false;
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
