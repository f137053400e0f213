/* tesslod::lod -- one view's frame on the fast path: the kernels'
 * constants from the camera and desc, then the vertex pass and the patch
 * pass (which also sets targets and continuous levels when nothing between
 * them needs every patch: no budget, not a locked view). */
#include <float.h>
#include <math.h>

#include "scheduler_frame.h"
#include "scheduler_math.h"

typedef struct fast_task {
  const _tlod_fast_kernels* kernels;
  _tlod_fast_frame k;
} fast_task;

static void vertex_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  const fast_task* t = data;
  t->kernels->vertices(&t->k, begin, end);
}

static void patch_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  const fast_task* t = data;
  t->kernels->patches(&t->k, begin, end);
}

/* tlod_patch_projection_scale's per-view constants (scheduler_metric.c). */
static void projection_constants(const tlod_view_desc* v, _tlod_fast_frame* k) {
  const float* P = v->proj;
  double fx = 0.5 * (double)v->viewport_width * fabs((double)P[0]);
  double fy = 0.5 * (double)v->viewport_height * fabs((double)P[5]);
  k->f = fx > fy ? fx : fy;
  k->ortho_scale = _tlod_float_up(k->f);
  k->tx = (1.0 + fabs((double)P[8])) / fabs((double)P[0]);
  k->ty = (1.0 + fabs((double)P[9])) / fabs((double)P[5]);
  float denom = P[10] - 1.0f, n = denom != 0.0f ? P[14] / denom : 0.0f;
  k->znear = n > 0.0f ? n : 0.0; /* near_distance(P, false) */
  for (int i = 0; i < 16; i++)
    k->V[i] = v->view[i];
}

static void camera_constants(const _tlod_camera* cam, _tlod_fast_frame* k) {
  memcpy(k->eye, cam->eye, sizeof(k->eye));
  memcpy(k->forward, cam->forward, sizeof(k->forward));
  memcpy(k->planes, cam->planes, sizeof(k->planes));
  k->ortho = cam->ortho;
}

static void rule_constants(const _tlod_frame* fr, _tlod_fast_frame* k) {
  const tlod_scheduler_desc* d = &fr->s->desc;
  k->m = d->silhouette_depth;
  k->eps = fr->eps;
  k->log2_relax = log2f(d->hybrid_relax);
  k->policy = d->policy;
  k->max_level = d->max_level;
  k->cull = !d->no_frustum_cull;
  k->fractional = d->morph == TLOD_MORPH_CONTINUOUS;
  k->timed = d->morph == TLOD_MORPH_TIME && fr->vs->has_history;
  k->bounded = d->policy == TLOD_POLICY_ERROR || d->policy == TLOD_POLICY_HYBRID;
  k->step = fr->step;
  k->cull_skip = fr->cull_skip && k->cull;
}

static void view_arrays(const tlod_scheduler* s, _tlod_view_state* vs, _tlod_fast_frame* k) {
  k->depth = vs->depth, k->scale = vs->scale, k->e_max = vs->e_max;
  k->contour = vs->contour, k->target = vs->target, k->cont = vs->cont;
  k->visible = vs->visible;
  size_t row = (size_t)(vs - s->views) * s->soa.block_count;
  k->held = s->soa.held + row, k->seen = s->soa.seen + row;
  k->levels = vs->levels;
}

void _tlod_fast_begin(_tlod_frame* fr, bool may_fuse) {
  tlod_scheduler* s = fr->s;
  fast_task t = {.kernels = &s->fast};
  t.k.soa = &s->soa;
  projection_constants(fr->view, &t.k);
  camera_constants(&fr->vs->cam, &t.k);
  rule_constants(fr, &t.k);
  view_arrays(s, fr->vs, &t.k);
  fr->fused = t.k.fuse = may_fuse && !fr->main && !fr->budget;
  _tlod_blocks_classify(&s->soa, &s->fast, t.k.planes, t.k.cull);
  tlod_context_parallel_for(s->ctx, vertex_task, &t, s->soa.chunk_count);
  fr->t[1] = tlod_now_ms();
  tlod_context_parallel_for(s->ctx, patch_task, &t, s->soa.block_count);
}
