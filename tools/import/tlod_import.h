/*
 * tlod_import.h -- scene import and mesh export for the `tlod` tool (module tesslod::import)
 * Owned by the import/export layer (tools/import/).
 *
 * WHAT IT DOES
 *   tlod_import_file() reads one mesh file into flat arrays that
 *   tlod_mesh_create() takes as they are:
 *     - glTF 2.0 (.gltf with embedded or external buffers, .glb): every
 *       triangle primitive of the default scene (scene 0 if none is set; no
 *       scenes: the root nodes; no nodes: every mesh), node transforms
 *       applied; TRIANGLE_STRIP and TRIANGLE_FAN converted to triangles;
 *       sparse accessors applied; u8/u16/u32 or no indices;
 *     - Wavefront OBJ: triangles and quads kept, larger polygons
 *       fan-triangulated, one output vertex per distinct (v, vn) pair;
 *     - PLY (ascii, binary little and big endian): vertex x y z [nx ny nz],
 *       face lists; triangles and quads kept, larger polygons fan-triangulated.
 *   tlod_export_file() writes a triangle mesh as OBJ, binary PLY, .gltf
 *   (one embedded base64 buffer) or .glb. Everything it writes reads back
 *   through tlod_import_file() with bitwise equal positions and indices.
 *
 * DOES NOT
 *   - validate mesh topology or repair normals (tlod_mesh_create() does);
 *   - read textures, skins, morph targets, animations or cameras (a skinned
 *     mesh comes in its bind pose);
 *   - trust the file: every offset, count and index is range-checked before
 *     it is read, and a malformed file gives an error naming the file and
 *     the element at fault, never a crash, a hang or unbounded memory;
 *   - decode images (glTF images are never decoded nor opened).
 *
 * SECURITY RULE (docs/security.md)
 *   A model file is untrusted input. An import
 *     - reads only files inside the model's folder: an external reference (glTF
 *       buffer URI, OBJ mtllib) is percent-decoded, refused if absolute or with
 *       a scheme ("/x", "file:", "http:"), resolved with symlinks (realpath)
 *       and refused unless the result lies inside the realpath of the model's
 *       folder; it is opened non-blocking and read only if fstat says it is a
 *       regular file (never a FIFO, device or socket), at most the remaining
 *       memory budget in size. A refusal names the reference as written in the
 *       file, never the size or the bytes of what it resolved to;
 *     - allocates at most its memory budget (tlod_import_desc.memory_limit):
 *       every size the file declares is checked against it, with overflow-
 *       checked arithmetic, before anything is allocated; past it the import
 *       fails with TLOD_ERROR_OUT_OF_MEMORY naming the element that asked;
 *     - refuses, before any parser sees them, JSON nested deeper than 256
 *       levels, GLB chunks that do not fit the file, and integer fields of
 *       glTF (offsets, strides, counts, indices into arrays) that are not
 *       non-negative JSON integers, and OBJ numbers whose exponent has
 *       more than 4 significant digits (tinyobjloader would overflow an int).
 *
 * STEP BY STEP
 *   1. char err[256];
 *      tlod_import_result* r = NULL;
 *      if (tlod_import_file("Duck.glb", NULL, &r, err, sizeof err) != TLOD_SUCCESS) puts(err);
 *   2. tlod_mesh_create(ctx, &(tlod_mesh_desc){ .positions = r->positions,
 *        .normals = r->normals, .vertex_count = r->vertex_count,
 *        .indices = r->indices, .index_count = r->index_count,
 *        .face_type = r->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
 *        .face_sizes = r->face_sizes, .face_count = r->face_count }, &mesh);
 *   3. tlod_import_free(r);
 *
 * THREADING, ALLOCATION, ERRORS
 *   No global state: calls on different files may run on different threads.
 *   The result and its arrays come from the given allocator (NULL: malloc),
 *   which the result keeps so that tlod_import_free() needs no arguments;
 *   temporary parsing memory comes from malloc / operator new, within the
 *   memory budget (which counts the result too). Errors are
 *   written to the caller's buffer (truncated to fit, always terminated;
 *   NULL or size 0: no message) as "<file>: <element>: <problem>".
 */
#ifndef TESSLOD_TOOLS_IMPORT_H
#define TESSLOD_TOOLS_IMPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "tesslod/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One imported piece: a glTF primitive instance (node x primitive), an OBJ
 * shape (o / g), or the whole PLY. Its faces and vertices are contiguous. */
typedef struct tlod_import_part {
  char name[64]; /* node, mesh or shape name; may be truncated */
  uint32_t first_face, face_count;
  uint32_t first_vertex, vertex_count;
  float base_color[4]; /* glTF baseColorFactor; OBJ Kd + d; default 1,1,1,1 */
  bool had_normals;    /* false: this part's normals are zero (core recomputes) */
} tlod_import_part;

#define TLOD_IMPORT_WARNINGS_SIZE 1024

typedef struct tlod_import_result {
  uint32_t vertex_count;
  float* positions; /* xyz, world space (node transforms applied) */
  /* xyz, or NULL when no part had normals; parts without normals are
   * zero-filled (core recomputes those). Normals of transformed glTF nodes
   * are renormalised; untransformed ones are passed through as stored. */
  float* normals;
  uint32_t index_count;
  uint32_t* indices;
  uint32_t face_count;
  uint8_t* face_sizes; /* NULL when every face is a triangle; else 3 or 4 per face */
  uint32_t part_count;
  tlod_import_part* parts;
  uint32_t polygons_triangulated;           /* OBJ/PLY faces with > 4 corners fan-triangulated */
  uint32_t strips_fans_converted;           /* glTF primitives in TRIANGLE_STRIP/FAN mode converted to triangles */
  uint32_t primitives_skipped;              /* glTF primitives left out (no POSITION, lines, points; see warnings) */
  uint32_t warning_count;                   /* warnings issued, also those that did not fit below */
  char warnings[TLOD_IMPORT_WARNINGS_SIZE]; /* human-readable, newline-separated, may be empty */
  tlod_allocator _allocator;                /* private: the allocator the arrays came from */
} tlod_import_result;

/* Memory budget, default rule: an import may allocate
 *   TLOD_IMPORT_MEMORY_BASE + TLOD_IMPORT_MEMORY_PER_INPUT_BYTE x (bytes of the
 *   file and of the external buffers it reads, at their real size),
 * at most TLOD_IMPORT_MEMORY_CAP. Allocations are counted in all, not at
 * their peak; parser-internal memory (tinygltf's model and JSON trees) is
 * counted by a documented estimate (docs/security.md). */
#define TLOD_IMPORT_MEMORY_BASE ((size_t)64 << 20)
#define TLOD_IMPORT_MEMORY_PER_INPUT_BYTE ((size_t)64)
#define TLOD_IMPORT_MEMORY_CAP ((size_t)8 << 30)

/* Options of an import; zero is the default for every field. */
typedef struct tlod_import_desc {
  tlod_allocator allocator; /* result memory; both hooks NULL: malloc/free */
  size_t memory_limit;      /* bytes the import may allocate in all; 0: the default rule above */
} tlod_import_desc;

/* Reads a mesh file; the format comes from the extension (.gltf .glb .obj
 * .ply, case-insensitive; anything else: TLOD_ERROR_UNSUPPORTED).
 *   path       file to read; external glTF buffers resolve relative to it
 *   allocator  for the result and its arrays; NULL (or both hooks NULL): malloc/free
 *   out        receives the result (free with tlod_import_free); NULL on failure
 *   error      receives "" on success, else a message naming the file and
 *              the element at fault; may be NULL
 * Returns TLOD_ERROR_IO (cannot read), TLOD_ERROR_PARSE (malformed file),
 * TLOD_ERROR_INVALID_MESH (index out of range, non-finite position),
 * TLOD_ERROR_UNSUPPORTED (format, extension or element not supported, e.g.
 * a glTF whose only primitives are lines), TLOD_ERROR_OUT_OF_MEMORY or
 * TLOD_ERROR_INVALID_ARGUMENT. */
TLOD_API tlod_result tlod_import_file(const char* path, const tlod_allocator* allocator, tlod_import_result** out,
                                      char* error, size_t error_size);

/* tlod_import_file() with options (desc NULL: all defaults). */
TLOD_API tlod_result tlod_import_file_desc(const char* path, const tlod_import_desc* desc, tlod_import_result** out,
                                           char* error, size_t error_size);

/* Reads a mesh from memory: name gives the format (its extension) and the
 * file name in messages; nothing is read from the file system, so an
 * external reference (glTF buffer URI, OBJ mtllib) fails the import with
 * TLOD_ERROR_IO naming it. data is not kept after the call. */
TLOD_API tlod_result tlod_import_memory(const char* name, const void* data, size_t size, const tlod_import_desc* desc,
                                        tlod_import_result** out, char* error, size_t error_size);

/* Frees a result and its arrays; NULL is a no-op. */
TLOD_API void tlod_import_free(tlod_import_result* r);

/* A triangle mesh to write. */
typedef struct tlod_export_mesh {
  uint32_t vertex_count;   /* >= 1 */
  const float* positions;  /* xyz per vertex, finite */
  const float* normals;    /* xyz per vertex; may be NULL */
  uint32_t triangle_count; /* >= 1 */
  const uint32_t* indices; /* 3 per triangle, each < vertex_count */
} tlod_export_mesh;

/* Writes mesh to path; the format comes from the extension: .obj, .ply
 * (binary little endian), .gltf (one embedded base64 buffer) or .glb
 * (case-insensitive; anything else: TLOD_ERROR_UNSUPPORTED). The file is
 * written under a temporary name in the same folder and renamed when
 * complete, so a failed write never leaves a partial file under path.
 * Returns TLOD_ERROR_INVALID_ARGUMENT (bad mesh: index out of range,
 * non-finite position), TLOD_ERROR_IO (cannot write) or
 * TLOD_ERROR_UNSUPPORTED (format; .glb larger than 4 GiB). */
TLOD_API tlod_result tlod_export_file(const char* path, const tlod_export_mesh* mesh, char* error, size_t error_size);

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_TOOLS_IMPORT_H */
