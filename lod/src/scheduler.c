/* tesslod::lod -- the per-frame scheduler: silhouette depth, projected
 * error, levels by policy under budgets, geomorph state, draw list.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006;
 *   T. Boubekeur, M. Alexa. Phong Tessellation. 2008 (silhouette depth).
 * Every stage writes only its own patch or vertex entries, so the result
 * does not depend on how the context's workers split the work. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "patterns_internal.h"
#include "scheduler_internal.h"

static tlod_scheduler_desc scheduler_desc_defaults(const tlod_scheduler_desc* in, const tlod_patterns* p) {
  tlod_scheduler_desc d = in ? *in : (tlod_scheduler_desc){0};
  if (d.epsilon_px == 0.0f) d.epsilon_px = 0.5f;
  if (d.max_level == 0) d.max_level = tlod_patterns_max_level(p);
  if (d.policy == TLOD_POLICY_DEFAULT) d.policy = TLOD_POLICY_HYBRID;
  if (d.silhouette_depth == 0.0f) d.silhouette_depth = (float)(1u << d.max_level);
  if (d.hybrid_relax == 0.0f) d.hybrid_relax = 16.0f;
  if (d.morph == TLOD_MORPH_DEFAULT) d.morph = TLOD_MORPH_TIME;
  if (d.morph_ms == 0.0f) d.morph_ms = 200.0f;
  if (!d.label) d.label = "scheduler";
  return d;
}

static tlod_result validate_desc(tlod_context* ctx, const tlod_scheduler_desc* d, const tlod_patterns* p) {
  const char* what = NULL;
  if (!(d->epsilon_px > 0.0f) || !isfinite(d->epsilon_px)) what = "epsilon_px must be positive and finite";
  if (d->max_level > tlod_patterns_max_level(p)) what = "max_level is above the patterns' max level";
  if ((unsigned)d->policy >= TLOD_POLICY_NUM) what = "unknown policy";
  if ((unsigned)d->morph >= TLOD_MORPH_NUM) what = "unknown morph mode";
  if (!(d->silhouette_depth > 0.0f) || !isfinite(d->silhouette_depth)) what = "silhouette_depth must be positive";
  if (!(d->hybrid_relax >= 1.0f) || !isfinite(d->hybrid_relax)) what = "hybrid_relax must be >= 1";
  if (!(d->morph_ms > 0.0f) || !isfinite(d->morph_ms)) what = "morph_ms must be positive";
  if (!(d->frame_time_target_ms >= 0.0f) || !isfinite(d->frame_time_target_ms))
    what = "frame_time_target_ms must be >= 0";
  return what ? _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': %s", d->label, what) : TLOD_SUCCESS;
}

static void free_view(tlod_context* ctx, _tlod_view_state* v) {
  void* arrays[] = {v->levels, v->e_max, v->depth, v->contour, v->target, v->cont, v->visible, v->instances, v->strips};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    _tlod_free(ctx, arrays[i]);
  memset(v, 0, sizeof(*v));
}

static tlod_result alloc_view(tlod_scheduler* s, _tlod_view_state* v) {
  tlod_context* ctx = s->ctx;
  size_t np = (size_t)s->patch_count + 1, nv = (size_t)s->vertex_count + 1;
  v->levels = _tlod_calloc(ctx, np, 1);
  v->e_max = _tlod_calloc(ctx, np, sizeof(float));
  v->depth = _tlod_calloc(ctx, nv, sizeof(float));
  v->contour = _tlod_calloc(ctx, np, sizeof(float));
  v->target = _tlod_calloc(ctx, np, sizeof(float));
  v->cont = _tlod_calloc(ctx, np, sizeof(float));
  v->visible = _tlod_calloc(ctx, np, 1);
  v->instances = _tlod_calloc(ctx, np, sizeof(tlod_draw_instance));
  bool ok = v->levels && v->e_max && v->depth && v->contour && v->target && v->cont && v->visible && v->instances;
  return ok ? TLOD_SUCCESS : _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
}

tlod_result tlod_scheduler_create(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                  const tlod_scheduler_desc* desc, tlod_scheduler** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out || !surface || !patterns)
    return _tlod_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_scheduler_create: NULL argument");
  tlod_scheduler_desc d = scheduler_desc_defaults(desc, patterns);
  tlod_result r = validate_desc(ctx, &d, patterns);
  if (r != TLOD_SUCCESS) return r;
  tlod_scheduler* s = _tlod_calloc(ctx, 1, sizeof(*s));
  if (!s) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", d.label);
  s->ctx = ctx;
  s->surface = surface;
  s->mesh = tlod_surface_mesh(surface);
  s->patterns = patterns;
  s->desc = d;
  snprintf(s->label, sizeof(s->label), "%s", d.label);
  s->desc.label = s->label;
  s->patch_count = tlod_surface_patch_count(surface);
  s->vertex_count = tlod_mesh_vertex_count(s->mesh);
  s->eps_scale = 1.0f;
  *out = s;
  return TLOD_SUCCESS;
}

void tlod_scheduler_destroy(tlod_scheduler* s) {
  if (!s) return;
  for (uint32_t v = 0; v < s->view_count; v++)
    free_view(s->ctx, &s->views[v]);
  _tlod_free(s->ctx, s->views);
  _tlod_free(s->ctx, s);
}

tlod_scheduler_desc tlod_scheduler_query_desc(const tlod_scheduler* s) { return s->desc; }

void tlod_scheduler_reset(tlod_scheduler* s) {
  for (uint32_t v = 0; v < s->view_count; v++)
    s->views[v].has_history = false;
  s->eps_scale = 1.0f;
  s->smoothed_ms = 0.0f;
}

const tlod_draw_list* tlod_scheduler_draw_list(const tlod_scheduler* s, uint32_t view) {
  return s && view < s->view_count ? &s->views[view].list : NULL;
}

/* ---- stage tasks ------------------------------------------------------------ */

typedef struct stage_job {
  tlod_scheduler* s;
  _tlod_view_state* vs;
  const tlod_view_desc* view;
  float eps;                    /* effective epsilon of this frame */
  float level_cap;              /* budget cap (silhouette policy) */
  float step;                   /* TIME morph: level change this frame */
  const _tlod_view_state* main; /* locked views: view 0 */
} stage_job;

static void silhouette_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  stage_job* j = data;
  const tlod_mesh* m = j->s->mesh;
  for (uint32_t i = begin; i < end; i++)
    j->vs->depth[i] = _tlod_silhouette_depth(&j->vs->cam, m->positions[i], m->normals[i], j->s->desc.silhouette_depth);
}

static void metric_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  stage_job* j = data;
  const tlod_scheduler* s = j->s;
  _tlod_view_state* vs = j->vs;
  for (uint32_t f = begin; f < end; f++) {
    const tlod_patch_info* info = &s->surface->info[f];
    vs->visible[f] = s->desc.no_frustum_cull || _tlod_sphere_visible(&vs->cam, info->center, info->radius);
    vs->e_max[f] = _tlod_patch_e_max(&vs->cam, j->view->view, j->view->proj, j->view->viewport_height, info);
    const tlod_mesh* m = s->mesh;
    float d = 0.0f;
    bool front = false, back = false;
    for (uint32_t c = 0; c < m->face_corners[f]; c++) {
      uint32_t v = m->faces[f][c];
      d = vs->depth[v] > d ? vs->depth[v] : d;
      float facing = _tlod_facing(&vs->cam, m->positions[v], m->normals[v]);
      front = front || facing > 0.0f;
      back = back || facing <= 0.0f;
    }
    /* Normals facing both ways: the contour crosses the patch. */
    if (front && back) d = s->desc.silhouette_depth;
    vs->contour[f] = d / s->desc.silhouette_depth;
  }
}

/* Target level of a patch at epsilon eps: integral unless morph is
 * CONTINUOUS, and always with ceil(target) the discrete rule's level. */
static float target_level(const tlod_scheduler* s, float e_max, float contour, float eps, float cap) {
  const tlod_scheduler_desc* d = &s->desc;
  uint32_t lmax = d->max_level;
  if (d->policy == TLOD_POLICY_UNIFORM) return (float)(lmax < cap ? lmax : (uint32_t)cap);
  if (d->policy == TLOD_POLICY_SILHOUETTE) {
    float segments = contour * d->silhouette_depth;
    float t = segments > 1.0f ? log2f(segments) : 0.0f;
    t = t < cap ? t : cap;
    t = t > (float)lmax ? (float)lmax : t;
    return d->morph == TLOD_MORPH_CONTINUOUS ? t : ceilf(t);
  }
  if (d->policy == TLOD_POLICY_HYBRID) eps *= powf(d->hybrid_relax, 1.0f - contour);
  uint32_t l = tlod_level_for_error(e_max, eps, lmax);
  if (d->morph != TLOD_MORPH_CONTINUOUS || l == 0) return (float)l;
  float t = log2f(e_max / eps) * 0.5f;
  float lo = (float)(l - 1) + 1e-4f;
  return t < lo ? lo : (t > (float)l ? (float)l : t);
}

static void target_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  stage_job* j = data;
  _tlod_view_state* vs = j->vs;
  for (uint32_t f = begin; f < end; f++)
    vs->target[f] = target_level(j->s, vs->e_max[f], vs->contour[f], j->eps, j->level_cap);
}

static void morph_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  stage_job* j = data;
  _tlod_view_state* vs = j->vs;
  bool timed = j->s->desc.morph == TLOD_MORPH_TIME && vs->has_history;
  for (uint32_t f = begin; f < end; f++) {
    float t = vs->target[f], c = vs->cont[f];
    if (!timed || !vs->visible[f]) {
      c = t;
    } else if (c < t) {
      c = c + j->step < t ? c + j->step : t;
    } else if (c > t) {
      c = c - j->step > t ? c - j->step : t;
    }
    /* A budget is a hard cap: never draw above the budget's level. */
    if (j->s->desc.triangle_budget && c > ceilf(t)) c = ceilf(t);
    vs->cont[f] = c;
  }
}

/* ---- levels, budget -------------------------------------------------------- */

static uint32_t drawn_level(float cont) { return cont > 0.0f ? (uint32_t)ceilf(cont) : 0u; }

static float morph_of(float cont, uint32_t level) {
  if (level == 0) return 1.0f;
  float m = cont - (float)(level - 1);
  return m < 0.0f ? 0.0f : (m > 1.0f ? 1.0f : m);
}

/* The scheduler reads core's arrays directly (lod is a friend of core): this
 * is the per-frame hot path over every patch. */
static tlod_pattern_shape shape_of(const tlod_mesh* m, uint32_t f) {
  return m->face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

/* Triangles of a frame whose levels are ceil(level[f]) (visible patches),
 * strips included. */
static uint64_t frame_triangles(const tlod_scheduler* s, const _tlod_view_state* vs, const float* level) {
  uint64_t tris = 0;
  for (uint32_t f = 0; f < s->patch_count; f++) {
    if (!vs->visible[f]) continue;
    uint32_t lf = drawn_level(level[f]);
    tris += tlod_pattern_triangle_count(shape_of(s->mesh, f), lf);
    for (uint32_t e = 0; e < s->mesh->face_corners[f]; e++) {
      tlod_edge_link link = s->mesh->links[f][e];
      if (link.face == UINT32_MAX || link.face < f || !vs->visible[link.face]) continue;
      uint32_t lg = drawn_level(level[link.face]);
      if (!link.smooth || lf != lg || morph_of(level[f], lf) != morph_of(level[link.face], lg))
        tris += s->patterns->connect_count[lf][lg];
    }
  }
  return tris;
}

/* Raises epsilon (or lowers the silhouette cap) until the frame fits the
 * triangle budget; level 0 everywhere is the floor. */
static void fit_budget(tlod_scheduler* s, stage_job* j) {
  uint32_t budget = s->desc.triangle_budget;
  _tlod_parallel_for(s->ctx, target_task, j, s->patch_count);
  if (!budget || frame_triangles(s, j->vs, j->vs->target) <= budget) return;
  if (s->desc.policy == TLOD_POLICY_SILHOUETTE || s->desc.policy == TLOD_POLICY_UNIFORM) {
    for (float cap = (float)s->desc.max_level - 1.0f; cap >= 0.0f; cap -= 1.0f) {
      j->level_cap = cap;
      _tlod_parallel_for(s->ctx, target_task, j, s->patch_count);
      if (frame_triangles(s, j->vs, j->vs->target) <= budget) return;
    }
    return;
  }
  /* Bisection on log2 of the epsilon factor: triangles fall as it grows. */
  float base = j->eps, lo = 0.0f, hi = 1.0f;
  for (;;) {
    j->eps = base * exp2f(hi);
    _tlod_parallel_for(s->ctx, target_task, j, s->patch_count);
    if (frame_triangles(s, j->vs, j->vs->target) <= budget || hi > 60.0f) break;
    lo = hi;
    hi *= 2.0f;
  }
  for (int it = 0; it < 20; it++) {
    float mid = 0.5f * (lo + hi);
    j->eps = base * exp2f(mid);
    _tlod_parallel_for(s->ctx, target_task, j, s->patch_count);
    if (frame_triangles(s, j->vs, j->vs->target) <= budget) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  j->eps = base * exp2f(hi);
  _tlod_parallel_for(s->ctx, target_task, j, s->patch_count);
}

/* ---- draw list ------------------------------------------------------------- */

/* An edge's new vertices blend with their patch: a blend shared with an
 * equal-level neighbour (the smaller of the two) cannot stay continuous, as
 * the shared value jumps whenever either side changes level (its coarser
 * edge vertices then become exact). Equal-level neighbours whose blends
 * differ get a strip instead (Schwarz et al. 2006, sec. 5). */
static float edge_morph(const _tlod_view_state* vs, uint32_t f, uint32_t level) { return morph_of(vs->cont[f], level); }

static void fill_instances(tlod_scheduler* s, _tlod_view_state* vs) {
  uint32_t lmax = s->desc.max_level, counts[2 * (TLOD_MAX_LEVEL + 1)] = {0};
  tlod_draw_list* dl = &vs->list;
  for (uint32_t f = 0; f < s->patch_count; f++) {
    uint32_t l = drawn_level(vs->cont[f]);
    vs->levels[f] = vs->visible[f] ? (int8_t)l : -1;
    if (vs->visible[f]) counts[(uint32_t)shape_of(s->mesh, f) * (lmax + 1) + l]++;
  }
  uint32_t first = 0, nb = 0, start[2 * (TLOD_MAX_LEVEL + 1)];
  for (uint32_t b = 0; b < 2 * (lmax + 1); b++) {
    start[b] = first;
    if (counts[b]) {
      vs->buckets[nb++] = (tlod_draw_bucket){(tlod_pattern_shape)(b / (lmax + 1)), b % (lmax + 1), first, counts[b]};
    }
    first += counts[b];
  }
  for (uint32_t f = 0; f < s->patch_count; f++) {
    if (!vs->visible[f]) continue;
    uint32_t l = (uint32_t)vs->levels[f], b = (uint32_t)shape_of(s->mesh, f) * (lmax + 1) + l;
    tlod_draw_instance* in = &vs->instances[start[b]++];
    *in = (tlod_draw_instance){.patch = f, .level = l, .morph = morph_of(vs->cont[f], l)};
    uint32_t n = s->mesh->face_corners[f];
    for (uint32_t e = 0; e < 4; e++)
      in->edge_morph[e] = e < n ? edge_morph(vs, f, l) : 1.0f;
  }
  dl->instances = vs->instances;
  dl->instance_count = first;
  dl->buckets = vs->buckets;
  dl->bucket_count = nb;
}

static tlod_result push_strip(tlod_scheduler* s, _tlod_view_state* vs, const tlod_draw_strip* st) {
  if (vs->list.strip_count == vs->strip_cap) {
    uint32_t cap = vs->strip_cap ? vs->strip_cap * 2 : 256;
    tlod_draw_strip* grown = _tlod_alloc(s->ctx, sizeof(*grown) * cap);
    if (!grown) return _tlod_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
    if (vs->list.strip_count) memcpy(grown, vs->strips, sizeof(*grown) * vs->list.strip_count);
    _tlod_free(s->ctx, vs->strips);
    vs->strips = grown;
    vs->strip_cap = cap;
  }
  vs->strips[vs->list.strip_count++] = *st;
  return TLOD_SUCCESS;
}

static tlod_result fill_strips(tlod_scheduler* s, _tlod_view_state* vs) {
  tlod_draw_list* dl = &vs->list;
  dl->strip_count = 0;
  dl->strip_triangles = 0;
  for (uint32_t f = 0; f < s->patch_count; f++) {
    if (!vs->visible[f]) continue;
    for (uint32_t e = 0; e < s->mesh->face_corners[f]; e++) {
      tlod_edge_link link = s->mesh->links[f][e];
      if (link.face == UINT32_MAX || link.face < f || !vs->visible[link.face]) continue;
      uint8_t la = (uint8_t)vs->levels[f], lb = (uint8_t)vs->levels[link.face];
      if (link.smooth && la == lb && edge_morph(vs, f, la) == edge_morph(vs, link.face, lb)) continue;
      tlod_draw_strip st = {f, link.face, (uint8_t)e, link.edge, la, lb, !link.smooth};
      if (push_strip(s, vs, &st) != TLOD_SUCCESS) return TLOD_ERROR_OUT_OF_MEMORY;
      dl->strip_triangles += s->patterns->connect_count[la][lb];
    }
  }
  dl->strips = vs->strips;
  return TLOD_SUCCESS;
}

static void fill_stats(tlod_scheduler* s, _tlod_view_state* vs, float eps) {
  tlod_draw_list* dl = &vs->list;
  dl->patch_count = s->patch_count;
  dl->levels = vs->levels;
  dl->e_max = vs->e_max;
  dl->vertex_depth = vs->depth;
  dl->pattern_triangles = 0;
  dl->culled = 0;
  memset(dl->level_histogram, 0, sizeof(dl->level_histogram));
  dl->e_max_min = INFINITY;
  dl->e_max_max = 0.0f;
  for (uint32_t f = 0; f < s->patch_count; f++) {
    if (vs->levels[f] < 0) {
      dl->culled++;
      continue;
    }
    dl->level_histogram[vs->levels[f]]++;
    dl->pattern_triangles += tlod_pattern_triangle_count(shape_of(s->mesh, f), (uint32_t)vs->levels[f]);
    dl->e_max_min = vs->e_max[f] < dl->e_max_min ? vs->e_max[f] : dl->e_max_min;
    dl->e_max_max = vs->e_max[f] > dl->e_max_max ? vs->e_max[f] : dl->e_max_max;
  }
  if (dl->culled == s->patch_count) dl->e_max_min = 0.0f;
  dl->effective_epsilon = eps;
}

/* ---- frame ----------------------------------------------------------------- */

static tlod_result validate_frame(tlod_scheduler* s, const tlod_frame_desc* fr) {
  if (!fr || !fr->views || fr->view_count == 0)
    return _tlod_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': a frame needs at least one view", s->label);
  if (!(fr->dt_ms >= 0.0f) || !isfinite(fr->dt_ms))
    return _tlod_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': dt_ms %g is not a time", s->label,
                      (double)fr->dt_ms);
  for (uint32_t v = 0; v < fr->view_count; v++) {
    const tlod_view_desc* vd = &fr->views[v];
    bool finite = true;
    for (int k = 0; k < 16; k++)
      finite = finite && isfinite(vd->view[k]) && isfinite(vd->proj[k]);
    if (!finite || vd->viewport_width == 0 || vd->viewport_height == 0 || vd->proj[5] == 0.0f)
      return _tlod_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                        "scheduler '%s': view %u: matrices must be finite, proj[5] non-zero and the viewport non-empty",
                        s->label, v);
  }
  return TLOD_SUCCESS;
}

static tlod_result ensure_views(tlod_scheduler* s, uint32_t count) {
  if (count <= s->view_count) return TLOD_SUCCESS;
  _tlod_view_state* grown = _tlod_calloc(s->ctx, count, sizeof(*grown));
  if (!grown) return _tlod_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
  if (s->view_count) memcpy(grown, s->views, sizeof(*grown) * s->view_count);
  _tlod_free(s->ctx, s->views);
  s->views = grown;
  for (uint32_t v = s->view_count; v < count; v++) {
    /* A view counts only once all its arrays exist: a later update must
     * not take a half-allocated view for a ready one. */
    if (alloc_view(s, &s->views[v]) != TLOD_SUCCESS) {
      free_view(s->ctx, &s->views[v]);
      return TLOD_ERROR_OUT_OF_MEMORY;
    }
    s->view_count = v + 1;
  }
  return TLOD_SUCCESS;
}

/* Frame-time control: a smoothed measurement outside a band around the
 * target moves the epsilon factor; inside the band nothing changes, so
 * levels do not flicker. */
static void control_frame_time(tlod_scheduler* s, float measured) {
  float target = s->desc.frame_time_target_ms;
  if (!(target > 0.0f) || !(measured > 0.0f) || !isfinite(measured)) return;
  s->smoothed_ms = s->smoothed_ms > 0.0f ? 0.8f * s->smoothed_ms + 0.2f * measured : measured;
  if (s->smoothed_ms > 1.05f * target) s->eps_scale *= 1.1f;
  if (s->smoothed_ms < 0.85f * target) s->eps_scale /= 1.05f;
  s->eps_scale = s->eps_scale < 1.0f ? 1.0f : (s->eps_scale > 1e6f ? 1e6f : s->eps_scale);
}

static tlod_result plan_view(tlod_scheduler* s, uint32_t v, const tlod_frame_desc* fr) {
  _tlod_view_state* vs = &s->views[v];
  const tlod_view_desc* vd = &fr->views[v];
  bool locked = v > 0 && vd->lock_to_main;
  stage_job j = {s,
                 vs,
                 vd,
                 s->desc.epsilon_px * s->eps_scale,
                 INFINITY,
                 fr->dt_ms / s->desc.morph_ms,
                 locked ? &s->views[0] : NULL};
  double t0 = _tlod_now_ms();
  _tlod_camera_from_view(vd->view, vd->proj, &vs->cam);
  _tlod_parallel_for(s->ctx, silhouette_task, &j, s->vertex_count);
  double t1 = _tlod_now_ms();
  _tlod_parallel_for(s->ctx, metric_task, &j, s->patch_count);
  double t2 = _tlod_now_ms();
  if (locked) {
    memcpy(vs->target, j.main->target, sizeof(float) * s->patch_count);
    memcpy(vs->cont, j.main->cont, sizeof(float) * s->patch_count);
    j.eps = j.main->list.effective_epsilon;
  } else {
    fit_budget(s, &j);
  }
  double t3 = _tlod_now_ms();
  if (!locked) _tlod_parallel_for(s->ctx, morph_task, &j, s->patch_count);
  vs->has_history = true;
  double t4 = _tlod_now_ms();
  fill_instances(s, vs);
  tlod_result r = fill_strips(s, vs);
  fill_stats(s, vs, j.eps);
  double t5 = _tlod_now_ms();
  double* ms = vs->list.stage_ms;
  ms[TLOD_STAGE_SILHOUETTE] = t1 - t0, ms[TLOD_STAGE_METRIC] = t2 - t1, ms[TLOD_STAGE_LEVELS] = t3 - t2;
  ms[TLOD_STAGE_MORPH] = t4 - t3, ms[TLOD_STAGE_STRIPS] = t5 - t4;
  return r;
}

tlod_result tlod_scheduler_update(tlod_scheduler* s, const tlod_frame_desc* frame) {
  if (!s) return TLOD_ERROR_INVALID_ARGUMENT;
  tlod_result r = validate_frame(s, frame);
  if (r == TLOD_SUCCESS) r = ensure_views(s, frame->view_count);
  if (r != TLOD_SUCCESS) return r;
  control_frame_time(s, frame->measured_frame_ms);
  for (uint32_t v = 0; v < frame->view_count && r == TLOD_SUCCESS; v++)
    r = plan_view(s, v, frame);
  return r;
}
