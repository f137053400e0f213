/* Input meshes of the tlod commands: a file through the importer or a
 * built-in demo mesh, as plain arrays ready for tlod_mesh_create. */
#ifndef TLOD_TOOLS_MESH_LOAD_H
#define TLOD_TOOLS_MESH_LOAD_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/core.h"

/* A mesh as loaded from a file or a built-in demo. */
typedef struct cli_mesh {
  char name[256];
  uint32_t vertex_count;
  float* positions;
  float* normals; /* NULL: none given */
  uint32_t index_count;
  uint32_t* indices;
  uint32_t face_count;
  uint8_t* face_sizes;        /* NULL: all triangles */
  uint32_t* face_source;      /* after cli_split_quads: loaded face of each face; NULL: identity */
  uint32_t source_face_count; /* faces as loaded */
  uint32_t quads_split;
  bool has_color; /* base_color holds the file's first part colour */
  float base_color[4];
  char warnings[1024];
} cli_mesh;

/* Loads IN: a file (.gltf .glb .obj .ply) or "demo:NAME". */
int cli_load(const char* in, cli_mesh* out);
/* Splits every quad into two triangles (PN triangles need triangles). */
int cli_split_quads(cli_mesh* m);
void cli_mesh_free(cli_mesh* m);
/* Names of the built-in demo meshes, for --help. */
const char* cli_demo_names(void);
/* "demo:NAME" without the prefix into m (see cli_demo_names). */
int cli_load_demo(const char* name, cli_mesh* m);

/* Creates a core mesh from a loaded one; prints the core's message on failure. */
int cli_create_mesh(tlod_context* ctx, const cli_mesh* m, tlod_normal_mode normals, float crease_deg, tlod_mesh** out);

#endif
