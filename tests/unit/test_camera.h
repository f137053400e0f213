/* Shared by the unit and GL tests: cameras built in double precision and
 * stored as float, from the public conventions only (column-major GL
 * look-at, perspective and orthographic), the 3-vector helpers they need
 * and a 4x4 matrix product. Independent of the library's own maths. */
#ifndef TLOD_TEST_CAMERA_H
#define TLOD_TEST_CAMERA_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/lod.h"

typedef struct camera {
  double eye[3], target[3], up[3];
  double fovy;   /* perspective, radians */
  double half_h; /* orthographic half height */
  double aspect, znear, zfar;
  bool ortho;
  uint32_t width, height;
} camera;

static inline void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline double len3(const double a[3]) { return sqrt(dot3(a, a)); }

/* Column-major GL look-at (gluLookAt). */
static inline void look_at(const double eye[3], const double target[3], const double up[3], double m[16]) {
  double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, s[3], u[3];
  shape_normalize3(f);
  cross3(f, up, s);
  shape_normalize3(s);
  cross3(s, f, u);
  memset(m, 0, 16 * sizeof *m);
  for (int k = 0; k < 3; ++k) {
    m[4 * k + 0] = s[k];
    m[4 * k + 1] = u[k];
    m[4 * k + 2] = -f[k];
  }
  m[12] = -dot3(s, eye);
  m[13] = -dot3(u, eye);
  m[14] = dot3(f, eye);
  m[15] = 1;
}

/* Column-major GL perspective (gluPerspective), fovy in radians. */
static inline void perspective(double fovy, double aspect, double n, double fa, double p[16]) {
  memset(p, 0, 16 * sizeof *p);
  double F = 1.0 / tan(fovy / 2);
  p[0] = F / aspect;
  p[5] = F;
  p[10] = (fa + n) / (n - fa);
  p[11] = -1.0;
  p[14] = 2.0 * fa * n / (n - fa);
}

/* Column-major GL orthographic (glOrtho), symmetric about the axis. */
static inline void orthographic(double half_w, double half_h, double n, double fa, double p[16]) {
  memset(p, 0, 16 * sizeof *p);
  p[0] = 1.0 / half_w;
  p[5] = 1.0 / half_h;
  p[10] = -2.0 / (fa - n);
  p[14] = -(fa + n) / (fa - n);
  p[15] = 1.0;
}

/* out = a * b (column-major); out must not alias a or b. */
static inline void mat4_mul(const double a[16], const double b[16], double out[16]) {
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k)
        s += a[4 * k + row] * b[4 * col + k];
      out[4 * col + row] = s;
    }
}

/* The camera's view, projection and viewport, stored as float. */
static inline tlod_view_desc make_view(const camera* c) {
  tlod_view_desc v;
  memset(&v, 0, sizeof v);
  double m[16], p[16];
  look_at(c->eye, c->target, c->up, m);
  if (c->ortho)
    orthographic(c->half_h * c->aspect, c->half_h, c->znear, c->zfar, p);
  else
    perspective(c->fovy, c->aspect, c->znear, c->zfar, p);
  for (int k = 0; k < 16; ++k)
    v.view[k] = (float)m[k], v.proj[k] = (float)p[k];
  v.viewport_width = c->width;
  v.viewport_height = c->height;
  return v;
}

#endif
