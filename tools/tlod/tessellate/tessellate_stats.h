/* tlod tessellate -- the --stats file (JSON). */
#ifndef TLOD_TOOLS_TESSELLATE_STATS_H
#define TLOD_TOOLS_TESSELLATE_STATS_H

#include <stdbool.h>
#include <stddef.h>

#include "common/mesh_load.h"
#include "tessellate_options.h"
#include "tesslod/cpu.h"

typedef struct tess_timings {
  double load, mesh, surface, patterns, tessellate, write, total;
} tess_timings;

typedef struct tess_stats {
  const tess_options* o;
  const cli_mesh* in;
  const tlod_mesh* mesh;
  const tlod_cpu_mesh* out;
  const tlod_draw_list* dl; /* adaptive mode; NULL: uniform */
  const tess_timings* t;
} tess_stats;

/* Scene mode (tessellate_scene.h): what was read and written, summed. */
typedef struct tess_scene_stats {
  const tess_options* o;
  uint32_t parts, meshes, nodes, materials, textures, images, copies, culled;
  uint64_t vertices, triangles;
  double total_ms;
} tess_scene_stats;

/* Writes o->stats of scene mode (atomically); false with one line in error. */
bool tessellate_write_scene_stats(const tess_scene_stats* s, char* error, size_t error_size);

/* Writes o->stats (atomically); false with one line in error. */
bool tessellate_write_stats(const tess_stats* s, char* error, size_t error_size);

#endif
