/* tlod bench --peers -- what the peers_*.c files share: the meshes both
 * libraries get (peers_mesh.c) and tesslod's side (peers_ours.c). */
#ifndef TLOD_TOOLS_BENCH_PEERS_INTERNAL_H
#define TLOD_TOOLS_BENCH_PEERS_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/cpu.h"

/* A closed torus of faces: "triangle" (every quad split), "quad", or "mixed"
 * (every other quad, checkerboard, split), about `faces` faces. */
typedef struct peers_mesh {
  const char* kind;
  uint32_t vertex_count, face_count, index_count;
  float* positions;
  uint32_t* indices;
  uint8_t* face_sizes;
  double volume; /* enclosed by the input faces (fans) */
} peers_mesh;

bool peers_mesh_make(const char* kind, uint32_t faces, peers_mesh* m);
void peers_mesh_free(peers_mesh* m);
/* Frame `frame` of the deforming case: z moved by a travelling wave. */
void peers_mesh_deform(const peers_mesh* m, uint32_t frame, float* out);
/* Volume enclosed by triangles (divergence theorem, double). */
double peers_triangle_volume(const float* positions, const uint32_t* indices, uint32_t triangles);
/* This thread's CPU time, ms. */
double peers_thread_ms(void);

/* tesslod on one thread: mesh, Phong surface, patterns, the output reused. */
typedef struct peers_ours {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_patterns* patterns;
  tlod_cpu_mesh* out;
  uint64_t heap_now, heap_peak; /* the context's allocations, bytes */
} peers_ours;

/* Mesh + surface (error tables as given) + patterns to level, timed: *ms the
 * thread CPU, *peak the allocator's high mark above what it held before. */
bool peers_ours_create(peers_ours* s, const peers_mesh* m, uint32_t level, tlod_error_tables tables, double* ms,
                       uint64_t* peak);
/* One frame: control (NULL: static) through tlod_mesh_update +
 * tlod_surface_refresh, then tlod_cpu_tessellate_into; the output vertices, 0 on failure. */
uint64_t peers_ours_evaluate(peers_ours* s, const float* control, uint32_t level, bool normals);
/* The largest distance of a mesh vertex to the surface at its corner parameter. */
double peers_ours_vertex_distance(const peers_ours* s);
void peers_ours_destroy(peers_ours* s);

#endif
