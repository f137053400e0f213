/* tesslod::lod -- the scheduler's entry points: create, update, destroy.
 * An update runs the stages of scheduler_frame.h in order for every view:
 * silhouette depth, metric, levels (budget), geomorph state, draw list.
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

#include "scheduler_frame.h"

/* ---- create / destroy ------------------------------------------------------- */

/* Every default of the desc in one place (lod.h documents each). */
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

static bool positive_finite(float x) { return x > 0.0f && isfinite(x); }

static tlod_result validate_desc(tlod_context* ctx, const tlod_scheduler_desc* d, const tlod_patterns* p) {
  const char* what = NULL;
  if (!positive_finite(d->epsilon_px)) what = "epsilon_px must be positive and finite";
  if (d->max_level > tlod_patterns_max_level(p)) what = "max_level is above the patterns' max level";
  if ((unsigned)d->policy >= TLOD_POLICY_NUM) what = "unknown policy";
  if ((unsigned)d->morph >= TLOD_MORPH_NUM) what = "unknown morph mode";
  if (!positive_finite(d->silhouette_depth)) what = "silhouette_depth must be positive";
  if (!(d->hybrid_relax >= 1.0f) || !isfinite(d->hybrid_relax)) what = "hybrid_relax must be >= 1";
  if (!positive_finite(d->morph_ms)) what = "morph_ms must be positive";
  if (!(d->frame_time_target_ms >= 0.0f) || !isfinite(d->frame_time_target_ms))
    what = "frame_time_target_ms must be >= 0";
  return what ? tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': %s", d->label, what)
              : TLOD_SUCCESS;
}

static tlod_result out_of_memory(const tlod_scheduler* s) {
  return tlod_context_fail(s->ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", s->label);
}

static void free_view(tlod_context* ctx, _tlod_view_state* v) {
  void* arrays[] = {v->levels, v->e_max,   v->scale,     v->depth,  v->contour, v->target,
                    v->cont,   v->visible, v->instances, v->strips, v->chunks,  v->strip_edges};
  for (size_t i = 0; i < sizeof(arrays) / sizeof(arrays[0]); i++)
    tlod_context_free(ctx, arrays[i]);
  memset(v, 0, sizeof(*v));
}

/* One spare entry each, so that a mesh of no faces still gets arrays. */
static tlod_result alloc_view(tlod_scheduler* s, _tlod_view_state* v) {
  tlod_context* ctx = s->ctx;
  size_t np = (size_t)s->patch_count + 1, nv = (size_t)s->vertex_count + 1;
  v->levels = tlod_context_calloc(ctx, np, 1);
  v->e_max = tlod_context_calloc(ctx, np, sizeof(float));
  v->scale = tlod_context_calloc(ctx, np, sizeof(float));
  v->depth = tlod_context_calloc(ctx, nv, sizeof(float));
  v->contour = tlod_context_calloc(ctx, np, sizeof(float));
  v->target = tlod_context_calloc(ctx, np, sizeof(float));
  v->cont = tlod_context_calloc(ctx, np, sizeof(float));
  v->visible = tlod_context_calloc(ctx, np + 3, 1); /* + 3: _tlod_list_in */
  v->instances = tlod_context_calloc(ctx, np, sizeof(tlod_draw_instance));
  bool ok =
      v->levels && v->e_max && v->scale && v->depth && v->contour && v->target && v->cont && v->visible && v->instances;
  return ok && _tlod_list_alloc(s, v) == TLOD_SUCCESS ? TLOD_SUCCESS : out_of_memory(s);
}

tlod_result tlod_scheduler_create(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                  const tlod_scheduler_desc* desc, tlod_scheduler** out) {
  if (out) *out = NULL;
  if (!ctx) return TLOD_ERROR_INVALID_ARGUMENT;
  if (!out || !surface || !patterns)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_scheduler_create: NULL argument");
  tlod_scheduler_desc d = scheduler_desc_defaults(desc, patterns);
  tlod_result r = validate_desc(ctx, &d, patterns);
  if (r != TLOD_SUCCESS) return r;
  if ((d.policy == TLOD_POLICY_ERROR || d.policy == TLOD_POLICY_HYBRID) &&
      tlod_surface_query_desc(surface).error_tables == TLOD_ERROR_TABLES_NONE)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "scheduler '%s': the ERROR and HYBRID policies need error bounds, but surface '%s' was "
                             "made with TLOD_ERROR_TABLES_NONE (use CLOSED_FORM, or the UNIFORM policy)",
                             d.label, tlod_surface_query_desc(surface).label);
  tlod_scheduler* s = tlod_context_calloc(ctx, 1, sizeof(*s));
  if (!s) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "scheduler '%s': out of memory", d.label);
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
  s->fast_path = !d.reference_path;
  s->fast = _tlod_fast_kernels_for(tlod_context_simd(ctx));
  s->list = _tlod_list_kernels_for(d.reference_path ? TLOD_SIMD_SCALAR : tlod_context_simd(ctx));
  r = _tlod_up_edges_build(s);
  if (r == TLOD_ERROR_OUT_OF_MEMORY) out_of_memory(s);
  if (r != TLOD_SUCCESS) {
    tlod_scheduler_destroy(s);
    return r;
  }
  *out = s;
  return TLOD_SUCCESS;
}

void tlod_scheduler_destroy(tlod_scheduler* s) {
  if (!s) return;
  for (uint32_t v = 0; v < s->view_count; v++)
    free_view(s->ctx, &s->views[v]);
  tlod_context_free(s->ctx, s->views);
  _tlod_soa_free(s->ctx, &s->soa);
  _tlod_up_edges_free(s->ctx, &s->up);
  tlod_context_free(s->ctx, s);
}

tlod_scheduler_desc tlod_scheduler_query_desc(const tlod_scheduler* s) {
  return s ? s->desc : (tlod_scheduler_desc){0};
}

void tlod_scheduler_reset(tlod_scheduler* s) {
  if (!s) return;
  for (uint32_t v = 0; v < s->view_count; v++)
    s->views[v].has_history = s->views[v].key_valid = false;
  s->eps_scale = 1.0f;
  s->smoothed_ms = 0.0f;
}

const tlod_draw_list* tlod_scheduler_draw_list(const tlod_scheduler* s, uint32_t view) {
  return s && view < s->view_count ? &s->views[view].list : NULL;
}

/* ---- update --------------------------------------------------------------------- */

static bool view_valid(const tlod_view_desc* vd) {
  bool finite = true;
  for (int k = 0; k < 16; k++)
    finite = finite && isfinite(vd->view[k]) && isfinite(vd->proj[k]);
  return finite && vd->viewport_width != 0 && vd->viewport_height != 0 && vd->proj[5] != 0.0f;
}

static tlod_result validate_frame(tlod_scheduler* s, const tlod_frame_desc* fr) {
  if (!fr || !fr->views || fr->view_count == 0)
    return tlod_context_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': a frame needs at least one view",
                             s->label);
  if (!(fr->dt_ms >= 0.0f) || !isfinite(fr->dt_ms))
    return tlod_context_fail(s->ctx, TLOD_ERROR_INVALID_ARGUMENT, "scheduler '%s': dt_ms %g is not a time", s->label,
                             (double)fr->dt_ms);
  for (uint32_t v = 0; v < fr->view_count; v++) {
    if (!view_valid(&fr->views[v]))
      return tlod_context_fail(
          s->ctx, TLOD_ERROR_INVALID_ARGUMENT,
          "scheduler '%s': view %u: matrices must be finite, proj[5] non-zero and the viewport non-empty", s->label, v);
  }
  return TLOD_SUCCESS;
}

static tlod_result ensure_views(tlod_scheduler* s, uint32_t count) {
  if (count <= s->view_count) return TLOD_SUCCESS;
  _tlod_view_state* grown = tlod_context_calloc(s->ctx, count, sizeof(*grown));
  if (!grown) return out_of_memory(s);
  if (s->view_count) memcpy(grown, s->views, sizeof(*grown) * s->view_count);
  tlod_context_free(s->ctx, s->views);
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

/* Levels of a view locked to view 0: its targets, continuous levels and
 * epsilon, so that both draw the same silhouettes. */
static void copy_main_levels(_tlod_frame* fr) {
  size_t bytes = sizeof(float) * fr->s->patch_count;
  memcpy(fr->vs->target, fr->main->target, bytes);
  memcpy(fr->vs->cont, fr->main->cont, bytes);
  fr->eps = fr->main->list.effective_epsilon;
}

static bool has_locked_view(const tlod_frame_desc* frame) {
  for (uint32_t v = 1; v < frame->view_count; v++)
    if (frame->views[v].lock_to_main) return true;
  return false;
}

/* Silhouette depth and metric of view v: the stages before the levels
 * (on the fast path outside a group, the levels and morph too). */
static void begin_view(tlod_scheduler* s, uint32_t v, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                       const tlod_surface_view* surface, bool group, _tlod_frame* fr) {
  const tlod_view_desc* vd = &frame->views[v];
  bool locked = v > 0 && vd->lock_to_main;
  *fr = (_tlod_frame){.s = s,
                      .vs = &s->views[v],
                      .view = vd,
                      .mesh = *mesh,
                      .surface = *surface,
                      .eps = s->desc.epsilon_px * s->eps_scale,
                      .level_cap = INFINITY,
                      .step = frame->dt_ms / s->desc.morph_ms,
                      .main = locked ? &s->views[0] : NULL,
                      .budget = s->desc.triangle_budget,
                      .cull_skip = !has_locked_view(frame)};
  fr->t[0] = tlod_now_ms();
  _tlod_camera_from_view(vd->view, vd->proj, &fr->vs->cam);
  if (s->fast_path) {
    _tlod_fast_begin(fr, !group);
  } else {
    tlod_context_parallel_for(s->ctx, _tlod_silhouette_task, fr, s->vertex_count);
    fr->t[1] = tlod_now_ms();
    tlod_context_parallel_for(s->ctx, _tlod_metric_task, fr, s->patch_count);
  }
  fr->t[2] = tlod_now_ms();
}

/* Geomorph state and draw list, once the levels (ending at t[3]) are set. */
static tlod_result finish_view(_tlod_frame* fr) {
  double start = tlod_now_ms();
  if (!fr->main && !fr->fused) tlod_context_parallel_for(fr->s->ctx, _tlod_morph_task, fr, fr->s->patch_count);
  fr->vs->has_history = true;
  fr->t[4] = tlod_now_ms();
  tlod_result r = _tlod_fill_draw_list(fr);
  fr->t[5] = tlod_now_ms();
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    fr->vs->list.stage_ms[st] = fr->t[st + 1] - fr->t[st];
  /* A group member waits for the others between its levels and morph. */
  fr->vs->list.stage_ms[TLOD_STAGE_MORPH] = fr->t[4] - start;
  return r;
}

static tlod_result plan_view(tlod_scheduler* s, uint32_t v, const tlod_frame_desc* frame, const tlod_mesh_view* mesh,
                             const tlod_surface_view* surface) {
  _tlod_frame fr;
  begin_view(s, v, frame, mesh, surface, false, &fr);
  if (fr.main) {
    copy_main_levels(&fr);
  } else if (!fr.fused) {
    _tlod_fit_budget(&fr);
  }
  fr.t[3] = tlod_now_ms();
  return finish_view(&fr);
}

/* Checks, views and frame-time control of one update. */
static tlod_result prepare_update(tlod_scheduler* s, const tlod_frame_desc* frame) {
  tlod_result r = validate_frame(s, frame);
  if (r == TLOD_SUCCESS) r = ensure_views(s, frame->view_count);
  if (r == TLOD_SUCCESS) _tlod_control_frame_time(s, frame->measured_frame_ms);
  return r;
}

/* Temporal coherence: nothing changed, the draw lists and their
 * generations stay (no stage ran: every stage_ms is 0). */
static tlod_result keep_views(tlod_scheduler* s, const tlod_frame_desc* frame) {
  for (uint32_t v = 0; v < frame->view_count; v++)
    memset(s->views[v].list.stage_ms, 0, sizeof(s->views[v].list.stage_ms));
  return TLOD_SUCCESS;
}

tlod_result tlod_scheduler_update(tlod_scheduler* s, const tlod_frame_desc* frame) {
  if (!s) return TLOD_ERROR_INVALID_ARGUMENT;
  tlod_result r = prepare_update(s, frame);
  if (r != TLOD_SUCCESS) return r;
  /* Read afresh every update: a tlod_mesh_update() or tlod_surface_refresh()
   * since the last frame may have moved the arrays. */
  tlod_mesh_view mesh = tlod_mesh_query_view(s->mesh);
  tlod_surface_view surface = tlod_surface_query_view(s->surface);
  if (_tlod_lists_unchanged(s, frame, &mesh, &surface)) return keep_views(s, frame);
  if (s->fast_path) r = _tlod_soa_update(s, &mesh, &surface);
  for (uint32_t v = 0; v < frame->view_count && r == TLOD_SUCCESS; v++)
    r = plan_view(s, v, frame, &mesh, &surface);
  if (r == TLOD_SUCCESS) _tlod_lists_remember(s, frame, &mesh, &surface);
  return r;
}

/* ---- group update ----------------------------------------------------------- */

/* The first context named by the group, for its error messages. */
static tlod_context* group_context(tlod_scheduler* const* schedulers, uint32_t count) {
  for (uint32_t i = 0; schedulers && i < count; i++)
    if (schedulers[i]) return schedulers[i]->ctx;
  return NULL;
}

/* Marks member i with slot i + 1; a member already marked is given twice.
 * Returns the count marked (all of them, or up to the duplicate). */
static uint32_t mark_members(tlod_scheduler* const* schedulers, uint32_t count, uint32_t* first, uint32_t* second) {
  for (uint32_t i = 0; i < count; i++) {
    if (schedulers[i]->group_slot) {
      *first = schedulers[i]->group_slot - 1, *second = i;
      return i;
    }
    schedulers[i]->group_slot = i + 1;
  }
  return count;
}

static tlod_result validate_group(tlod_scheduler* const* schedulers, const tlod_frame_desc* frames, uint32_t count) {
  tlod_context* ctx = group_context(schedulers, count);
  if (!ctx) return count ? TLOD_ERROR_INVALID_ARGUMENT : TLOD_SUCCESS;
  if (!frames) return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_scheduler_update_group: NULL frames");
  for (uint32_t i = 0; i < count; i++)
    if (!schedulers[i])
      return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "tlod_scheduler_update_group: scheduler %u is NULL",
                               i);
  uint32_t first = 0, second = 0, marked = mark_members(schedulers, count, &first, &second);
  for (uint32_t i = 0; i < marked; i++)
    schedulers[i]->group_slot = 0;
  if (marked < count)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "tlod_scheduler_update_group: scheduler '%s' is given twice (%u and %u)",
                             schedulers[second]->label, first, second);
  return TLOD_SUCCESS;
}

/* Views after the first of every member, each on its own (locked ones
 * copy the group's view 0). */
static tlod_result plan_other_views(tlod_scheduler* s, const tlod_frame_desc* frame) {
  tlod_result r = TLOD_SUCCESS;
  for (uint32_t v = 1; v < frame->view_count && r == TLOD_SUCCESS; v++)
    r = plan_view(s, v, frame, &s->group.mesh, &s->group.surface);
  return r;
}

/* The joint search, its time shared out over the members' levels stage
 * (their sum is the search's time). */
static void fit_group(tlod_scheduler* const* schedulers, uint32_t count, uint32_t budget) {
  double t0 = tlod_now_ms();
  _tlod_fit_group(schedulers, count, budget);
  double share = (tlod_now_ms() - t0) / count;
  for (uint32_t i = 0; i < count; i++)
    schedulers[i]->group.t[3] = schedulers[i]->group.t[2] + share;
}

/* Every member's view 0 through silhouette and metric, then the joint
 * levels, then each member's morph, draw list and other views. */
static tlod_result update_group(tlod_scheduler* const* schedulers, const tlod_frame_desc* frames, uint32_t count,
                                uint32_t budget) {
  for (uint32_t i = 0; i < count; i++) {
    tlod_scheduler* s = schedulers[i];
    tlod_result r = prepare_update(s, &frames[i]);
    if (r != TLOD_SUCCESS) return r;
    tlod_mesh_view mesh = tlod_mesh_query_view(s->mesh);
    tlod_surface_view surface = tlod_surface_query_view(s->surface);
    if (s->fast_path && (r = _tlod_soa_update(s, &mesh, &surface)) != TLOD_SUCCESS) return r;
    begin_view(s, 0, &frames[i], &mesh, &surface, true, &s->group);
  }
  fit_group(schedulers, count, budget);
  for (uint32_t i = 0; i < count; i++) {
    tlod_result r = finish_view(&schedulers[i]->group);
    if (r == TLOD_SUCCESS) r = plan_other_views(schedulers[i], &frames[i]);
    if (r != TLOD_SUCCESS) return r;
  }
  return TLOD_SUCCESS;
}

tlod_result tlod_scheduler_update_group(tlod_scheduler* const* schedulers, const tlod_frame_desc* frames,
                                        uint32_t count, uint32_t triangle_budget) {
  tlod_result r = validate_group(schedulers, frames, count);
  if (r != TLOD_SUCCESS) return r;
  if (triangle_budget) return update_group(schedulers, frames, count, triangle_budget);
  for (uint32_t i = 0; i < count && r == TLOD_SUCCESS; i++)
    r = tlod_scheduler_update(schedulers[i], &frames[i]);
  return r;
}
