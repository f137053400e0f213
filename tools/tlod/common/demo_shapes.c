/* tlod tool -- procedural demo meshes: a cylinder with sharp rims (split
 * normals) and a smooth torus of any size (for benchmarks). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "demo_shapes.h"

static bool shape_alloc(demo_shape* s, uint32_t verts, uint32_t quads) {
  s->vertex_count = verts;
  s->quad_count = quads;
  s->positions = calloc((size_t)verts * 3, sizeof(float));
  s->normals = calloc((size_t)verts * 3, sizeof(float));
  s->indices = calloc((size_t)quads * 4, sizeof(uint32_t));
  if (s->positions && s->normals && s->indices) return true;
  demo_shape_free(s);
  return false;
}

void demo_shape_free(demo_shape* s) {
  free(s->positions);
  free(s->normals);
  free(s->indices);
  memset(s, 0, sizeof(*s));
}

static void set3(float* p, double x, double y, double z) {
  p[0] = (float)x;
  p[1] = (float)y;
  p[2] = (float)z;
}

/* Quads (a, b, c, d) of a grid of rings x segments vertices starting at base,
 * wrapping around the segments (and around the rings when wrap_rings). */
static uint32_t grid_quads(uint32_t* idx, uint32_t base, uint32_t rings, uint32_t segs, bool wrap_rings) {
  uint32_t n = 0, rows = wrap_rings ? rings : rings - 1;
  for (uint32_t r = 0; r < rows; r++) {
    for (uint32_t s = 0; s < segs; s++) {
      uint32_t r1 = (r + 1) % rings, s1 = (s + 1) % segs;
      uint32_t q[4] = {base + r * segs + s, base + r * segs + s1, base + r1 * segs + s1, base + r1 * segs + s};
      memcpy(idx + 4 * n++, q, sizeof(q));
    }
  }
  return n;
}

bool demo_torus(uint32_t rings, uint32_t segs, demo_shape* s) {
  if (!shape_alloc(s, rings * segs, rings * segs)) return false;
  const double big = 1.0, small = 0.35, tau = 6.283185307179586;
  for (uint32_t r = 0; r < rings; r++) {
    for (uint32_t k = 0; k < segs; k++) {
      double a = tau * r / rings, b = tau * k / segs;
      double nx = cos(a) * cos(b), ny = sin(a) * cos(b), nz = sin(b);
      float* p = s->positions + 3 * (r * segs + k);
      set3(p, cos(a) * big + small * nx, sin(a) * big + small * ny, small * nz);
      set3(s->normals + 3 * (r * segs + k), nx, ny, nz);
    }
  }
  grid_quads(s->indices, 0, rings, segs, true);
  return true;
}

/* Side rings carry radial normals; each cap has its own copies of the rim
 * positions with axial normals, so the rims are creases (split normals). A
 * cap is a ring of quads to an inner ring, then quads spanning two inner
 * segments each round the centre. */
bool demo_cylinder(uint32_t segs, demo_shape* s) {
  const uint32_t side_rings = 4;
  uint32_t verts = segs * side_rings + 2 * (2 * segs + 1);
  uint32_t quads = segs * (side_rings - 1) + 2 * (segs + segs);
  if (!shape_alloc(s, verts, quads)) return false;
  const double tau = 6.283185307179586, h = 1.2;
  for (uint32_t r = 0; r < side_rings; r++) {
    for (uint32_t k = 0; k < segs; k++) {
      double a = tau * k / segs;
      set3(s->positions + 3 * (r * segs + k), cos(a), sin(a), -h / 2 + h * r / (side_rings - 1));
      set3(s->normals + 3 * (r * segs + k), cos(a), sin(a), 0);
    }
  }
  uint32_t nq = grid_quads(s->indices, 0, side_rings, segs, false);
  for (int cap = 0; cap < 2; cap++) {
    uint32_t base = segs * side_rings + (uint32_t)cap * (2 * segs + 1);
    double z = cap ? h / 2 : -h / 2, nz = cap ? 1 : -1;
    for (uint32_t ring = 0; ring < 2; ring++) {
      for (uint32_t k = 0; k < segs; k++) {
        double a = tau * k / segs, rad = ring == 0 ? 1.0 : 0.5;
        set3(s->positions + 3 * (base + ring * segs + k), rad * cos(a), rad * sin(a), z);
        set3(s->normals + 3 * (base + ring * segs + k), 0, 0, nz);
      }
    }
    uint32_t centre = base + 2 * segs;
    set3(s->positions + 3 * centre, 0, 0, z);
    set3(s->normals + 3 * centre, 0, 0, nz);
    for (uint32_t k = 0; k < segs; k++) {
      uint32_t k1 = (k + 1) % segs;
      uint32_t q[4] = {base + k, base + k1, base + segs + k1, base + segs + k};
      if (!cap) {
        uint32_t t = q[1];
        q[1] = q[3];
        q[3] = t;
      }
      memcpy(s->indices + 4 * nq++, q, sizeof(q));
    }
    for (uint32_t k = 0; k < segs; k += 2) {
      uint32_t q[4] = {centre, base + segs + k, base + segs + (k + 1) % segs, base + segs + (k + 2) % segs};
      if (!cap) {
        uint32_t t = q[1];
        q[1] = q[3];
        q[3] = t;
      }
      memcpy(s->indices + 4 * nq++, q, sizeof(q));
    }
  }
  s->quad_count = nq;
  return true;
}
