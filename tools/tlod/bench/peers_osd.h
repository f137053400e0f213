/* tlod bench --peers -- OpenSubdiv 3.5 behind a C API (peers_osd.cpp, C++17,
 * built only with TLOD_WITH_OPENSUBDIV). One object per mesh, level and path:
 * Loop when every face is a triangle, else Catmull-Clark; every allocation is
 * OpenSubdiv's own (operator new), counted by the heap figures below. */
#ifndef TLOD_TOOLS_BENCH_PEERS_OSD_H
#define TLOD_TOOLS_BENCH_PEERS_OSD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct peers_osd peers_osd;

typedef struct peers_osd_desc {
  const float* positions; /* xyz per vertex */
  uint32_t vertex_count;
  const uint32_t* indices; /* face_sizes[f] per face, one after the other */
  const uint8_t* face_sizes;
  uint32_t face_count;
  uint32_t level; /* 1..4: the uniform level, or the limit samples' grid 2^level per face */
  /* false: the positions path (topology refined uniformly to level,
   * Far::PrimvarRefiner per frame); true: the limit path (adaptive refiner,
   * Far::PatchTable, patch coordinates of the samples, Osd::CpuEvaluator). */
  bool limit;
} peers_osd_desc;

/* "3.5.0" (OpenSubdiv's version.h). */
const char* peers_osd_version(void);
/* The topology and tables of d (the preprocessing); NULL with err set. */
peers_osd* peers_osd_create(const peers_osd_desc* d, char* err, size_t err_size);
void peers_osd_destroy(peers_osd* o);
/* "loop" or "catmull-clark". */
const char* peers_osd_scheme(const peers_osd* o);
/* Output vertices of one evaluation: the level's vertices (positions path)
 * or the limit samples (limit path, half-open grids per ptex face). */
uint64_t peers_osd_output_count(const peers_osd* o);
/* One frame from control points (vertex_count xyz). Positions path:
 * PrimvarRefiner level by level. Limit path: deforming refines the control
 * points and computes the local points again first (static: the points of the
 * last call); then the limit positions and unit normals of every sample. */
void peers_osd_evaluate(peers_osd* o, const float* control, bool deforming);
/* After an evaluation: the largest distance from an input vertex to its point
 * on the surface (positions path: its level-`level` descendant; limit path:
 * its limit point) and the volume of the level's faces (positions path; the
 * limit path answers 0). */
double peers_osd_vertex_distance(const peers_osd* o, const float* input);
double peers_osd_volume(const peers_osd* o);

/* The heap of operator new (every C++ allocation in the process), bytes in
 * use now and the peak since the last reset. */
uint64_t peers_osd_heap_now(void);
uint64_t peers_osd_heap_peak(void);
void peers_osd_heap_reset_peak(void);

#ifdef __cplusplus
}
#endif

#endif
