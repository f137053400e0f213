/* tesslod::lod -- the per-frame metrics: silhouette depth per vertex,
 * projected error bound and frustum test per patch, and the level rule.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. 2008 (silhouette depth
 *   d_i = (1 - |n_i . (c - p_i)/|c - p_i||) m);
 *   M. Schwarz, M. Staginski, M. Stamminger. 2006 (e_max = projected
 *   d'_max bound; l smallest with 4^-l e_max <= eps). */
#include <math.h>

#include "scheduler_internal.h"

uint32_t tlod_level_for_error(float e_max, float epsilon, uint32_t max_level) {
  uint32_t l = 0;
  /* Multiply up rather than take a log, so the rule is exact at the
   * thresholds: 4^-l e <= eps <=> e <= eps * 4^l. */
  double bound = epsilon;
  while (l < max_level && !((double)e_max <= bound)) {
    bound *= 4.0;
    l++;
  }
  return l;
}

static bool is_ortho(const float proj[16]) { return proj[15] == 1.0f && proj[11] == 0.0f; }

float tlod_projection_scale(const float proj[16], uint32_t viewport_height, float depth) {
  float half = 0.5f * (float)viewport_height * fabsf(proj[5]);
  if (is_ortho(proj)) return half;
  return depth > 0.0f ? half / depth : INFINITY;
}

void _tlod_camera_from_view(const float view[16], const float proj[16], _tlod_camera* cam) {
  /* Rigid view: eye = -R^T t, forward = -(third row of R). */
  const float* t = view + 12;
  for (int i = 0; i < 3; i++) {
    cam->eye[i] = -(view[i * 4 + 0] * t[0] + view[i * 4 + 1] * t[1] + view[i * 4 + 2] * t[2]);
    cam->forward[i] = -view[i * 4 + 2];
  }
  cam->ortho = is_ortho(proj);
  /* Near distance of a GL projection (a [0, 1]-depth one gives about half
   * of it: only more conservative). */
  float denom = proj[10] - 1.0f;
  float n = denom != 0.0f ? proj[14] / denom : 0.0f;
  cam->near_z = cam->ortho || !(n > 0.0f) ? 0.0f : n;
  /* Frustum planes from the rows of clip = P V (Gribb & Hartmann). */
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
      cam->planes[p][k] = m[k * 4 + 3] + sign * m[k * 4 + row];
      if (k < 3) len += cam->planes[p][k] * cam->planes[p][k];
    }
    len = sqrtf(len);
    for (int k = 0; k < 4 && len > 0.0f; k++)
      cam->planes[p][k] /= len;
  }
}

float _tlod_view_depth(const float view[16], const float p[3]) {
  return -(view[2] * p[0] + view[6] * p[1] + view[10] * p[2] + view[14]);
}

bool _tlod_sphere_visible(const _tlod_camera* cam, const float c[3], float r) {
  for (int p = 0; p < 6; p++) {
    const float* pl = cam->planes[p];
    if (pl[0] * c[0] + pl[1] * c[1] + pl[2] * c[2] + pl[3] < -r) return false;
  }
  return true;
}

float _tlod_facing(const _tlod_camera* cam, const float p[3], const float n[3]) {
  if (cam->ortho) return -(n[0] * cam->forward[0] + n[1] * cam->forward[1] + n[2] * cam->forward[2]);
  return n[0] * (cam->eye[0] - p[0]) + n[1] * (cam->eye[1] - p[1]) + n[2] * (cam->eye[2] - p[2]);
}

float _tlod_silhouette_depth(const _tlod_camera* cam, const float p[3], const float n[3], float m) {
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

float _tlod_patch_e_max(const _tlod_camera* cam, const float view[16], const float proj[16], uint32_t height,
                        const tlod_patch_info* info) {
  if (cam->ortho) return info->error_bound * tlod_projection_scale(proj, height, 1.0f);
  float z = _tlod_view_depth(view, info->center) - info->radius;
  /* Inside the sphere or past the near plane: the nearest visible depth. */
  float zmin = cam->near_z > 0.0f ? cam->near_z : 1e-4f * info->radius;
  if (z < zmin) z = zmin;
  return info->error_bound * tlod_projection_scale(proj, height, z);
}
