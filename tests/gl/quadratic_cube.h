/*
 * quadratic_cube.h -- a curved second-order cube for the GPU tests of
 * TLOD_SURFACE_QUADRATIC (tests/gl, tests/vk), and its surface evaluated
 * here from the shape functions, independently of core. Header-only.
 *
 * Corners (+-1, +-1, +-1). The four side faces are quads: +x, -x and +y
 * 9-node (biquadratic) faces, -y an 8-node (serendipity) face; +z and -z
 * are two 6-node triangles each, split on a diagonal whose node both
 * triangles share. Every cube edge's node sits at 1.2x the edge midpoint,
 * face centres and diagonal nodes at 1.3x the face centre: a closed,
 * visibly curved surface. Faces are outward (counter-clockwise seen from
 * outside); kept faces == patches, in this order: 4 quads, 4 triangles.
 */
#ifndef TLOD_QUADRATIC_CUBE_H
#define TLOD_QUADRATIC_CUBE_H

#include <string.h>

#include "tesslod/core.h"

#define QCUBE_FACES 8
#define QCUBE_VERTICES 25 /* 8 corners, 12 edge nodes, 3 side centres, 2 diagonal nodes */

typedef struct qcube {
  float pos[QCUBE_VERTICES][3];
  uint32_t indices[4 * 4 + 4 * 3];
  uint8_t sizes[QCUBE_FACES];
  uint32_t nodes[QCUBE_FACES][TLOD_FACE_NODES];
  uint32_t corners[QCUBE_FACES][4]; /* per face, sizes[f] of them */
  tlod_mesh_desc desc;
} qcube;

/* Node vertex of the cube edge between corners a and b (indices x + 2y + 4z). */
static inline uint32_t qcube_edge_node(uint32_t a, uint32_t b) {
  uint32_t lo = a < b ? a : b, bit = a ^ b, n = 0;
  for (uint32_t x = 0; x < 8; x++)
    for (uint32_t k = 1; k <= 4; k <<= 1)
      if (!(x & k)) {
        if (x == lo && k == bit) return 8 + n;
        n++;
      }
  return TLOD_NO_NODE;
}

static inline void qcube_scaled_mid(qcube* q, uint32_t out, const uint32_t* c, int n, float scale) {
  for (int k = 0; k < 3; k++) {
    float s = 0.0f;
    for (int i = 0; i < n; i++)
      s += q->pos[c[i]][k];
    q->pos[out][k] = s / (float)n * scale;
  }
}

/* The corners of side (axis, sign) in cyclic order, outward. */
static inline void qcube_side(int axis, int sign, uint32_t c[4]) {
  int a = (axis + 1) % 3, b = (axis + 2) % 3;
  const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; i++)
    c[i] = (uint32_t)(sign << axis | cyc[i][0] << a | cyc[i][1] << b);
  /* (a, b, axis) is right-handed: counter-clockwise about +axis; flip for -axis. */
  if (!sign) {
    uint32_t t = c[1];
    c[1] = c[3], c[3] = t;
  }
}

static inline void qcube_face(qcube* q, int f, const uint32_t* c, int n, uint32_t centre, const uint32_t* diag) {
  q->sizes[f] = (uint8_t)n;
  for (int i = 0; i < TLOD_FACE_NODES; i++)
    q->nodes[f][i] = TLOD_NO_NODE;
  for (int e = 0; e < n; e++) {
    q->corners[f][e] = c[e];
    uint32_t a = c[e], b = c[(e + 1) % n];
    q->nodes[f][e] =
        diag && ((a == diag[0] && b == diag[1]) || (a == diag[1] && b == diag[0])) ? diag[2] : qcube_edge_node(a, b);
  }
  if (n == 4) q->nodes[f][4] = centre;
}

/* desc points into q: keep q where it is. */
static inline void qcube_make(qcube* q) {
  memset(q, 0, sizeof *q);
  for (uint32_t i = 0; i < 8; i++)
    for (int k = 0; k < 3; k++)
      q->pos[i][k] = (i >> k & 1) ? 1.0f : -1.0f;
  for (uint32_t a = 0; a < 8; a++)
    for (uint32_t k = 1; k <= 4; k <<= 1)
      if (!(a & k)) qcube_scaled_mid(q, qcube_edge_node(a, a | k), (uint32_t[2]){a, a | k}, 2, 1.2f);
  const int sides[4][2] = {{0, 1}, {0, 0}, {1, 1}, {1, 0}}; /* +x -x +y -y */
  uint32_t c[4], next = 20, *ix = q->indices;
  for (int f = 0; f < 4; f++) {
    qcube_side(sides[f][0], sides[f][1], c);
    uint32_t centre = f == 3 ? TLOD_NO_NODE : next++;
    if (centre != TLOD_NO_NODE) qcube_scaled_mid(q, centre, c, 4, 1.3f);
    qcube_face(q, f, c, 4, centre, NULL);
    memcpy(ix, c, sizeof c), ix += 4;
  }
  for (int s = 0; s < 2; s++) { /* +z, -z: triangles (c0 c1 c2), (c0 c2 c3) */
    qcube_side(2, 1 - s, c);
    uint32_t d[3] = {c[0], c[2], next++};
    qcube_scaled_mid(q, d[2], c, 4, 1.3f);
    uint32_t t0[3] = {c[0], c[1], c[2]}, t1[3] = {c[0], c[2], c[3]};
    qcube_face(q, 4 + 2 * s, t0, 3, TLOD_NO_NODE, d);
    qcube_face(q, 5 + 2 * s, t1, 3, TLOD_NO_NODE, d);
    memcpy(ix, t0, sizeof t0), ix += 3;
    memcpy(ix, t1, sizeof t1), ix += 3;
  }
  q->desc = (tlod_mesh_desc){.positions = &q->pos[0][0],
                             .vertex_count = QCUBE_VERTICES,
                             .indices = q->indices,
                             .index_count = (uint32_t)(ix - q->indices),
                             .face_type = TLOD_FACE_MIXED,
                             .face_sizes = q->sizes,
                             .face_count = QCUBE_FACES,
                             .face_nodes = &q->nodes[0][0],
                             .label = "quadratic_cube"};
}

/* The cube with one colour attribute (COLOR_0, 3 components), every vertex
 * rgb (a field's time step, for the attribute update tests). desc points
 * into c: keep c where it is. */
typedef struct qcube_coloured {
  qcube q;
  float rgb[QCUBE_VERTICES][3];
  tlod_attribute_desc attr;
} qcube_coloured;

static inline void qcube_coloured_make(qcube_coloured* c, const float rgb[3]) {
  qcube_make(&c->q);
  for (int v = 0; v < QCUBE_VERTICES; v++)
    memcpy(c->rgb[v], rgb, sizeof(float[3]));
  c->attr = (tlod_attribute_desc){.data = &c->rgb[0][0], .components = 3, .name = "COLOR_0"};
  c->q.desc.attributes = &c->attr;
  c->q.desc.attribute_count = 1;
}

/* 1D quadratic Lagrange basis at nodes 0, 1/2, 1. */
static inline void qcube_basis(double t, double b[3]) {
  b[0] = (1.0 - t) * (1.0 - 2.0 * t), b[1] = 4.0 * t * (1.0 - t), b[2] = t * (2.0 * t - 1.0);
}

static inline void qcube_add(double out[3], const float p[3], double w) {
  for (int k = 0; k < 3; k++)
    out[k] += w * p[k];
}

/* The 6-node triangle at (u, v): l = (u, v, 1 - u - v) on corners 0, 1, 2. */
static inline void qcube_eval_triangle(const qcube* q, int f, double u, double v, double out[3]) {
  const double l[3] = {u, v, 1.0 - u - v};
  for (int i = 0; i < 3; i++) {
    qcube_add(out, q->pos[q->corners[f][i]], l[i] * (2.0 * l[i] - 1.0));
    qcube_add(out, q->pos[q->nodes[f][i]], 4.0 * l[i] * l[(i + 1) % 3]);
  }
}

/* The 8-node serendipity quad, from its own shape functions (xi, eta in [-1, 1]). */
static inline void qcube_eval_serendipity(const qcube* q, int f, double u, double v, double out[3]) {
  const double xi = 2.0 * u - 1.0, eta = 2.0 * v - 1.0;
  const double cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1}, mx[4] = {0, 1, 0, -1}, my[4] = {-1, 0, 1, 0};
  for (int i = 0; i < 4; i++) {
    double a = xi * cx[i], b = eta * cy[i];
    qcube_add(out, q->pos[q->corners[f][i]], 0.25 * (1.0 + a) * (1.0 + b) * (a + b - 1.0));
    double m =
        mx[i] == 0.0 ? 0.5 * (1.0 - xi * xi) * (1.0 + eta * my[i]) : 0.5 * (1.0 + xi * mx[i]) * (1.0 - eta * eta);
    qcube_add(out, q->pos[q->nodes[f][i]], m);
  }
}

/* Face f at (u, v) (core.h PARAMETERS), in double. */
static inline void qcube_eval(const qcube* q, int f, double u, double v, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  if (q->sizes[f] == 3) {
    qcube_eval_triangle(q, f, u, v, out);
    return;
  }
  if (q->nodes[f][4] == TLOD_NO_NODE) {
    qcube_eval_serendipity(q, f, u, v, out);
    return;
  }
  double a[3], b[3];
  qcube_basis(u, a), qcube_basis(v, b);
  /* (index of the u basis, of the v basis) per node: corners, edge nodes, centre */
  const int ia[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, ib[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
  for (int n = 0; n < 9; n++) {
    uint32_t vtx = n < 4 ? q->corners[f][n] : q->nodes[f][n - 4];
    qcube_add(out, q->pos[vtx], a[ia[n]] * b[ib[n]]);
  }
}

#endif
