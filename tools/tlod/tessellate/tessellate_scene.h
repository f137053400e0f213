/* tlod tessellate -- scene mode: a .gltf/.glb output of a file input keeps
 * the file's scene. Each part (glTF primitive) becomes a core mesh, a
 * surface and a cpu tessellation in its mesh's space, written with the
 * nodes, materials, textures and images of the input.
 *   --level L:   every mesh tessellated once, whatever the nodes using it;
 *   with a camera: every instance (node x part) planned for its own view
 *     (the camera seen from the mesh's space through the node's world
 *     matrix); a mesh's first instance is written as the mesh itself, every
 *     further instance as a mesh of its own, "<mesh>@<node>", used by that
 *     node only. An instance fully culled is written at level 0. */
#ifndef TLOD_TOOLS_TESSELLATE_SCENE_H
#define TLOD_TOOLS_TESSELLATE_SCENE_H

#include <stdbool.h>

#include "tessellate_export.h"
#include "tessellate_options.h"

typedef struct tess_item {
  uint32_t part; /* the part tessellated */
  tlod_cpu_mesh* out;
  tess_export ex;
} tess_item;

typedef struct tess_scene {
  const tess_options* o;
  tlod_context* ctx;
  tlod_import_result* r;
  tlod_patterns* patterns;
  tlod_mesh** meshes;      /* per part */
  tlod_surface** surfaces; /* per part */
  tess_item* parts;        /* per part: its tessellation (camera: its mesh's first instance) */
  tess_item* copies;       /* camera mode: the further instances' parts */
  uint32_t copy_count;
  uint32_t* node_first; /* per node: its first copy, UINT32_MAX: none */
  uint32_t culled;      /* instances written at level 0 */
} tess_scene;

/* True when o asks for scene mode (.gltf/.glb output of a file input). */
bool tessellate_is_scene(const tess_options* o);
/* Runs scene mode: tessellate, write, report. */
int tessellate_scene(const tess_options* o);
/* Camera mode: every instance tessellated for its own view. */
int tessellate_instances(tess_scene* s);
/* Tessellates the surface of part p with draw list dl, or without one
 * uniformly at level, into *out. */
int tessellate_part(tess_scene* s, uint32_t p, const tlod_draw_list* dl, uint32_t level, tlod_cpu_mesh** out);

#endif
