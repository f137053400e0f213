/* export_internal.h -- plumbing shared by the writers (private to tools/import/).
 * Owned by the import/export layer: the output file with a sticky write
 * error, a byte sink (raw or base64), a growable JSON text, and the scene
 * model the glTF writer takes (a single mesh is a one-node scene). */
#ifndef TESSLOD_TOOLS_EXPORT_INTERNAL_H
#define TESSLOD_TOOLS_EXPORT_INTERNAL_H

#include <stdbool.h>
#include <stdio.h>

#include "import_internal.h"

#ifndef TLOD_IMPORT_NONE
#define TLOD_IMPORT_NONE UINT32_MAX
#endif

typedef struct _exp_job {
  const char* path;
  const char* name; /* for messages */
  char* error;
  size_t error_size;
  FILE* file;
  bool write_failed; /* sticky: checked once at the end */
} _exp_job;

typedef enum { _EXP_OBJ, _EXP_PLY, _EXP_GLTF, _EXP_GLB, _EXP_UNKNOWN } _exp_format;

_exp_format _exp_format_of(const char* path);
/* A job for path ("" error; name = the file name without folders). */
_exp_job _exp_job_for(const char* path, char* error, size_t error_size);
tlod_result _exp_fail(_exp_job* job, tlod_result result, const char* fmt, ...) _TLOD_IMPORT_PRINTF(3, 4);
void _exp_write(_exp_job* job, const void* data, size_t size);
void _exp_printf(_exp_job* job, const char* fmt, ...) _TLOD_IMPORT_PRINTF(2, 3);
void _exp_put_u32(unsigned char* p, uint32_t v);
uint32_t _exp_float_bits(float f);

/* A byte stream into the file, raw or base64, fed in small pieces. */
typedef struct _exp_sink {
  _exp_job* job;
  bool base64;
  unsigned char carry[3];
  size_t carried;
  unsigned char buf[65536];
  size_t used;
} _exp_sink;

void _exp_sink_put(_exp_sink* s, const unsigned char* p, size_t n);
void _exp_sink_u32(_exp_sink* s, uint32_t v);
/* Ends a base64 run (pads it) and flushes. */
void _exp_sink_end(_exp_sink* s);

/* A growable string for JSON (it holds no vertex data). */
typedef struct _exp_text {
  char* s;
  size_t len, cap;
  bool failed;
} _exp_text;

void _exp_text_add(_exp_text* t, const char* fmt, ...) _TLOD_IMPORT_PRINTF(2, 3);
/* A JSON string: quotes, escapes, bytes of broken UTF-8 as '?'. */
void _exp_text_string(_exp_text* t, const char* s, size_t max_len);

/* Attribute a of vertex v (components floats). */
static inline const float* _exp_attr_at(const tlod_export_attribute* a, uint32_t v) {
  const size_t stride = a->stride ? a->stride : 4u * a->components;
  return (const float*)(const void*)((const char*)a->data + stride * v);
}
/* The attribute called name, or NULL. */
const tlod_export_attribute* _exp_find_attr(const tlod_export_mesh* m, const char* name);
tlod_result _exp_check_mesh(_exp_job* job, const tlod_export_mesh* m, const char* what);

/* True when source's parts are already in world space (imported without
 * keep_scene): some part names a node, and the scene is not the one
 * identity node of an OBJ/PLY import (where both spaces are the same). */
bool _exp_flattened(const tlod_import_result* r);

/* OBJ and PLY of one mesh. */
void _exp_obj(_exp_job* job, const tlod_export_mesh* m);
void _exp_ply(_exp_job* job, _exp_sink* s, const tlod_export_mesh* m);

/* One glTF mesh of the output: prims [first, first + count) of the scene. */
typedef struct _exp_gltf_mesh {
  const char* name;   /* may be NULL */
  const char* suffix; /* "@node" of a per-node copy, or NULL */
  uint32_t first, count;
} _exp_gltf_mesh;

typedef struct _exp_prim {
  const tlod_export_mesh* mesh;
  uint32_t material; /* TLOD_IMPORT_NONE: none */
} _exp_prim;

/* What the glTF writer writes. source gives nodes (node_count of them, with
 * node_mesh[n] the output mesh of node n or TLOD_IMPORT_NONE), materials,
 * textures and images; NULL source: one unnamed root node, mesh 0. */
typedef struct _exp_scene {
  const tlod_import_result* source;
  uint32_t node_count;
  const uint32_t* node_mesh;
  uint32_t mesh_count;
  const _exp_gltf_mesh* meshes;
  uint32_t prim_count;
  const _exp_prim* prims;
} _exp_scene;

tlod_result _exp_gltf(_exp_job* job, _exp_sink* s, const _exp_scene* scene, bool glb);

/* Writes through the atomic file writer; write(job, sink, user) fills it. */
typedef tlod_result (*_exp_body)(_exp_job* job, _exp_sink* s, const void* user);
tlod_result _exp_write_atomic(_exp_job* job, _exp_body body, const void* user);

#endif
