/*
 * shapes.h -- procedural test meshes for the surface and tessellator tests
 * (header-only, every function static inline so a test uses what it needs).
 *
 * Every shape is built in double precision and stored as float arrays:
 * positions (xyz), optional normals (xyz, unit in double before rounding),
 * indices, counter-clockwise seen from outside. Shared vertices are shared
 * by index; "seam" duplicates have bitwise equal positions and normals.
 *
 *   shape_icosphere(s)      unit sphere, icosahedron split s times, normal = position
 *   shape_cube_split()      24 vertices, face normals (glTF Box layout), creases everywhere
 *   shape_cube_soft()       24 vertices like cube_split, but each face's corner normals
 *                           tilted halfway to the corner direction: creases whose two
 *                           sides' boundary curves really differ (face normals make
 *                           straight, coinciding edges)
 *   shape_cube_shared()     8 vertices, normal = normalised corner direction
 *   shape_quad_cube()       6 quads on the 8 shared corners
 *   shape_quad_sphere(n)    cube-sphere, n x n quads per cube face, unit radius
 *   shape_torus(nu, nv)     R = 1, r = 0.4, triangles, closed, genus 1
 *   shape_open_grid(n)      n x n paraboloid cap z = 0.25 (x^2 + y^2) on [-1, 1]^2 (boundary)
 *   shape_seam_sphere(a, b) lat-long sphere whose seam column and pole vertices are
 *                           duplicated (same floats, different indices)
 *
 * The random generator (shape_rng) is a splitmix64, so runs are reproducible.
 */
#ifndef TLOD_TEST_SHAPES_H
#define TLOD_TEST_SHAPES_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tesslod/core.h"

#define SHAPES_PI 3.14159265358979323846

typedef struct shape {
  const char* name;
  float* positions; /* 3 per vertex */
  float* normals;   /* 3 per vertex, or NULL */
  uint32_t vertex_count;
  uint32_t* indices;
  uint32_t index_count;
  uint32_t corners; /* 3 (triangles) or 4 (quads) */
  bool closed;      /* closed 2-manifold after welding equal positions */
  bool creases;     /* some welded vertex has several different normals */
} shape;

static inline void shape_free(shape* s) {
  free(s->positions);
  free(s->normals);
  free(s->indices);
  memset(s, 0, sizeof *s);
}

static inline uint32_t shape_face_count(const shape* s) { return s->index_count / s->corners; }

/* ---------------------------------------------------------------------- */
/* Random numbers                                                         */
/* ---------------------------------------------------------------------- */

typedef struct shape_rng {
  uint64_t state;
} shape_rng;

static inline uint64_t shape_rng_next(shape_rng* r) {
  uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double shape_rng_unit(shape_rng* r) {
  return (double)(shape_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

static inline double shape_rng_range(shape_rng* r, double lo, double hi) { return lo + (hi - lo) * shape_rng_unit(r); }

/* Uniform on the unit sphere. */
static inline void shape_rng_direction(shape_rng* r, double out[3]) {
  for (;;) {
    double x = shape_rng_range(r, -1, 1), y = shape_rng_range(r, -1, 1), z = shape_rng_range(r, -1, 1);
    double l2 = x * x + y * y + z * z;
    if (l2 > 1e-4 && l2 <= 1.0) {
      double l = sqrt(l2);
      out[0] = x / l, out[1] = y / l, out[2] = z / l;
      return;
    }
  }
}

/* ---------------------------------------------------------------------- */
/* Builders                                                               */
/* ---------------------------------------------------------------------- */

static inline void shape_alloc(shape* s, const char* name, uint32_t vertex_count, uint32_t index_count,
                               uint32_t corners, bool normals) {
  memset(s, 0, sizeof *s);
  s->name = name;
  s->vertex_count = vertex_count;
  s->index_count = index_count;
  s->corners = corners;
  s->positions = calloc((size_t)vertex_count * 3 + 1, sizeof(float));
  s->normals = normals ? calloc((size_t)vertex_count * 3 + 1, sizeof(float)) : NULL;
  s->indices = calloc((size_t)index_count + 1, sizeof(uint32_t));
}

static inline void shape_set_vertex(shape* s, uint32_t v, const double p[3], const double n[3]) {
  for (int c = 0; c < 3; ++c)
    s->positions[3 * v + c] = (float)p[c];
  if (n && s->normals) {
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c)
      s->normals[3 * v + c] = (float)(n[c] / l);
  }
}

static inline void shape_normalize3(double v[3]) {
  double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  v[0] /= l, v[1] /= l, v[2] /= l;
}

/* Icosahedron split `subdivisions` times, projected to the unit sphere. */
static inline shape shape_icosphere(uint32_t subdivisions) {
  const double t = (1.0 + sqrt(5.0)) / 2.0;
  double base[12][3] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                        {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  static const uint32_t base_faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  uint32_t vcount = 12, fcount = 20;
  uint32_t vmax = 12, fmax = 20;
  for (uint32_t s = 0; s < subdivisions; ++s) {
    vmax = vmax + (fmax * 3 / 2);
    fmax *= 4;
  }
  double(*p)[3] = malloc(sizeof *p * vmax);
  uint32_t* f = malloc(sizeof *f * 3 * fmax);
  for (uint32_t v = 0; v < 12; ++v) {
    memcpy(p[v], base[v], sizeof base[v]);
    shape_normalize3(p[v]);
  }
  memcpy(f, base_faces, sizeof base_faces);
  for (uint32_t s = 0; s < subdivisions; ++s) {
    uint32_t* mid = malloc(sizeof *mid * vcount * vcount);
    for (uint32_t k = 0; k < vcount * vcount; ++k)
      mid[k] = UINT32_MAX;
    uint32_t* nf = malloc(sizeof *nf * 3 * fcount * 4);
    uint32_t old_vcount = vcount;
    for (uint32_t face = 0; face < fcount; ++face) {
      uint32_t c[3] = {f[3 * face], f[3 * face + 1], f[3 * face + 2]}, m[3];
      for (int e = 0; e < 3; ++e) {
        uint32_t a = c[e], b = c[(e + 1) % 3];
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
        uint32_t* slot = &mid[lo * old_vcount + hi];
        if (*slot == UINT32_MAX) {
          for (int k = 0; k < 3; ++k)
            p[vcount][k] = 0.5 * (p[a][k] + p[b][k]);
          shape_normalize3(p[vcount]);
          *slot = vcount++;
        }
        m[e] = *slot;
      }
      uint32_t tri[4][3] = {{c[0], m[0], m[2]}, {m[0], c[1], m[1]}, {m[2], m[1], c[2]}, {m[0], m[1], m[2]}};
      memcpy(nf + 12 * face, tri, sizeof tri);
    }
    free(mid);
    free(f);
    f = nf;
    fcount *= 4;
  }
  shape out;
  shape_alloc(&out,
              subdivisions == 1   ? "icosphere1"
              : subdivisions == 2 ? "icosphere2"
                                  : "icosphere",
              vcount, 3 * fcount, 3, true);
  for (uint32_t v = 0; v < vcount; ++v)
    shape_set_vertex(&out, v, p[v], p[v]);
  /* Orient every face outward (the table above is CCW outward already; this
   * makes it so regardless). */
  for (uint32_t face = 0; face < fcount; ++face) {
    uint32_t* c = f + 3 * face;
    const double *a = p[c[0]], *b = p[c[1]], *d = p[c[2]];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * (a[0] + b[0] + d[0]) + n[1] * (a[1] + b[1] + d[1]) + n[2] * (a[2] + b[2] + d[2]) < 0) {
      uint32_t tmp = c[1];
      c[1] = c[2];
      c[2] = tmp;
    }
  }
  memcpy(out.indices, f, sizeof *f * 3 * fcount);
  out.closed = true;
  free(p);
  free(f);
  return out;
}

/* Cube lattice helper: the grid point (a, b, c) in [0, n]^3 on the surface. */
static inline uint32_t shape__lattice_id(uint32_t n, uint32_t a, uint32_t b, uint32_t c) {
  return (a * (n + 1) + b) * (n + 1) + c;
}

/* A cube [-h, h]^3 split into n x n quads a face, shared vertices.
 * spherize: positions projected on the unit sphere, normal = position;
 * otherwise normal = normalised position (corner directions). quads: 4
 * corners a face, otherwise each quad split in two triangles. */
static inline shape shape__cube_lattice(const char* name, uint32_t n, double h, bool spherize, bool quads) {
  uint32_t side = n + 1;
  uint32_t* id = malloc(sizeof *id * side * side * side);
  uint32_t vcount = 0;
  for (uint32_t a = 0; a <= n; ++a)
    for (uint32_t b = 0; b <= n; ++b)
      for (uint32_t c = 0; c <= n; ++c) {
        bool surface = a == 0 || a == n || b == 0 || b == n || c == 0 || c == n;
        id[shape__lattice_id(n, a, b, c)] = surface ? vcount++ : UINT32_MAX;
      }
  uint32_t fcount = 6 * n * n;
  shape out;
  shape_alloc(&out, name, vcount, quads ? 4 * fcount : 6 * fcount, quads ? 4 : 3, true);
  for (uint32_t a = 0; a <= n; ++a)
    for (uint32_t b = 0; b <= n; ++b)
      for (uint32_t c = 0; c <= n; ++c) {
        uint32_t v = id[shape__lattice_id(n, a, b, c)];
        if (v == UINT32_MAX) continue;
        double p[3] = {(2.0 * a / n - 1.0) * h, (2.0 * b / n - 1.0) * h, (2.0 * c / n - 1.0) * h};
        double nn[3] = {p[0], p[1], p[2]};
        shape_normalize3(nn);
        if (spherize) memcpy(p, nn, sizeof p);
        shape_set_vertex(&out, v, p, nn);
      }
  /* Faces: fixed axis, sign, and in-face axes (s, t) with s x t = outward. */
  static const int face_axes[6][4] = {/* axis, sign(1 = max side), s axis, t axis */
                                      {0, 1, 1, 2}, {0, 0, 2, 1}, {1, 1, 2, 0},
                                      {1, 0, 0, 2}, {2, 1, 0, 1}, {2, 0, 1, 0}};
  uint32_t k = 0;
  for (int fa = 0; fa < 6; ++fa) {
    for (uint32_t t = 0; t < n; ++t)
      for (uint32_t s = 0; s < n; ++s) {
        uint32_t corner[4];
        static const uint32_t ds[4] = {0, 1, 1, 0}, dt[4] = {0, 0, 1, 1};
        for (int q = 0; q < 4; ++q) {
          uint32_t coord[3];
          coord[face_axes[fa][0]] = face_axes[fa][1] ? n : 0;
          coord[face_axes[fa][2]] = s + ds[q];
          coord[face_axes[fa][3]] = t + dt[q];
          corner[q] = id[shape__lattice_id(n, coord[0], coord[1], coord[2])];
        }
        if (quads) {
          for (int q = 0; q < 4; ++q)
            out.indices[k++] = corner[q];
        } else {
          uint32_t tri[6] = {corner[0], corner[1], corner[2], corner[0], corner[2], corner[3]};
          for (int q = 0; q < 6; ++q)
            out.indices[k++] = tri[q];
        }
      }
  }
  out.closed = true;
  free(id);
  return out;
}

static inline shape shape_cube_shared(void) { return shape__cube_lattice("cube_shared", 1, 0.5, false, false); }
static inline shape shape_quad_cube(void) { return shape__cube_lattice("quad_cube", 1, 0.5, false, true); }
static inline shape shape_quad_sphere(uint32_t n) { return shape__cube_lattice("quad_sphere", n, 1.0, true, true); }

/* glTF-Box-like cube [-0.5, 0.5]^3: 4 vertices a face with the face normal
 * (soft: normalize(face normal + corner direction)). */
static inline shape shape__cube_split(bool soft) {
  shape out;
  shape_alloc(&out, soft ? "cube_soft" : "cube_split", 24, 36, 3, true);
  static const int face_axes[6][4] = {{0, 1, 1, 2}, {0, 0, 2, 1}, {1, 1, 2, 0},
                                      {1, 0, 0, 2}, {2, 1, 0, 1}, {2, 0, 1, 0}};
  static const int ds[4] = {0, 1, 1, 0}, dt[4] = {0, 0, 1, 1};
  for (uint32_t fa = 0; fa < 6; ++fa) {
    double nn[3] = {0, 0, 0};
    nn[face_axes[fa][0]] = face_axes[fa][1] ? 1.0 : -1.0;
    for (int q = 0; q < 4; ++q) {
      double p[3];
      p[face_axes[fa][0]] = face_axes[fa][1] ? 0.5 : -0.5;
      p[face_axes[fa][2]] = ds[q] ? 0.5 : -0.5;
      p[face_axes[fa][3]] = dt[q] ? 0.5 : -0.5;
      double sn[3] = {nn[0], nn[1], nn[2]};
      if (soft) {
        double cd[3] = {p[0], p[1], p[2]};
        shape_normalize3(cd);
        for (int c = 0; c < 3; ++c)
          sn[c] += cd[c];
      }
      shape_set_vertex(&out, 4 * fa + (uint32_t)q, p, sn);
    }
    uint32_t b = 4 * fa, tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
    memcpy(out.indices + 6 * fa, tri, sizeof tri);
  }
  out.closed = true;
  out.creases = true;
  return out;
}

/* The quad sphere of shape_quad_sphere(n) with each cube face's vertices
 * its own, normal = normalize(position + 0.5 face direction): smooth and
 * curved inside a face, a crease (bitwise equal positions, other normals)
 * along the cube's 12 edges. */
static inline shape shape_creased_sphere(uint32_t n) {
  static const int face_axes[6][4] = {{0, 1, 1, 2}, {0, 0, 2, 1}, {1, 1, 2, 0},
                                      {1, 0, 0, 2}, {2, 1, 0, 1}, {2, 0, 1, 0}};
  uint32_t side = n + 1;
  shape out;
  shape_alloc(&out, "creased_sphere", 6 * side * side, 6 * 4 * n * n, 4, true);
  uint32_t k = 0;
  for (uint32_t fa = 0; fa < 6; ++fa) {
    for (uint32_t t = 0; t <= n; ++t)
      for (uint32_t u = 0; u <= n; ++u) {
        double p[3], nn[3];
        p[face_axes[fa][0]] = face_axes[fa][1] ? 1.0 : -1.0;
        p[face_axes[fa][2]] = 2.0 * u / n - 1.0;
        p[face_axes[fa][3]] = 2.0 * t / n - 1.0;
        shape_normalize3(p);
        memcpy(nn, p, sizeof nn);
        nn[face_axes[fa][0]] += face_axes[fa][1] ? 0.5 : -0.5;
        shape_normalize3(nn);
        shape_set_vertex(&out, fa * side * side + t * side + u, p, nn);
      }
    for (uint32_t t = 0; t < n; ++t)
      for (uint32_t u = 0; u < n; ++u) {
        uint32_t b = fa * side * side + t * side + u, quad[4] = {b, b + 1, b + side + 1, b + side};
        memcpy(out.indices + k, quad, sizeof quad);
        k += 4;
      }
  }
  out.closed = true;
  out.creases = true;
  return out;
}

static inline shape shape_cube_split(void) { return shape__cube_split(false); }
static inline shape shape_cube_soft(void) { return shape__cube_split(true); }

static inline shape shape_torus(uint32_t nu, uint32_t nv) {
  const double R = 1.0, r = 0.4;
  shape out;
  shape_alloc(&out, "torus", nu * nv, 6 * nu * nv, 3, true);
  for (uint32_t i = 0; i < nu; ++i)
    for (uint32_t j = 0; j < nv; ++j) {
      double u = 2 * SHAPES_PI * i / nu, v = 2 * SHAPES_PI * j / nv;
      double p[3] = {(R + r * cos(v)) * cos(u), (R + r * cos(v)) * sin(u), r * sin(v)};
      double n[3] = {cos(v) * cos(u), cos(v) * sin(u), sin(v)};
      shape_set_vertex(&out, i * nv + j, p, n);
    }
  uint32_t k = 0;
  for (uint32_t i = 0; i < nu; ++i)
    for (uint32_t j = 0; j < nv; ++j) {
      uint32_t i1 = (i + 1) % nu, j1 = (j + 1) % nv;
      uint32_t a = i * nv + j, b = i1 * nv + j, c = i1 * nv + j1, d = i * nv + j1;
      uint32_t tri[6] = {a, b, c, a, c, d};
      memcpy(out.indices + k, tri, sizeof tri);
      k += 6;
    }
  out.closed = true;
  return out;
}

/* Paraboloid cap over [-1, 1]^2, n x n cells, two triangles a cell. */
static inline shape shape_open_grid(uint32_t n) {
  shape out;
  shape_alloc(&out, "open_grid", (n + 1) * (n + 1), 6 * n * n, 3, true);
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) {
      double x = 2.0 * i / n - 1.0, y = 2.0 * j / n - 1.0;
      double p[3] = {x, y, 0.25 * (x * x + y * y)};
      double nn[3] = {-0.5 * x, -0.5 * y, 1.0};
      shape_set_vertex(&out, j * (n + 1) + i, p, nn);
    }
  uint32_t k = 0;
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      uint32_t tri[6] = {a, b, c, a, c, d};
      memcpy(out.indices + k, tri, sizeof tri);
      k += 6;
    }
  out.closed = false;
  return out;
}

/* Lat-long unit sphere, nlat >= 2 rings of quads (triangle fans at the poles),
 * nlon columns. Vertex (i, j), i = 0..nlat, j = 0..nlon: column nlon is a copy
 * of column 0 (UV seam) and each pole has a copy per column; copies are
 * bitwise equal in position and normal. */
static inline shape shape_seam_sphere(uint32_t nlat, uint32_t nlon) {
  uint32_t cols = nlon + 1;
  shape out;
  shape_alloc(&out, "seam_sphere", (nlat + 1) * cols, 6 * nlon * (nlat - 1), 3, true);
  for (uint32_t i = 0; i <= nlat; ++i)
    for (uint32_t j = 0; j <= nlon; ++j) {
      uint32_t v = i * cols + j;
      if (j == nlon) {
        memcpy(out.positions + 3 * v, out.positions + 3 * (i * cols), 3 * sizeof(float));
        memcpy(out.normals + 3 * v, out.normals + 3 * (i * cols), 3 * sizeof(float));
        continue;
      }
      double th = SHAPES_PI * i / nlat, ph = 2 * SHAPES_PI * j / nlon;
      double p[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
      if (i == 0) p[0] = p[1] = 0, p[2] = 1;
      if (i == nlat) p[0] = p[1] = 0, p[2] = -1;
      shape_set_vertex(&out, v, p, p);
    }
  uint32_t k = 0;
  for (uint32_t i = 0; i < nlat; ++i)
    for (uint32_t j = 0; j < nlon; ++j) {
      uint32_t a = i * cols + j, b = (i + 1) * cols + j, c = (i + 1) * cols + j + 1, d = i * cols + j + 1;
      if (i == 0) {
        uint32_t tri[3] = {a, b, c};
        memcpy(out.indices + k, tri, sizeof tri);
        k += 3;
      } else if (i == nlat - 1) {
        uint32_t tri[3] = {a, b, d};
        memcpy(out.indices + k, tri, sizeof tri);
        k += 3;
      } else {
        uint32_t tri[6] = {a, b, c, a, c, d};
        memcpy(out.indices + k, tri, sizeof tri);
        k += 6;
      }
    }
  out.index_count = k;
  out.closed = true;
  return out;
}

/* ---------------------------------------------------------------------- */
/* Topology of a shape, by exact position equality                        */
/* ---------------------------------------------------------------------- */

static inline int shape__cmp_u64(const void* a, const void* b) {
  uint64_t x = *(const uint64_t*)a, y = *(const uint64_t*)b;
  return x < y ? -1 : x > y;
}

static inline uint64_t shape__mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Smallest power of two >= 2 n + 2 (open-addressing table size). */
static inline size_t shape__table_size(size_t n) {
  size_t cap = 16;
  while (cap < 2 * n + 2)
    cap *= 2;
  return cap;
}

/* Weld id per vertex (ids dense from 0, in order of first occurrence), by
 * bitwise equal position; returns the count. */
static inline uint32_t shape_weld_ids(const float* positions, uint32_t vertex_count, uint32_t* weld) {
  size_t cap = shape__table_size(vertex_count), mask = cap - 1;
  uint32_t* slot = malloc(sizeof *slot * cap);
  memset(slot, 0xFF, sizeof *slot * cap);
  uint32_t count = 0;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    uint32_t bits[3];
    memcpy(bits, positions + 3 * (size_t)v, sizeof bits);
    size_t h = (size_t)shape__mix64(((uint64_t)bits[0] << 32 | bits[1]) ^ shape__mix64(bits[2])) & mask;
    for (;; h = (h + 1) & mask) {
      if (slot[h] == UINT32_MAX) {
        slot[h] = v;
        weld[v] = count++;
        break;
      }
      if (memcmp(positions + 3 * (size_t)slot[h], bits, sizeof bits) == 0) {
        weld[v] = weld[slot[h]];
        break;
      }
    }
  }
  free(slot);
  return count;
}

/* Counts of welded vertices used by faces and distinct welded edges. */
static inline void shape_topology(const shape* s, uint32_t* welded_vertices, uint32_t* edges) {
  uint32_t* weld = malloc(sizeof *weld * (s->vertex_count + 1));
  uint32_t wcount = shape_weld_ids(s->positions, s->vertex_count, weld);
  uint64_t* keys = malloc(sizeof *keys * (s->index_count + 1));
  uint32_t faces = shape_face_count(s);
  bool* used = calloc(wcount + 1, 1);
  for (uint32_t f = 0; f < faces; ++f)
    for (uint32_t c = 0; c < s->corners; ++c) {
      uint32_t a = weld[s->indices[f * s->corners + c]], b = weld[s->indices[f * s->corners + (c + 1) % s->corners]];
      used[a] = true;
      keys[f * s->corners + c] = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
    }
  qsort(keys, s->index_count, sizeof *keys, shape__cmp_u64);
  uint32_t e = 0;
  for (uint32_t k = 0; k < s->index_count; ++k)
    if (k == 0 || keys[k] != keys[k - 1]) e++;
  uint32_t vcount = 0;
  for (uint32_t w = 0; w < wcount; ++w)
    vcount += used[w];
  *welded_vertices = vcount;
  *edges = e;
  free(used);
  free(keys);
  free(weld);
}

/* ---------------------------------------------------------------------- */
/* Closedness of a triangle soup, by exact position equality              */
/* ---------------------------------------------------------------------- */

/* Half-edge census of triangles welded by bitwise equal positions (shared
 * by the tessellator and scheduler tests). A half-edge is corner c -> c + 1
 * of triangle t, named 3 t + c. Degenerate triangles (two corners at one
 * welded position) are counted and their half-edges left out. */
typedef struct shape_census {
  uint32_t degenerate; /* triangles with two corners at one position */
  uint32_t duplicated; /* directed (welded) edges used more than once */
  uint32_t open;       /* half-edges without an opposite half */
  uint32_t first_degenerate;
  uint64_t first_duplicated, first_open; /* welded ids, from << 32 | to */
} shape_census;

/* open_list (may be NULL) receives the ids of up to open_capacity open half-edges. */
static inline shape_census shape_half_edge_census(const float* positions, uint32_t vertex_count,
                                                  const uint32_t* indices, uint32_t triangle_count, uint32_t* open_list,
                                                  uint32_t open_capacity) {
  shape_census c;
  memset(&c, 0, sizeof c);
  uint32_t* weld = malloc(sizeof *weld * ((size_t)vertex_count + 1));
  shape_weld_ids(positions, vertex_count, weld);
  /* table of directed welded edges (key 0 is free: from != to) with counts */
  size_t cap = shape__table_size(3 * (size_t)triangle_count), mask = cap - 1;
  uint64_t* key = calloc(cap, sizeof *key);
  uint32_t* count = calloc(cap, sizeof *count);
  uint64_t* he = malloc(sizeof *he * (3 * (size_t)triangle_count + 1)); /* per half-edge: key, or 0 */
  for (uint32_t t = 0; t < triangle_count; ++t) {
    uint32_t w[3];
    for (int k = 0; k < 3; ++k)
      w[k] = weld[indices[3 * (size_t)t + k]];
    bool degenerate = w[0] == w[1] || w[1] == w[2] || w[2] == w[0];
    if (degenerate && c.degenerate++ == 0) c.first_degenerate = t;
    for (int k = 0; k < 3; ++k) {
      uint64_t kk = degenerate ? 0 : (uint64_t)w[k] << 32 | w[(k + 1) % 3];
      he[3 * (size_t)t + k] = kk;
      if (!kk) continue;
      size_t h = (size_t)shape__mix64(kk) & mask;
      while (key[h] && key[h] != kk)
        h = (h + 1) & mask;
      key[h] = kk;
      if (count[h]++ == 1) {
        if (c.duplicated == 0) c.first_duplicated = kk;
        c.duplicated++;
      }
    }
  }
  for (size_t i = 0; i < 3 * (size_t)triangle_count; ++i) {
    uint64_t kk = he[i];
    if (!kk) continue;
    uint64_t rev = kk << 32 | kk >> 32;
    size_t h = (size_t)shape__mix64(rev) & mask;
    while (key[h] && key[h] != rev)
      h = (h + 1) & mask;
    if (!key[h]) {
      if (c.open == 0) c.first_open = kk;
      if (open_list && c.open < open_capacity) open_list[c.open] = (uint32_t)i;
      c.open++;
    }
  }
  free(he);
  free(count);
  free(key);
  free(weld);
  return c;
}

/* Welds the triangles by bitwise equal positions and checks that the result
 * is a closed, consistently oriented 2-manifold without degenerate
 * triangles: every directed edge occurs once and its reverse occurs once.
 * triangle_patch (may be NULL) names a degenerate triangle's patch in `why`. */
static inline bool shape_closed_manifold(const float* positions, uint32_t vertex_count, const uint32_t* indices,
                                         uint32_t triangle_count, const uint32_t* triangle_patch, char* why,
                                         size_t why_size) {
  if (triangle_count == 0) {
    snprintf(why, why_size, "no triangles");
    return false;
  }
  shape_census c = shape_half_edge_census(positions, vertex_count, indices, triangle_count, NULL, 0);
  if (c.degenerate) {
    snprintf(why, why_size, "triangle %u (patch %d) is degenerate after welding (%u such)", c.first_degenerate,
             triangle_patch ? (int)triangle_patch[c.first_degenerate] : -2, c.degenerate);
    return false;
  }
  if (c.duplicated) {
    snprintf(why, why_size, "directed edge %u->%u used twice (non-manifold or flipped; %u such)",
             (uint32_t)(c.first_duplicated >> 32), (uint32_t)c.first_duplicated, c.duplicated);
    return false;
  }
  if (c.open) {
    snprintf(why, why_size, "edge %u->%u has no opposite half (a crack or a boundary; %u such)",
             (uint32_t)(c.first_open >> 32), (uint32_t)c.first_open, c.open);
    return false;
  }
  return true;
}

/* A mesh desc for the shape (kept normals, no creases computed, exact weld). */
static inline tlod_mesh_desc shape_mesh_desc(const shape* s) {
  tlod_mesh_desc d = {0};
  d.positions = s->positions;
  d.normals = s->normals;
  d.vertex_count = s->vertex_count;
  d.indices = s->indices;
  d.index_count = s->index_count;
  d.face_type = s->corners == 4 ? TLOD_FACE_QUADS : TLOD_FACE_TRIANGLES;
  d.normal_mode = TLOD_NORMALS_KEEP;
  d.label = s->name;
  return d;
}

#endif
