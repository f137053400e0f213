/* The one scene set-up of tlod tessellate, play and bench: input (file or
 * demo) -> quads split for PN -> core mesh -> surface -> patterns, with the
 * time each step took. Errors are printed (cli_error) and name the input. */
#ifndef TLOD_TOOLS_SCENE_SETUP_H
#define TLOD_TOOLS_SCENE_SETUP_H

#include "field/field_select.h"
#include "mesh_load.h"
#include "tesslod/lod.h"

typedef struct scene_setup_desc {
  const char* input;          /* a .gltf .glb .obj .ply or VTK file (cli_load) or "demo:NAME" */
  const char* label;          /* the surface's label; NULL: input */
  tlod_surface_type surface;  /* PN splits quads into triangles; DEFAULT: auto (cli_resolve_surface) */
  tlod_alpha_mode alpha_mode; /* as tlod_surface_desc: default 0.75 everywhere */
  float alpha;                /* TLOD_ALPHA_GLOBAL: the Phong shape factor (0 is flat) */
  tlod_normal_mode normals;
  float crease_deg;           /* negative: the input's default (cli_resolve_crease) */
  const field_options* field; /* a result field as a 1-component attribute; NULL or no spec: none */
  bool split_quads;           /* split quads whatever the surface */
  uint32_t pattern_level;     /* finest level of the patterns; 0: make no patterns */
  /* Called on the loaded mesh before anything is made of it (moves it); may be NULL. */
  void (*place)(cli_mesh* m, const void* user);
  const void* place_user;
} scene_setup_desc;

typedef struct scene_setup {
  cli_mesh in;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_patterns* patterns;        /* NULL when pattern_level is 0 */
  tlod_surface_type surface_type; /* the type made (auto resolved) */
  float crease_deg;               /* the crease angle used */
  bool has_field;
  field_selection field;
  uint32_t field_attribute; /* the field's mesh attribute (has_field) */
  double load_ms, mesh_ms, surface_ms, patterns_ms;
} scene_setup;

/* The input alone: loaded, placed, quads split as the desc says. */
int scene_input_load(const scene_setup_desc* d, cli_mesh* out);
/* Everything of the desc in ctx; on failure out holds nothing (and an error was printed). */
int scene_setup_create(tlod_context* ctx, const scene_setup_desc* d, scene_setup* out);
/* Frees what create made; a zeroed setup is a no-op. */
void scene_setup_destroy(scene_setup* s);

#endif
