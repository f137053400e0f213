/* tlod tool -- camera matrices. */
#include "camera.h"

#include <math.h>
#include <string.h>

static void normalize3(double v[3]) {
  double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3 && l > 0; i++)
    v[i] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

const char* camera_view_problem(const float eye[3], const float target[3], const float up[3]) {
  double f[3] = {(double)target[0] - eye[0], (double)target[1] - eye[1], (double)target[2] - eye[2]};
  double u[3] = {up[0], up[1], up[2]}, s[3];
  double lf = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  if (!(lf > 0.0) || !isfinite(lf)) return "eye and target are the same point";
  cross3(f, u, s);
  /* sin of the angle between up and the view direction: below 1e-6 the side vector is noise */
  if (!(sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) > 1e-6 * lf * lu)) return "up is parallel to the view direction";
  return NULL;
}

void camera_look_at(const float eye[3], const float target[3], const float up[3], float view[16]) {
  double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, u[3] = {up[0], up[1], up[2]}, s[3];
  normalize3(f);
  cross3(f, u, s);
  if (sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) < 1e-9) {
    /* Up parallel to the view direction: any perpendicular will do. */
    double alt[3] = {fabs(f[0]) < 0.9 ? 1.0 : 0.0, fabs(f[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    cross3(f, alt, s);
  }
  normalize3(s);
  cross3(s, f, u);
  double e[3] = {eye[0], eye[1], eye[2]};
  float m[16] = {(float)s[0],
                 (float)u[0],
                 (float)-f[0],
                 0,
                 (float)s[1],
                 (float)u[1],
                 (float)-f[1],
                 0,
                 (float)s[2],
                 (float)u[2],
                 (float)-f[2],
                 0,
                 (float)-(s[0] * e[0] + s[1] * e[1] + s[2] * e[2]),
                 (float)-(u[0] * e[0] + u[1] * e[1] + u[2] * e[2]),
                 (float)(f[0] * e[0] + f[1] * e[1] + f[2] * e[2]),
                 1};
  memcpy(view, m, sizeof(m));
}

void camera_perspective(float fovy_deg, float aspect, float n, float f, float proj[16]) {
  double t = 1.0 / tan(fovy_deg * 3.14159265358979323846 / 360.0);
  memset(proj, 0, sizeof(float) * 16);
  proj[0] = (float)(t / aspect);
  proj[5] = (float)t;
  proj[10] = (float)(-(f + n) / (double)(f - n));
  proj[11] = -1.0f;
  proj[14] = (float)(-2.0 * f * n / (double)(f - n));
}

void camera_orthographic(float height, float aspect, float n, float f, float proj[16]) {
  memset(proj, 0, sizeof(float) * 16);
  proj[0] = 2.0f / (height * aspect);
  proj[5] = 2.0f / height;
  proj[10] = -2.0f / (f - n);
  proj[14] = -(f + n) / (f - n);
  proj[15] = 1.0f;
}

void camera_fit_planes(const float eye[3], const float bmin[3], const float bmax[3], float* near_z, float* far_z) {
  double diag = 0.0, far = 0.0;
  for (int i = 0; i < 3; i++)
    diag += (double)(bmax[i] - bmin[i]) * (bmax[i] - bmin[i]);
  diag = sqrt(diag);
  for (int c = 0; c < 8; c++) {
    double d = 0.0;
    for (int i = 0; i < 3; i++) {
      double x = (c >> i & 1) ? bmax[i] : bmin[i];
      d += (x - eye[i]) * (x - eye[i]);
    }
    far = sqrt(d) > far ? sqrt(d) : far;
  }
  *near_z = (float)(diag > 0 ? diag * 1e-3 : 1e-3);
  *far_z = (float)(far * 1.5 + diag);
}
