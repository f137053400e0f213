/* Input meshes of the tlod commands: a file through the importer or a
 * built-in demo mesh, as plain arrays ready for tlod_mesh_create, with the
 * import's vertex attributes (TEXCOORD_0, COLOR_0, ...) and, for files, the
 * import result itself (parts, materials, textures, images, nodes).
 *
 * Two ways in:
 *   - cli_load(): one mesh in world space (a glTF scene flattened: every
 *     node x primitive placed), for commands that draw one object;
 *   - cli_load_scene() + cli_create_part_mesh(): the scene as the file has it
 *     (keep_scene: each glTF mesh once in mesh space, nodes instancing it),
 *     one core mesh per part, for commands that draw instances:
 *       tlod_import_result* r;
 *       if (cli_load_scene(path, &r) != CLI_OK) return CLI_FAILED;
 *       for (uint32_t p = 0; p < r->part_count; p++)
 *         cli_create_part_mesh(ctx, r, p, &(cli_part_options){0}, &meshes[p]);
 *       for each node n with r->nodes[n].mesh != TLOD_IMPORT_NONE: draw the
 *         parts meshes[r->meshes[mesh].first_part ..] with r->nodes[n].world;
 *       tlod_import_free(r);  (after the meshes: they copied what they need)
 */
#ifndef TLOD_TOOLS_MESH_LOAD_H
#define TLOD_TOOLS_MESH_LOAD_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/core.h"
#include "tlod_import.h"

/* A vertex attribute of a loaded mesh (owned: components floats per vertex). */
typedef struct cli_attribute {
  char name[32];
  uint32_t components;
  float* data;
} cli_attribute;

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
  /* Second-order nodes, TLOD_FACE_NODES per face (tlod_mesh_desc.face_nodes);
   * NULL: none (also after cli_split_quads: PN ignores nodes). */
  uint32_t* face_nodes;
  bool has_color; /* base_color holds the file's first part colour */
  float base_color[4];
  char warnings[1024];
  uint32_t attribute_count; /* 0..TLOD_MAX_ATTRIBUTES; kept through cli_split_quads (vertices unchanged) */
  cli_attribute attributes[TLOD_MAX_ATTRIBUTES];
  /* Files: the import result (parts, materials, textures, images, nodes;
   * its vertex arrays moved into this mesh, so NULL there); demos: NULL. */
  tlod_import_result* source;
} cli_mesh;

/* Loads IN: a file (.gltf .glb .obj .ply, and with VTK .vtk .vtu .vtp
 * .pvtu .pvd .stl or a numbered series) or "demo:NAME". Long VTK imports
 * show their progress on a terminal (stderr). */
int cli_load(const char* in, cli_mesh* out);
/* true when m came from a VTK file (m->source->vtk): its defaults differ
 * (--surface auto, the crease angle CLI_VTK_CREASE_DEG). */
bool cli_mesh_is_vtk(const cli_mesh* m);
/* The crease angle VTK meshes get when none is given: machined parts keep
 * their feature edges (a box's 90 and a chamfer's 45 degrees) sharp, while
 * coarse curved walls (a cylinder of 10 or more elements round, 36 degrees
 * apart or less) stay smooth (docs/play.md, "VTK input"). */
#define CLI_VTK_CREASE_DEG 40.0f
/* --surface auto (TLOD_SURFACE_DEFAULT) resolved for m: QUADRATIC when it
 * has second-order faces, else PHONG; a type asked for stays as it is. */
tlod_surface_type cli_resolve_surface(tlod_surface_type asked, const cli_mesh* m);
/* --crease not given (negative): CLI_VTK_CREASE_DEG for VTK meshes, else 0. */
float cli_resolve_crease(float asked, const cli_mesh* m);
/* Splits every quad into two triangles (PN triangles need triangles). */
int cli_split_quads(cli_mesh* m);
void cli_mesh_free(cli_mesh* m);
/* Import progress on a terminal (stderr) for d; end clears the line. */
void cli_progress_hook(tlod_import_desc* d);
void cli_progress_end(const tlod_import_desc* d);
/* Names of the built-in demo meshes, for --help. */
const char* cli_demo_names(void);
/* "demo:NAME" without the prefix into m (see cli_demo_names). */
int cli_load_demo(const char* name, cli_mesh* m);

/* Creates a core mesh from a loaded one, with its attributes; prints the
 * core's message on failure. */
int cli_create_mesh(tlod_context* ctx, const cli_mesh* m, tlod_normal_mode normals, float crease_deg, tlod_mesh** out);
/* Appends a 1-component attribute (values copied, vertex_count floats):
 * its index, or UINT32_MAX (printed) when m has TLOD_MAX_ATTRIBUTES already. */
uint32_t cli_add_scalar_attribute(cli_mesh* m, const char* name, const float* values);

/* Reads IN (.gltf .glb .obj .ply; not demo:) with keep_scene: parts in mesh
 * space, nodes with world matrices. Warnings stay in (*out)->warnings.
 * CLI_OK, or CLI_FAILED with the error printed (and *out NULL). Free with
 * tlod_import_free(). */
int cli_load_scene(const char* in, tlod_import_result** out);

/* How a part becomes a core mesh; zero: the tools' defaults. */
typedef struct cli_part_options {
  tlod_normal_mode normals; /* default TLOD_NORMALS_KEEP */
  float crease_deg;
  bool split_quads; /* true for PN surfaces */
} cli_part_options;

/* Part `part` of r as a cli_mesh of its own (copies: vertices renumbered
 * from 0, attributes included, name: the part's, or "part N"); quads split if
 * asked. CLI_FAILED (printed) when the part's indices leave its vertices. */
int cli_load_part(const tlod_import_result* r, uint32_t part, const cli_part_options* o, cli_mesh* out);

/* cli_load_part() then cli_create_mesh(): the core mesh of one part. */
int cli_create_part_mesh(tlod_context* ctx, const tlod_import_result* r, uint32_t part, const cli_part_options* o,
                         tlod_mesh** out);

#endif
