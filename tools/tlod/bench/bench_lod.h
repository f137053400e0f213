/* tlod bench suites for the scheduler (bench_scheduler.c, bench_table1.c)
 * and the model set-up they share with the gl suite (bench_scene.c). */
#ifndef TLOD_TOOLS_BENCH_LOD_H
#define TLOD_TOOLS_BENCH_LOD_H

#include <stdio.h>

#include "cli.h"
#include "common/scene_setup.h"
#include "tesslod/lod.h"

typedef struct bench_lod_options {
  const uint32_t* threads;
  uint32_t thread_count;
  uint32_t frames;
  const char* const* inputs; /* table1 models */
  uint32_t input_count;
  const char* const* meshes; /* scheduler meshes */
  uint32_t mesh_count;
} bench_lod_options;

/* A loaded model with its mesh, surface and patterns, for the suites. */
typedef struct bench_scene {
  tlod_context* ctx;
  scene_setup setup;
} bench_scene;

/* threads 0 == all CPUs; PN splits quads. */
int bench_scene_load(const char* in, uint32_t threads, tlod_surface_type type, uint32_t max_level, bench_scene* s);
void bench_scene_free(bench_scene* s);
/* A camera on a circle round the mesh at the given angle (radians), framing
 * it at distance_scale times the framing distance; 45 degrees. */
void bench_orbit_view(const tlod_mesh* mesh, float angle, float distance_scale, uint32_t w, uint32_t h,
                      tlod_view_desc* v);

/* The scheduler suite's refining camera on demo:torus-NxM at ring angle
 * `angle` (radians): levels 0-6, contours and culling in one view. */
void bench_refine_view(float angle, uint32_t w, uint32_t h, tlod_view_desc* v);

/* Scheduler CPU and wall time per frame on o->meshes for each thread count,
 * refining cameras moving and still (bench_scheduler.c); rep gets the cases
 * and scheduler_1m_ms. */
struct bench_report;
int bench_scheduler(const bench_lod_options* o, struct bench_report* rep, FILE* csv);
/* Schwarz et al.'s Table 1: base / adaptive / uniform triangles at 1600x1144,
 * 0.5 px, PN; rep gets the strip overhead (HYBRID, worst scene). */
int bench_table1(const bench_lod_options* o, struct bench_report* rep, FILE* csv);

#endif
