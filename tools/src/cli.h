/* Shared plumbing of the tlod commands: argument parsing, input loading,
 * timing and error reporting. */
#ifndef TLOD_TOOLS_CLI_H
#define TLOD_TOOLS_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "tesslod/core.h"

enum { CLI_OK = 0, CLI_FAILED = 1, CLI_USAGE = 2 };

/* Prints "tlod: error: ..." to stderr; returns code. */
int cli_error(int code, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

/* Parses a whole string as a number in [lo, hi]; false (with an error
 * printed naming the option) otherwise. */
bool cli_parse_float(const char* option, const char* text, double lo, double hi, float* out);
bool cli_parse_uint(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out);
/* Index of text in names (NULL-terminated), or -1 with an error printed. */
int cli_parse_enum(const char* option, const char* text, const char* const* names);
/* The value of an option that takes one: argv[*i + 1]; advances *i. */
const char* cli_value(int argc, char** argv, int* i);

/* A mesh as loaded from a file or a built-in demo, ready for tlod_mesh_create. */
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
  char warnings[1024];
} cli_mesh;

/* Loads IN: a file (.gltf .glb .obj .ply) or "demo:NAME". */
int cli_load(const char* in, cli_mesh* out);
/* Splits every quad into two triangles (PN triangles need triangles). */
int cli_split_quads(cli_mesh* m);
void cli_mesh_free(cli_mesh* m);
/* Names of the built-in demo meshes, for --help. */
const char* cli_demo_names(void);

double cli_now_ms(void);

/* Creates a core mesh from a loaded one; prints the core's message on failure. */
int cli_create_mesh(tlod_context* ctx, const cli_mesh* m, tlod_normal_mode normals, float crease_deg, tlod_mesh** out);
/* Writes a mesh's validation findings (and the counts) as text. */
/* At most limit of them (the mesh keeps the first TLOD_MAX_FINDINGS). */
void cli_print_findings(FILE* f, const tlod_mesh* mesh, uint32_t limit);
#endif
