/* tesslod::lod -- the per-frame metrics: silhouette depth per vertex,
 * projection scale (nearest depth and off-axis factor), frustum test and
 * contour measure per patch, and the level rule that turns the patch's
 * per-level error table (tesslod/core.h) into levels.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. 2008 (silhouette depth
 *   d_i = (1 - |n_i . (c - p_i)/|c - p_i||) m);
 *   M. Schwarz, M. Staginski, M. Stamminger. 2006 (projected error bound,
 *   the smallest level that meets eps; here with the per-level tables of
 *   issue #9 instead of 4^-l e_max, docs/design.md 3.6). */
#include <float.h>
#include <math.h>

#include "scheduler_frame.h"
#include "scheduler_math.h"

/* ---- camera ----------------------------------------------------------------- */

static bool is_ortho(const float proj[16]) { return proj[15] == 1.0f && proj[11] == 0.0f; }

float tlod_projection_scale(const float proj[16], uint32_t viewport_height, float depth) {
  float half = 0.5f * (float)viewport_height * fabsf(proj[5]);
  if (is_ortho(proj)) return half;
  return depth > 0.0f ? half / depth : INFINITY;
}

/* The smallest float >= x (x >= 0, finite). */
static float float_up(double x) {
  float f = (float)x;
  return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Near distance of a GL projection (a [0, 1]-depth one gives about half of
 * it: only more conservative); 0 when unknown or orthographic. */
static float near_distance(const float proj[16], bool ortho) {
  float denom = proj[10] - 1.0f;
  float n = denom != 0.0f ? proj[14] / denom : 0.0f;
  return ortho || !(n > 0.0f) ? 0.0f : n;
}

/* docs/design.md 3.6: f = max(W |P00|, H |P11|) / 2; at view point (x, y, z)
 * a displacement d projects to at most (f / z) sqrt(1 + (x/z)^2 + (y/z)^2) |d|
 * pixels; over the sphere z >= z_c - r (at least the near plane) and
 * |x/z| <= (|x_c| + r) / z_min, at most the frustum's (1 + |P20|) / |P00|
 * (y likewise). Computed in double (one division: 1 / z), rounded up. */
float tlod_patch_projection_scale(const tlod_view_desc* v, const float center[3], float radius) {
  const float *V = v->view, *P = v->proj;
  double fx = 0.5 * (double)v->viewport_width * fabs((double)P[0]);
  double fy = 0.5 * (double)v->viewport_height * fabs((double)P[5]);
  double f = fx > fy ? fx : fy;
  if (is_ortho(P)) return float_up(f);
  double c[3] = {center[0], center[1], center[2]}, r = radius > 0.0f ? radius : 0.0;
  double x = V[0] * c[0] + V[4] * c[1] + V[8] * c[2] + V[12];
  double y = V[1] * c[0] + V[5] * c[1] + V[9] * c[2] + V[13];
  double z = -(V[2] * c[0] + V[6] * c[1] + V[10] * c[2] + V[14]) - r;
  double zmin = near_distance(P, false);
  if (!(zmin > 0.0)) zmin = r > 0.0 ? 1e-4 * r : 1e-30;
  if (!(z >= zmin)) z = zmin;
  double tx = (1.0 + fabs((double)P[8])) / fabs((double)P[0]), ty = (1.0 + fabs((double)P[9])) / fabs((double)P[5]);
  double iz = 1.0 / z, rx = (fabs(x) + r) * iz, ry = (fabs(y) + r) * iz;
  rx = rx < tx ? rx : tx;
  ry = ry < ty ? ry : ty;
  double s = f * iz * sqrt(1.0 + rx * rx + ry * ry);
  return isfinite(s) && s < (double)FLT_MAX ? float_up(s) : INFINITY;
}

/* Rigid view: eye = -R^T t, forward = -(third row of R). */
static void eye_and_forward(const float view[16], _tlod_camera* cam) {
  const float* t = view + 12;
  for (int i = 0; i < 3; i++) {
    cam->eye[i] = -(view[i * 4 + 0] * t[0] + view[i * 4 + 1] * t[1] + view[i * 4 + 2] * t[2]);
    cam->forward[i] = -view[i * 4 + 2];
  }
}

/* Frustum planes from the rows of clip = P V (Gribb & Hartmann). */
static void frustum_planes(const float view[16], const float proj[16], float planes[6][4]) {
  float m[16];
  for (int c = 0; c < 4; c++) {
    for (int r = 0; r < 4; r++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++)
        s += proj[k * 4 + r] * view[c * 4 + k];
      m[c * 4 + r] = s;
    }
  }
  for (int p = 0; p < 6; p++) {
    int row = p / 2;
    float sign = (p % 2) ? -1.0f : 1.0f;
    float len = 0.0f;
    for (int k = 0; k < 4; k++) {
      planes[p][k] = m[k * 4 + 3] + sign * m[k * 4 + row];
      if (k < 3) len += planes[p][k] * planes[p][k];
    }
    len = sqrtf(len);
    for (int k = 0; k < 4 && len > 0.0f; k++)
      planes[p][k] /= len;
  }
}

void _tlod_camera_from_view(const float view[16], const float proj[16], _tlod_camera* cam) {
  eye_and_forward(view, cam);
  cam->ortho = is_ortho(proj);
  cam->near_z = near_distance(proj, cam->ortho);
  frustum_planes(view, proj, cam->planes);
}

/* ---- per vertex and per patch measures -------------------------------------------- */

static bool sphere_visible(const _tlod_camera* cam, const float c[3], float r) {
  for (int p = 0; p < 6; p++) {
    const float* pl = cam->planes[p];
    if (pl[0] * c[0] + pl[1] * c[1] + pl[2] * c[2] + pl[3] < -r) return false;
  }
  return true;
}

/* n . (eye - p) (orthographic: n . -forward): > 0 where the normal faces the camera. */
static float facing(const _tlod_camera* cam, const float p[3], const float n[3]) {
  if (cam->ortho) return -(n[0] * cam->forward[0] + n[1] * cam->forward[1] + n[2] * cam->forward[2]);
  return n[0] * (cam->eye[0] - p[0]) + n[1] * (cam->eye[1] - p[1]) + n[2] * (cam->eye[2] - p[2]);
}

static float silhouette_depth(const _tlod_camera* cam, const float p[3], const float n[3], float m) {
  float d[3];
  if (cam->ortho) {
    d[0] = -cam->forward[0], d[1] = -cam->forward[1], d[2] = -cam->forward[2];
  } else {
    d[0] = cam->eye[0] - p[0], d[1] = cam->eye[1] - p[1], d[2] = cam->eye[2] - p[2];
  }
  float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0.0f)) return m;
  float c = fabsf(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / len;
  return (1.0f - (c > 1.0f ? 1.0f : c)) * m;
}

/* s = max d_i / m over the corners, 1 where the corner normals face both
 * ways: the contour then crosses the patch whatever the d_i say. */
static float patch_contour(const _tlod_frame* fr, uint32_t f) {
  const tlod_mesh_view* m = &fr->mesh;
  float d = 0.0f;
  bool front = false, back = false;
  for (uint32_t c = 0; c < m->face_corners[f]; c++) {
    uint32_t v = m->faces[f][c];
    d = fr->vs->depth[v] > d ? fr->vs->depth[v] : d;
    float toward = facing(&fr->vs->cam, m->positions[v], m->normals[v]);
    front = front || toward > 0.0f;
    back = back || toward <= 0.0f;
  }
  if (front && back) d = fr->s->desc.silhouette_depth;
  return d / fr->s->desc.silhouette_depth;
}

void _tlod_silhouette_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  float m = fr->s->desc.silhouette_depth;
  for (uint32_t i = begin; i < end; i++)
    fr->vs->depth[i] = silhouette_depth(&fr->vs->cam, fr->mesh.positions[i], fr->mesh.normals[i], m);
}

void _tlod_metric_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  _tlod_frame* fr = data;
  _tlod_view_state* vs = fr->vs;
  for (uint32_t f = begin; f < end; f++) {
    const tlod_patch_info* info = &fr->surface.patches[f];
    vs->visible[f] = fr->s->desc.no_frustum_cull || sphere_visible(&vs->cam, info->center, info->radius);
    /* Every point of the patch lies in its sphere, and so does every
     * pattern point (a convex combination of surface points). */
    vs->scale[f] = tlod_patch_projection_scale(fr->view, info->center, info->radius);
    vs->e_max[f] = tlod_patch_error_bound(info, 0) * vs->scale[f];
    if (fr->cull_skip && !vs->visible[f]) vs->e_max[f] = 0.0f; /* culled (docs/design.md 3.13) */
    vs->contour[f] = patch_contour(fr, f);
  }
}

/* ---- the level rule ------------------------------------------------------------ */

/* Bound of level l in pixels, double (exact product of two floats). */
static double px_bound(const tlod_patch_info* info, float scale, uint32_t l) {
  return (double)tlod_patch_error_bound(info, l) * (double)scale;
}

/* The compare ladder: the smallest l <= max_level whose bound, projected,
 * is <= eps (the table is non-increasing in l). Exact at the thresholds. */
static uint32_t error_level(const tlod_patch_info* info, float scale, float eps, uint32_t max_level) {
  uint32_t l = 0;
  while (l < max_level && !(px_bound(info, scale, l) <= (double)eps))
    l++;
  return l;
}

/* ERROR and HYBRID: the discrete level l, and below it the fractional level
 * (l - 1) + a with the smallest blend a whose morphed mesh is within eps:
 * (1 - a) b_{l-1} + a b_l = eps, b the projected bounds (docs/design.md 3.9),
 * in [1e-4, 1], rounded up. Its ceil is l; a patch clamped at max_level
 * (b_l > eps) gets l. */
static float error_target(const tlod_scheduler_desc* d, const tlod_patch_info* info, float scale, float eps) {
  uint32_t l = error_level(info, scale, eps, d->max_level);
  if (l == 0) return 0.0f;
  double hi = px_bound(info, scale, l - 1), lo = px_bound(info, scale, l);
  if (!(lo <= (double)eps)) return (float)l;
  double a = (hi - (double)eps) / (hi - lo); /* hi > eps >= lo */
  a = a > 1e-4 ? (a < 1.0 ? a : 1.0) : 1e-4;
  return float_up((double)(l - 1) + a);
}

/* SILHOUETTE: log2 of the segments the contour asks for, at most the cap
 * and max_level; integral (the compare ladder 2^k >= segments) unless
 * morphs are CONTINUOUS (scheduler_math.h's log2). The cap is integral. */
static float silhouette_target(const tlod_scheduler_desc* d, float contour, float cap) {
  float segments = contour * d->silhouette_depth;
  float t;
  if (d->morph == TLOD_MORPH_CONTINUOUS) {
    t = segments > 1.0f ? _tlod_log2(segments) : 0.0f;
  } else {
    t = _tlod_ceil_log2(segments);
  }
  t = t < cap ? t : cap;
  return t > (float)d->max_level ? (float)d->max_level : t;
}

float _tlod_level_rule(const tlod_scheduler_desc* d, const tlod_patch_info* info, float scale, float contour, float eps,
                       float cap) {
  switch (d->policy) {
  case TLOD_POLICY_FLAT:
    return 0.0f;
  case TLOD_POLICY_UNIFORM:
    return (float)((float)d->max_level < cap ? d->max_level : (uint32_t)cap);
  case TLOD_POLICY_SILHOUETTE:
    return silhouette_target(d, contour, cap);
  case TLOD_POLICY_HYBRID:
    /* Away from contours (s < 1) shading hides the flat geometry. */
    /* relax^(1-s) as 2^((1-s) log2 relax): one log per frame in the fast path. */
    return error_target(d, info, scale, eps * _tlod_exp2((1.0f - contour) * log2f(d->hybrid_relax)));
  default:
    return error_target(d, info, scale, eps);
  }
}

/* The old rule through the one ladder: a table e_max 4^-l (exact: powers
 * of two), no slack, scale 1. */
uint32_t tlod_level_for_error(float e_max, float epsilon, uint32_t max_level) {
  tlod_patch_info info = {.corner_count = 3, .error_bound = e_max, .error_tail = e_max};
  for (uint32_t l = 0; l < TLOD_ERROR_TABLE_LEVELS; l++)
    info.error_table[l] = ldexpf(e_max, -2 * (int)l);
  tlod_scheduler_desc d = {.policy = TLOD_POLICY_ERROR, .max_level = max_level, .morph = TLOD_MORPH_NONE};
  return _tlod_drawn_level(_tlod_level_rule(&d, &info, 1.0f, 0.0f, epsilon, INFINITY));
}
