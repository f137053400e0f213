/* tesslod::lod -- the per-frame metrics: silhouette depth per vertex,
 * projected error bound, frustum test and contour measure per patch, and
 * the level rule that turns them into levels.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. 2008 (silhouette depth
 *   d_i = (1 - |n_i . (c - p_i)/|c - p_i||) m);
 *   M. Schwarz, M. Staginski, M. Stamminger. 2006 (e_max = projected
 *   d'_max bound; l smallest with 4^-l e_max <= eps). */
#include <math.h>

#include "scheduler_frame.h"

/* ---- camera ----------------------------------------------------------------- */

static bool is_ortho(const float proj[16]) { return proj[15] == 1.0f && proj[11] == 0.0f; }

float tlod_projection_scale(const float proj[16], uint32_t viewport_height, float depth) {
  float half = 0.5f * (float)viewport_height * fabsf(proj[5]);
  if (is_ortho(proj)) return half;
  return depth > 0.0f ? half / depth : INFINITY;
}

/* Rigid view: eye = -R^T t, forward = -(third row of R). */
static void eye_and_forward(const float view[16], _tlod_camera* cam) {
  const float* t = view + 12;
  for (int i = 0; i < 3; i++) {
    cam->eye[i] = -(view[i * 4 + 0] * t[0] + view[i * 4 + 1] * t[1] + view[i * 4 + 2] * t[2]);
    cam->forward[i] = -view[i * 4 + 2];
  }
}

/* Near distance of a GL projection (a [0, 1]-depth one gives about half of
 * it: only more conservative); 0 when unknown or orthographic. */
static float near_distance(const float proj[16], bool ortho) {
  float denom = proj[10] - 1.0f;
  float n = denom != 0.0f ? proj[14] / denom : 0.0f;
  return ortho || !(n > 0.0f) ? 0.0f : n;
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

static float view_depth(const float view[16], const float p[3]) {
  return -(view[2] * p[0] + view[6] * p[1] + view[10] * p[2] + view[14]);
}

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

/* Projected error bound of a patch at level 0, pixels, at the nearest depth
 * of its bounding sphere: the bound must hold for every point of the patch. */
static float patch_e_max(const _tlod_camera* cam, const tlod_view_desc* vd, const tlod_patch_info* info) {
  if (cam->ortho) return info->error_bound * tlod_projection_scale(vd->proj, vd->viewport_height, 1.0f);
  float z = view_depth(vd->view, info->center) - info->radius;
  /* Inside the sphere or past the near plane: the nearest visible depth. */
  float zmin = cam->near_z > 0.0f ? cam->near_z : 1e-4f * info->radius;
  if (z < zmin) z = zmin;
  return info->error_bound * tlod_projection_scale(vd->proj, vd->viewport_height, z);
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
    vs->e_max[f] = patch_e_max(&vs->cam, fr->view, info);
    vs->contour[f] = patch_contour(fr, f);
  }
}

/* ---- the level rule ------------------------------------------------------------ */

/* Smallest l <= max_level with 4^-l e_max <= eps. Multiplies up rather than
 * taking a log, so the rule is exact at the thresholds:
 * 4^-l e <= eps <=> e <= eps * 4^l. */
static uint32_t error_level(float e_max, float eps, uint32_t max_level) {
  uint32_t l = 0;
  double bound = eps;
  while (l < max_level && !((double)e_max <= bound)) {
    bound *= 4.0;
    l++;
  }
  return l;
}

/* ERROR and HYBRID: the discrete level, or for CONTINUOUS morphs log4(e_max
 * / eps) kept in (l - 1, l], so that its ceil is the discrete level. */
static float error_target(const tlod_scheduler_desc* d, float e_max, float eps) {
  uint32_t l = error_level(e_max, eps, d->max_level);
  if (d->morph != TLOD_MORPH_CONTINUOUS || l == 0) return (float)l;
  float t = log2f(e_max / eps) * 0.5f;
  float lo = (float)(l - 1) + 1e-4f;
  return t < lo ? lo : (t > (float)l ? (float)l : t);
}

/* SILHOUETTE: log2 of the segments the contour asks for, at most the cap
 * and max_level; integral unless morphs are CONTINUOUS. */
static float silhouette_target(const tlod_scheduler_desc* d, float contour, float cap) {
  float segments = contour * d->silhouette_depth;
  float t = segments > 1.0f ? log2f(segments) : 0.0f;
  t = t < cap ? t : cap;
  t = t > (float)d->max_level ? (float)d->max_level : t;
  return d->morph == TLOD_MORPH_CONTINUOUS ? t : ceilf(t);
}

float _tlod_level_rule(const tlod_scheduler_desc* d, float e_max, float contour, float eps, float cap) {
  switch (d->policy) {
  case TLOD_POLICY_FLAT:
    return 0.0f;
  case TLOD_POLICY_UNIFORM:
    return (float)(d->max_level < cap ? d->max_level : (uint32_t)cap);
  case TLOD_POLICY_SILHOUETTE:
    return silhouette_target(d, contour, cap);
  case TLOD_POLICY_HYBRID:
    /* Away from contours (s < 1) shading hides the flat geometry. */
    return error_target(d, e_max, eps * powf(d->hybrid_relax, 1.0f - contour));
  default:
    return error_target(d, e_max, eps);
  }
}

uint32_t tlod_level_for_error(float e_max, float epsilon, uint32_t max_level) {
  tlod_scheduler_desc d = {.policy = TLOD_POLICY_ERROR, .max_level = max_level, .morph = TLOD_MORPH_NONE};
  return (uint32_t)_tlod_level_rule(&d, e_max, 0.0f, epsilon, INFINITY);
}
