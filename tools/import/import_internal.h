/* import_internal.h -- plumbing shared by the importers (private to tools/import/).
 * Owned by the import/export layer. Plain C so the C++ shims and the C
 * readers share one result builder; no C++ type crosses this header. */
#ifndef TESSLOD_TOOLS_IMPORT_INTERNAL_H
#define TESSLOD_TOOLS_IMPORT_INTERNAL_H

#include <stdarg.h>

#include "tlod_import.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define _TLOD_IMPORT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define _TLOD_IMPORT_PRINTF(a, b)
#endif

/* Files larger than this are refused before reading (keeps a corrupt size
 * field or a wrong path from exhausting memory). */
#define _TLOD_IMPORT_MAX_FILE_BYTES ((size_t)1 << 31)
/* Output limits: past these an import fails cleanly instead of asking the
 * allocator for gigabytes (a corrupt count or a node instanced 10^6 times). */
#define _TLOD_IMPORT_MAX_VERTICES ((size_t)1 << 26)
#define _TLOD_IMPORT_MAX_INDICES ((size_t)1 << 28)
/* glTF accessors without a bufferView read as zeros: a count this large
 * there is corruption, not data. */
#define _TLOD_IMPORT_MAX_ZERO_FILLED ((size_t)1 << 20)

/* What a reader produced, in temporary memory; _tlod_import_finish copies it
 * into allocator memory. */
typedef struct _tlod_import_data {
  uint32_t vertex_count;
  const float* positions;
  const float* normals; /* NULL: no part had normals */
  uint32_t index_count;
  const uint32_t* indices;
  uint32_t face_count;
  const uint8_t* face_sizes; /* NULL: all triangles */
  uint32_t part_count;
  const tlod_import_part* parts;
  uint32_t polygons_triangulated;
  uint32_t strips_fans_converted;
  uint32_t primitives_skipped;
  const char* warnings; /* newline-separated, may be NULL */
  uint32_t warning_count;
  /* The scene (tlod_import.h), every pointer in temporary memory; deep-copied.
   * No mesh and no node: one mesh of all parts at one identity node. No
   * material: every part's material is TLOD_IMPORT_NONE. */
  uint32_t attribute_count;
  const tlod_import_attribute* attributes;
  const uint16_t* joints; /* NULL: none skinned */
  const float* weights;
  uint32_t mesh_count;
  const tlod_import_mesh* meshes;
  uint32_t node_count;
  const tlod_import_node* nodes;
  uint32_t material_count;
  const tlod_import_material* materials;
  uint32_t texture_count;
  const tlod_import_texture* textures;
  uint32_t image_count;
  const tlod_import_image* images;
  uint32_t animation_count;
  const tlod_import_animation* animations;
  uint32_t skin_count;
  const tlod_import_skin* skins;
  uint32_t weights_renormalised;
  /* VTK (issue 14), deep-copied like the rest: TLOD_FACE_NODES per face or NULL;
   * fields[i].data holds max(1, step_count) x vertex_count x components floats;
   * vtk NULL for other formats; step_positions step_count x vertex_count x 3. */
  const uint32_t* face_nodes;
  uint32_t field_count;
  const tlod_import_field* fields;
  const tlod_import_vtk_info* vtk;
  uint32_t step_count;
  const float* step_times;
  const float* step_positions;
} _tlod_import_data;

/* The import's memory budget (tlod_import_desc.memory_limit): every
 * allocation whose size comes from the file is taken from it first, so a
 * small file declaring huge counts fails before it costs memory. Bytes
 * taken are not given back when freed: the budget bounds what an import
 * allocates in all, which bounds its peak too. */
typedef struct _tlod_import_budget {
  size_t limit;      /* bytes */
  size_t used;       /* bytes taken so far */
  bool proportional; /* limit follows the input size (default rule): grows with external files */
} _tlod_import_budget;

/* The default limit for input_bytes of files (tlod_import.h). */
size_t _tlod_budget_default(size_t input_bytes);

/* An input file of bytes was found (main file, external buffer): the
 * default rule's limit grows by its share. */
void _tlod_budget_add_input(_tlod_import_budget* b, size_t bytes);

/* Largest external file the budget can still hold twice (the read and one
 * copy), at most _TLOD_IMPORT_MAX_FILE_BYTES. */
size_t _tlod_budget_file_limit(const _tlod_import_budget* b);

/* Takes bytes from the budget; false (nothing taken) when it would exceed the limit. */
bool _tlod_budget_take(_tlod_import_budget* b, size_t bytes);

/* Overflow-checked size arithmetic: false when the result does not fit size_t. */
static inline bool _tlod_size_mul(size_t a, size_t b, size_t* out) { return !__builtin_mul_overflow(a, b, out); }
static inline bool _tlod_size_add(size_t a, size_t b, size_t* out) { return !__builtin_add_overflow(a, b, out); }

/* Where a reader reports to: the caller's allocator, output and error buffer. */
typedef struct _tlod_import_job {
  const char* path;            /* as given */
  const char* name;            /* file name without folders, for messages */
  const char* folder;          /* where external references resolve ("" = cwd); NULL: refuse them (memory import) */
  const unsigned char* memory; /* non-NULL: the file's bytes (tlod_import_memory), path is only a name */
  size_t memory_size;
  tlod_allocator allocator; /* resolved: never NULL hooks */
  _tlod_import_budget* budget;
  tlod_import_result** out;
  char* error;
  size_t error_size;
  bool keep_scene;                                                  /* tlod_import_desc.keep_scene */
  void (*progress)(void* user, const char* stage, double fraction); /* tlod_import_desc.progress; NULL: none */
  void* progress_user;
} _tlod_import_job;

/* Copies d into a new result (allocator memory) and stores it in *job->out. */
tlod_result _tlod_import_finish(const _tlod_import_job* job, const _tlod_import_data* d);

/* Writes "<name>: <message>" to job->error and returns result. */
tlod_result _tlod_import_fail(const _tlod_import_job* job, tlod_result result, const char* fmt, ...)
    _TLOD_IMPORT_PRINTF(3, 4);

/* Reads a whole file into malloc memory (+1 zero byte past the end so text
 * parsers may stop on it; a memory import is copied). Takes its size from
 * the budget. Fails with TLOD_ERROR_IO naming the file. */
tlod_result _tlod_import_read_file(const _tlod_import_job* job, unsigned char** data, size_t* size);

/* The readers, one per format. */
tlod_result _tlod_import_gltf(const _tlod_import_job* job);
tlod_result _tlod_import_obj(const _tlod_import_job* job);
tlod_result _tlod_import_ply(const _tlod_import_job* job);
/* .vtk .vtu .vtp .pvtu .pvd .stl and numbered series (a '*' in the name): vtk_import.cpp
 * when built with TLOD_WITH_VTK, else TLOD_ERROR_UNSUPPORTED naming the build option. */
tlod_result _tlod_import_vtk(const _tlod_import_job* job);
/* True when path names one of the formats above (the dispatch's test). */
bool _tlod_is_vtk_path(const char* path);

/* Case-insensitive "does s end with suffix" (format from the extension). */
bool _tlod_str_ends_with_nocase(const char* s, const char* suffix);

#ifdef __cplusplus
}
#endif
#endif
