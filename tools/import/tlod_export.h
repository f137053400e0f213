/*
 * tlod_export.h -- mesh and scene export for the `tlod` tool (module tesslod::import)
 * Owned by the import/export layer (tools/import/). Included by tlod_import.h;
 * include that header, not this one.
 *
 * WHAT IT DOES
 *   tlod_export_file() writes one triangle mesh with its attributes;
 *   tlod_export_scene_file() writes tessellated parts with the scene of the
 *   import they came from (nodes, meshes, materials, textures, images).
 *   Formats, from the extension (case-insensitive):
 *     .obj   v, vn, vt (TEXCOORD_0 with v flipped back to OBJ's bottom-left
 *            origin: v = 1 - v', the inverse of the importer's flip), faces
 *            v/vt/vn; other attributes are not written;
 *     .ply   binary little endian: x y z, nx ny nz, u v (float, TEXCOORD_0
 *            as it is, as the importer reads PLY u v), red green blue alpha (uchar,
 *            COLOR_0 x 255 rounded, clamped to 0..255; 3 components: alpha
 *            255); other attributes are not written;
 *     .gltf  one buffer embedded as a base64 data URI; images embedded as
 *            data URIs too (one self-contained file: nothing is written
 *            beside it, so the atomic write below covers all of it);
 *     .glb   one BIN chunk holding the geometry and the images' bytes.
 *   glTF writes every attribute: "TEXCOORD_n" with 2 components, "COLOR_n"
 *   with 3 or 4 and "TANGENT" with 4 under their names, any other as the
 *   custom attribute "_NAME" (glTF requires the underscore; a name that
 *   already starts with one is kept; no name: "_ATTRIBUTE_a"). TANGENT xyz
 *   is renormalised and its w set to +-1 (interpolation shortens it; glTF
 *   requires unit tangents), NORMAL too when not unit within 1e-4 (a zero
 *   normal is written as 0,0,1). POSITION has min and max. Positions are bit-exact in every
 *   format ("%.9g" in text, float bits in binary), so a file reads back
 *   through tlod_import_file() with bitwise equal positions and indices.
 *
 * SCENES (tlod_export_scene_file)
 *   source is the import result the parts were made from, read with
 *   tlod_import_desc.keep_scene; parts[i] is source part i tessellated in
 *   its mesh's space (source->part_count entries).
 *   glTF/glb: source's nodes (names, hierarchy, TRS when source's T, R, S
 *   compose to its local matrix within 1e-6, else the matrix), meshes (one
 *   primitive per part, with its material), materials (baseColorFactor,
 *   baseColorTexture with its texCoord set, alphaMode, alphaCutoff for
 *   MASK, doubleSided; metallicFactor 0 since the import keeps no metal or
 *   roughness and tesslod shades base colour only), textures, samplers
 *   (valid GL enums only) and images re-embedded from their encoded bytes.
 *   An image without encoded bytes, or whose bytes are neither PNG nor JPEG,
 *   is left out and its textures lose their source. Skins, animations and
 *   cameras are not written (a caller that drops them says so).
 *   View-dependent exports: node_parts (scene desc) gives a node meshes of
 *   its own, for a mesh tessellated per instance.
 *   OBJ/PLY: every node's mesh parts transformed by the node's world matrix
 *   (normals by its inverse transpose, renormalised), merged into one mesh.
 *
 * DOES NOT
 *   - write quads (tessellated output is triangles), morph targets, skins,
 *     animations or extensions;
 *   - leave a partial file: output goes to a temporary name in the same
 *     folder, renamed when complete (platform/atomic_file).
 *
 * ERRORS
 *   TLOD_ERROR_INVALID_ARGUMENT (NULL path or mesh, index out of range,
 *   non-finite position, normal or attribute, attribute with 0 or more than
 *   4 components or NULL data, a source without keep_scene parts or with a
 *   node/mesh/material index out of range), TLOD_ERROR_IO (cannot write),
 *   TLOD_ERROR_UNSUPPORTED (extension; .glb larger than 4 GiB),
 *   TLOD_ERROR_OUT_OF_MEMORY. Messages: "<file>: <element>: <problem>".
 *   Allocation: malloc (tool layer). No global state.
 */
#ifndef TESSLOD_TOOLS_EXPORT_H
#define TESSLOD_TOOLS_EXPORT_H

#include <stddef.h>
#include <stdint.h>

#include "tesslod/core.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tlod_import_result;
struct tlod_import_image;

/* One per-vertex attribute to write. */
typedef struct tlod_export_attribute {
  const char* name;    /* "TEXCOORD_0", "COLOR_0", "TANGENT", ...; NULL: unnamed */
  uint32_t components; /* 1..4 */
  const float* data;   /* components floats per vertex, finite */
  uint32_t stride;     /* bytes between vertices; 0: tight (4 * components) */
} tlod_export_attribute;

/* A triangle mesh to write. */
typedef struct tlod_export_mesh {
  uint32_t vertex_count;   /* >= 1 */
  const float* positions;  /* xyz per vertex, finite */
  const float* normals;    /* xyz per vertex; may be NULL */
  uint32_t triangle_count; /* >= 1 */
  const uint32_t* indices; /* 3 per triangle, each < vertex_count */
  uint32_t attribute_count;
  const tlod_export_attribute* attributes; /* attribute_count entries; NULL when 0 */
} tlod_export_mesh;

/* Writes mesh to path (formats above). Returns TLOD_SUCCESS or an error of
 * the list above, with the message in error (NULL / 0: none). */
TLOD_API tlod_result tlod_export_file(const char* path, const tlod_export_mesh* mesh, char* error, size_t error_size);

/* Writes the parts with source's scene (SCENES above). */
TLOD_API tlod_result tlod_export_scene_file(const char* path, const struct tlod_import_result* source,
                                            const tlod_export_mesh* parts, char* error, size_t error_size);

/* The type an image of a scene source is written as: "image/png" or
 * "image/jpeg" from its encoded bytes' magic number (not its declared type),
 * or NULL when it is left out (no bytes, or another format). */
TLOD_API const char* tlod_export_image_mime(const struct tlod_import_image* image);

/* Everything of tlod_export_scene_file(), for view-dependent exports. */
typedef struct tlod_export_scene_desc {
  const struct tlod_import_result* source; /* required */
  const tlod_export_mesh* parts;           /* required: source->part_count meshes */
  /* Optional, node_count entries: non-NULL node_parts[n] replaces parts for
   * node n (its mesh's part_count meshes, in mesh space); glTF writes them as
   * a mesh of the node's own, named "<mesh>@<node>". */
  const tlod_export_mesh* const* node_parts;
} tlod_export_scene_desc;

TLOD_API tlod_result tlod_export_scene_file_desc(const char* path, const tlod_export_scene_desc* desc, char* error,
                                                 size_t error_size);

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_TOOLS_EXPORT_H */
