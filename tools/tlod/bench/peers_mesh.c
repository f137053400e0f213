/* tlod bench --peers -- the meshes: the demo torus (tools/tlod/common) as
 * triangles, quads or both, and the geometry both sides are judged by. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "common/demo_shapes.h"
#include "peers.h"

/* Quads of the torus for `faces` faces of this kind. */
static uint32_t quads_for(const char* kind, uint32_t faces) {
  if (!strcmp(kind, "triangle")) return faces / 2;
  if (!strcmp(kind, "mixed")) return (uint32_t)(faces / 1.5);
  return faces;
}

/* Whether quad (r, k) is split: all of them, none, or a checkerboard. */
static bool split(const char* kind, uint32_t r, uint32_t k) {
  return !strcmp(kind, "triangle") || (!strcmp(kind, "mixed") && (r + k) % 2 == 0);
}

static void emit(peers_mesh* m, const uint32_t* q, bool tri_pair) {
  uint32_t* idx = m->indices + m->index_count;
  if (tri_pair) {
    uint32_t t[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
    memcpy(idx, t, sizeof(t));
    m->face_sizes[m->face_count++] = 3;
    m->face_sizes[m->face_count++] = 3;
    m->index_count += 6;
  } else {
    memcpy(idx, q, 4 * sizeof(uint32_t));
    m->face_sizes[m->face_count++] = 4;
    m->index_count += 4;
  }
}

static double fan_volume(const peers_mesh* m) {
  double v = 0.0;
  for (uint32_t f = 0, first = 0; f < m->face_count; first += m->face_sizes[f++]) {
    for (uint32_t k = 1; k + 1 < m->face_sizes[f]; k++) {
      uint32_t t[3] = {m->indices[first], m->indices[first + k], m->indices[first + k + 1]};
      v += peers_triangle_volume(m->positions, t, 1);
    }
  }
  return v;
}

bool peers_mesh_make(const char* kind, uint32_t faces, peers_mesh* m) {
  uint32_t quads = quads_for(kind, faces);
  uint32_t rings = (uint32_t)sqrt((double)quads) < 3 ? 3 : (uint32_t)sqrt((double)quads);
  uint32_t segs = quads / rings < 3 ? 3 : quads / rings;
  demo_shape s;
  if (!demo_torus(rings, segs, &s)) return false;
  *m = (peers_mesh){.kind = kind, .vertex_count = s.vertex_count, .positions = s.positions};
  m->indices = malloc(sizeof(uint32_t) * 6 * (size_t)s.quad_count);
  m->face_sizes = malloc(2 * (size_t)s.quad_count);
  if (!m->indices || !m->face_sizes) {
    demo_shape_free(&s);
    return false;
  }
  for (uint32_t q = 0; q < s.quad_count; q++)
    emit(m, s.indices + 4 * q, split(kind, q / segs, q % segs));
  free(s.normals);
  free(s.indices);
  m->volume = fan_volume(m);
  return true;
}

void peers_mesh_free(peers_mesh* m) {
  free(m->positions);
  free(m->indices);
  free(m->face_sizes);
  *m = (peers_mesh){0};
}

void peers_mesh_deform(const peers_mesh* m, uint32_t frame, float* out) {
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    const float* p = m->positions + 3 * (size_t)v;
    float* o = out + 3 * (size_t)v;
    o[0] = p[0];
    o[1] = p[1];
    o[2] = p[2] + 0.02f * sinf(3.0f * p[0] + 0.7f * (float)(frame + 1));
  }
}

double peers_triangle_volume(const float* p, const uint32_t* idx, uint32_t triangles) {
  double v = 0.0;
  for (uint32_t t = 0; t < triangles; t++) {
    const float *a = p + 3 * (size_t)idx[3 * t], *b = p + 3 * (size_t)idx[3 * t + 1],
                *c = p + 3 * (size_t)idx[3 * t + 2];
    v += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
         (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
         (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v / 6.0;
}

double peers_thread_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}
