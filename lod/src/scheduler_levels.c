/* tesslod::lod -- levels under budgets: the target level of every patch
 * through the level rule, the search that raises epsilon (or lowers the
 * level cap) until a frame fits its triangle budget, and the frame-time
 * control that scales epsilon from measured frame times.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006 (levels from the
 *   projected error bound; the triangle count falls as epsilon grows). */
#include <math.h>

#include "scheduler_frame.h"

static void target_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  _tlod_view_state* vs = fr->vs;
  for (uint32_t f = begin; f < end; f++) {
    bool skip = fr->cull_skip && !vs->visible[f]; /* culled: target 0 (docs/design.md 3.13) */
    vs->target[f] = skip ? 0.0f
                         : _tlod_level_rule(&fr->s->desc, &fr->surface.patches[f], vs->scale[f], vs->contour[f],
                                            fr->eps, fr->level_cap);
  }
}

static tlod_pattern_shape shape_of(const tlod_mesh_view* m, uint32_t f) {
  return m->face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

/* Triangles of a frame drawn at the targets (visible patches), strips
 * included: what the budget bounds. */
static uint64_t target_triangles(const _tlod_frame* fr) {
  const float* level = fr->vs->target;
  const tlod_mesh_view* m = &fr->mesh;
  uint64_t tris = 0;
  for (uint32_t f = 0; f < fr->s->patch_count; f++) {
    if (!fr->vs->visible[f]) continue;
    uint32_t lf = _tlod_drawn_level(level[f]);
    tris += tlod_pattern_triangle_count(shape_of(m, f), lf);
    for (uint32_t e = 0; e < m->face_corners[f]; e++) {
      if (!_tlod_strip_needed(fr, level, f, e)) continue;
      tris += fr->s->patterns->connect_count[lf][_tlod_drawn_level(level[m->links[f][e].face])];
    }
  }
  return tris;
}

static void targets(_tlod_frame* fr) { tlod_context_parallel_for(fr->s->ctx, target_task, fr, fr->s->patch_count); }

/* Targets at the frame's epsilon and cap; true when they fit the budget. */
static bool targets_fit(_tlod_frame* fr) {
  targets(fr);
  return target_triangles(fr) <= fr->budget;
}

/* SILHOUETTE and UNIFORM ignore epsilon: lower the level cap instead, one
 * level at a time; level 0 everywhere is the floor. */
static void fit_cap(_tlod_frame* fr) {
  for (float cap = (float)fr->s->desc.max_level - 1.0f; cap >= 0.0f; cap -= 1.0f) {
    fr->level_cap = cap;
    if (targets_fit(fr)) return;
  }
}

/* Whether a frame fits at epsilon base * 2^x. */
typedef bool (*fits_at_fn)(void* data, float x);

/* Bisection on x = log2 of the epsilon factor, as the triangle count falls
 * while epsilon grows: doubling until the frame fits (or epsilon has grown
 * by 2^60, past every e_max), then 20 halvings, ending on the side that
 * fits. Returns that x. */
static float search_log2(fits_at_fn fits, void* data) {
  float lo = 0.0f, hi = 1.0f;
  while (!fits(data, hi) && hi <= 60.0f) {
    lo = hi;
    hi *= 2.0f;
  }
  for (int it = 0; it < 20; it++) {
    float mid = 0.5f * (lo + hi);
    if (fits(data, mid)) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return hi;
}

typedef struct one_search {
  _tlod_frame* fr;
  float base;
} one_search;

static bool one_fits_at(void* data, float x) {
  one_search* o = data;
  o->fr->eps = o->base * exp2f(x);
  return targets_fit(o->fr);
}

static void fit_epsilon(_tlod_frame* fr) {
  one_search o = {fr, fr->eps};
  fr->eps = o.base * exp2f(search_log2(one_fits_at, &o));
  targets(fr);
}

void _tlod_fit_budget(_tlod_frame* fr) {
  const tlod_scheduler_desc* d = &fr->s->desc;
  targets(fr);
  /* FLAT is the floor already: no budget can lower it. */
  if (!fr->budget || d->policy == TLOD_POLICY_FLAT || target_triangles(fr) <= fr->budget) return;
  if (d->policy == TLOD_POLICY_SILHOUETTE || d->policy == TLOD_POLICY_UNIFORM) {
    fit_cap(fr);
  } else {
    fit_epsilon(fr);
  }
}

/* ---- group budget ----------------------------------------------------------- */

static bool follows_epsilon(const _tlod_frame* fr) {
  return fr->s->desc.policy == TLOD_POLICY_ERROR || fr->s->desc.policy == TLOD_POLICY_HYBRID;
}

typedef struct group_search {
  tlod_scheduler* const* members;
  uint32_t count, budget;
  float base;
} group_search;

/* Every member that follows epsilon at the shared base * 2^x; the others
 * keep their targets. Summed in member order (deterministic). */
static uint64_t group_triangles_at(const group_search* g, float x) {
  uint64_t tris = 0;
  for (uint32_t i = 0; i < g->count; i++) {
    _tlod_frame* fr = &g->members[i]->group;
    if (follows_epsilon(fr)) {
      fr->eps = g->base * exp2f(x);
      targets(fr);
    }
    tris += target_triangles(fr);
  }
  return tris;
}

static bool group_fits_at(void* data, float x) {
  const group_search* g = data;
  return group_triangles_at(g, x) <= g->budget;
}

/* The search starts from the largest member epsilon, so that one epsilon
 * holds for all and none is drawn finer than its own bound asks. */
void _tlod_fit_group(tlod_scheduler* const* members, uint32_t count, uint32_t budget) {
  group_search g = {members, count, budget, 0.0f};
  uint64_t tris = 0;
  for (uint32_t i = 0; i < count; i++) {
    _tlod_frame* fr = &members[i]->group;
    fr->budget = budget;
    targets(fr);
    tris += target_triangles(fr);
    if (follows_epsilon(fr) && fr->eps > g.base) g.base = fr->eps;
  }
  if (tris <= budget || g.base == 0.0f) return;
  group_triangles_at(&g, search_log2(group_fits_at, &g));
}

/* A smoothed measurement outside a band around the target moves the
 * epsilon factor; inside the band nothing changes, so levels do not flicker. */
void _tlod_control_frame_time(tlod_scheduler* s, float measured) {
  float target = s->desc.frame_time_target_ms;
  if (!(target > 0.0f) || !(measured > 0.0f) || !isfinite(measured)) return;
  s->smoothed_ms = s->smoothed_ms > 0.0f ? 0.8f * s->smoothed_ms + 0.2f * measured : measured;
  if (s->smoothed_ms > 1.05f * target) s->eps_scale *= 1.1f;
  if (s->smoothed_ms < 0.85f * target) s->eps_scale /= 1.05f;
  s->eps_scale = s->eps_scale < 1.0f ? 1.0f : (s->eps_scale > 1e6f ? 1e6f : s->eps_scale);
}
