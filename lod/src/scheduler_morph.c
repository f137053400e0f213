/* tesslod::lod -- geomorph state: each patch's continuous level follows its
 * target (at once, or 1 level per morph_ms of frame time, never below the
 * blend that meets the error bound), and the drawn level and vertex blends
 * derive from it.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006, sec. 5 (vertices
 *   new at a level blend from their parents' midpoint). */
#include <math.h>

#include "scheduler_frame.h"

/* Continuous level c moved towards target t by at most step. */
static float approach(float c, float t, float step) {
  if (c < t) return c + step < t ? c + step : t;
  if (c > t) return c - step > t ? c - step : t;
  return c;
}

void _tlod_morph_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  _tlod_view_state* vs = fr->vs;
  const tlod_scheduler_desc* d = &fr->s->desc;
  /* Without history (first frame, after a reset) there is nothing to blend from. */
  bool timed = d->morph == TLOD_MORPH_TIME && vs->has_history;
  /* ERROR and HYBRID targets are fractional: the smallest continuous level
   * whose blended mesh meets eps (docs/design.md 3.9). TIME and NONE head
   * for its ceil, the discrete level, and never fall below it. */
  bool bounded = d->policy == TLOD_POLICY_ERROR || d->policy == TLOD_POLICY_HYBRID;
  bool fractional = d->morph == TLOD_MORPH_CONTINUOUS;
  for (uint32_t f = begin; f < end; f++) {
    float t = vs->target[f], goal = fractional ? t : ceilf(t);
    /* A culled patch keeps no history: back in view it starts at its goal. */
    bool history = timed && vs->visible[f] && vs->cont[f] != _TLOD_NO_HISTORY;
    float c = history ? approach(vs->cont[f], goal, fr->step) : goal;
    if (bounded && c < t) c = t;
    /* A budget is a hard cap: never draw above the budget's level. */
    if (fr->budget && c > ceilf(t)) c = ceilf(t);
    vs->cont[f] = fr->cull_skip && !vs->visible[f] ? _TLOD_NO_HISTORY : c;
  }
}

/* An edge's new vertices blend with their patch: a blend shared with an
 * equal-level neighbour (the smaller of the two) cannot stay continuous, as
 * the shared value jumps whenever either side changes level (its coarser
 * edge vertices then become exact). Equal-level neighbours whose blends
 * differ get a strip instead (Schwarz et al. 2006, sec. 5), as do creases
 * and level differences. FLAT draws the input faces: no strip at all. */
bool _tlod_strip_needed(const _tlod_frame* fr, const float* cont, uint32_t f, uint32_t e) {
  tlod_edge_link link = fr->mesh.links[f][e];
  uint32_t g = link.face;
  if (fr->s->desc.policy == TLOD_POLICY_FLAT) return false;
  if (g == _TLOD_NO_FACE || g < f || !fr->vs->visible[g]) return false;
  uint32_t lf = _tlod_drawn_level(cont[f]), lg = _tlod_drawn_level(cont[g]);
  return !link.smooth || lf != lg || _tlod_morph_of(cont[f], lf) != _tlod_morph_of(cont[g], lg);
}
