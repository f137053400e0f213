/* The built-in demo meshes, compiled into tlod so it runs with no files. */
#ifndef TLOD_TOOLS_DEMO_SCENE_H
#define TLOD_TOOLS_DEMO_SCENE_H

#include <stdint.h>

typedef struct tlod_demo_mesh {
  const char* name;
  uint32_t vertex_count;
  const float* positions;
  uint32_t index_count;
  const uint32_t* indices;
  uint32_t face_count;
  const uint8_t* face_sizes; /* 3 or 4 */
} tlod_demo_mesh;

/* The VTK cow (VTK BSD-3 licence, see tools/data/LICENSE-cow.txt): a real,
 * closed, mixed triangle/quad model. Generated at build time from
 * tools/data/cow.vtp by tools/data/embed_vtp.py. */
extern const tlod_demo_mesh tlod_demo_cow;

#endif
