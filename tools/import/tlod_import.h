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
 *       fan-triangulated, one output vertex per distinct (v, vt, vn);
 *     - PLY (ascii, binary little and big endian): vertex x y z [nx ny nz],
 *       face lists; triangles and quads kept, larger polygons fan-triangulated;
 *     - VTK (issue 14, docs/vtk.md; needs a build with TLOD_WITH_VTK, else
 *       TLOD_ERROR_UNSUPPORTED "<file>: .vtu files need VTK: this build has
 *       TLOD_WITH_VTK=OFF"): legacy .vtk (unstructured grid, polydata,
 *       structured and rectilinear grids, structured points), .vtu, .vtp,
 *       .pvtu (pieces merged, bitwise equal points welded), .stl (VTK reads
 *       the file by its path: not from memory), and time series: .pvd, or
 *       numbered files named with a '*' ("run_*.vtu": the folder's files with
 *       digits there, by number). Volume cells (tetra, hexahedron, wedge,
 *       pyramid, voxel and their second-order kinds: 10-node tetra, 20/24/27-
 *       node hexahedron, 12/15/18-node wedge, 13-node pyramid) become their
 *       boundary: faces keyed by sorted corners, used once = boundary, twice =
 *       interior (dropped), more = non-manifold (kept once, a warning); each
 *       cell oriented by its signed volume so faces point out even for
 *       inverted cells (vtk->cells_reoriented). A linear cell with repeated
 *       point ids (a hexahedron written for a wedge, pyramid or tetra; a quad
 *       for a triangle) is the solid it collapses to: each face's repeated
 *       consecutive corners merged, faces left with < 3 corners dropped
 *       (vtk->cells_collapsed); collapsed flat (no volume) or second-order
 *       with repeated nodes: dropped (vtk->degenerate_cells). 2D cells are
 *       kept (quadratic triangle/quad, biquadratic quad too; polygons over 4 corners fan-
 *       triangulated, strips converted); quads stay quads. Second-order faces
 *       give face_nodes (TLOD_FACE_NODES per face: mid-edge node of edge e from
 *       corner e to e+1, centre of a 9-node face). Vertex and line cells are
 *       ignored (counted). Only points used by a kept face or node become
 *       vertices (file order). No normals (core computes them). Point data
 *       and cell data (averaged to points) become fields[], "NAME [UNITS]" /
 *       "NAME (UNITS)" split into name and units. Refused, naming the cell,
 *       point, array or tuple: unsupported cell types (polyhedron, prisms,
 *       Lagrange, Bezier, ...: "cell 17 (polyhedron): unsupported cell type
 *       42"), a cell with the wrong point count or a point id out of range,
 *       non-finite coordinates, an array of the wrong tuple count or with a
 *       non-finite value, a series whose steps differ in cells. VTK's own
 *       errors become the one message ("<file>: VTK: ..."); nothing is printed.
 *   Besides geometry (issue 11, "real assets"):
 *     - attributes[]: glTF TEXCOORD_0, TEXCOORD_1 (float or normalised u8/u16),
 *       COLOR_0 (VEC3 gets alpha 1, VEC4; float or normalised u8/u16) and
 *       TANGENT (float VEC4); OBJ vt as "TEXCOORD_0" with v flipped to glTF's
 *       top-left origin (v' = 1 - v; a corner without vt gets 0, 0); PLY
 *       u v / s t / texture_u texture_v as "TEXCOORD_0" (as stored) and red
 *       green blue [alpha] as "COLOR_0" (integers / their type's maximum,
 *       uchar / 255). An attribute covers every vertex of the result: parts
 *       without it hold zeros (COLOR_0: ones). A glTF layout the spec does not
 *       allow for these is a warning (attribute ignored).
 *     - joints/weights: glTF JOINTS_0 (u8/u16) and WEIGHTS_0 (float or
 *       normalised u8/u16), 4 per vertex; weights summing within 2e-2 of 1 are
 *       renormalised (counted in weights_renormalised and a warning).
 *     - meshes[], nodes[] (glTF: every node of the file, same indices, with
 *       parent, TRS, local and rest-pose world matrices; a node given by a
 *       matrix gets its decomposition as TRS), materials[], textures[],
 *       images[] (same indices as the file), animations[] (translation,
 *       rotation, scale channels; STEP, LINEAR, CUBICSPLINE), skins[]
 *       (inverse bind matrices, identity when absent). OBJ/PLY: one mesh of
 *       every part at one identity node; OBJ materials from mtllib (Kd, d;
 *       d < 1: BLEND; map_Kd: a texture whose image is read and decoded; OBJ
 *       materials are double-sided).
 *     - keep_scene (tlod_import_desc): each glTF mesh's primitives once, in
 *       mesh space (positions bitwise as stored), meshes[i] naming its parts,
 *       parts' node TLOD_IMPORT_NONE; the caller instances them with nodes[].
 *       Without it (flattened, as before): one part per node x primitive in
 *       world space, part.node the node, meshes[i] naming the parts of the
 *       mesh's first instance (part_count 0 if never instanced).
 *     - images: the bytes of every image are kept (encoded, for re-export);
 *       those some material uses as its base colour texture are decoded to
 *       RGBA8 (libpng, libjpeg-turbo; docs/security.md section 5).
 *   tlod_export_file() writes a triangle mesh as OBJ, binary PLY, .gltf
 *   (one embedded base64 buffer) or .glb. Everything it writes reads back
 *   through tlod_import_file() with bitwise equal positions and indices.
 *
 *   Refused (an error naming the accessor or node): a node graph that is not
 *   a forest; a JOINTS_0 index at or past the joint count of a skin the mesh
 *   is drawn with; a negative or non-finite weight, or weights summing more
 *   than 2e-2 away from 1; an inverse bind matrix that is not finite or not
 *   invertible (|det| below 1e-6 x the product of its column lengths); an
 *   animation whose key times are not finite and strictly increasing, whose
 *   value count does not match its keys x (1 or 3 for CUBICSPLINE), or whose
 *   channel targets a node that does not exist.
 *
 * DOES NOT
 *   - validate mesh topology or repair normals (tlod_mesh_create() does);
 *   - pose skins or sample animations (a skinned mesh comes in its bind pose;
 *     flattened mode warns about it, keep_scene does not: the caller animates);
 *   - read morph targets (a warning names the mesh; a "weights" animation
 *     channel is a warning "morph target animation ignored"), cameras, or
 *     material inputs besides base colour, alpha and double-sidedness;
 *   - decode images other than base colour ones, or images past
 *     TLOD_IMPORT_MAX_IMAGE_PIXELS or the memory budget: a missing, refused
 *     or undecodable image is a warning naming it, its rgba is NULL, and the
 *     model still loads;
 *   - trust the file: every offset, count and index is range-checked before
 *     it is read, and a malformed file gives an error naming the file and
 *     the element at fault, never a crash, a hang or unbounded memory.
 *
 * SECURITY RULE (docs/security.md)
 *   A model file is untrusted input. An import
 *     - reads only files inside the model's folder: an external reference (glTF
 *       buffer or image URI, OBJ mtllib or map_Kd) is percent-decoded, refused if absolute or with
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
 *       more than 4 significant digits (tinyobjloader would overflow an int);
 *     - for VTK files, before VTK allocates: every count a legacy file
 *       declares (POINTS, CELLS, data arrays ...) against the bytes left in
 *       the file and the budget, paired counts that disagree (CELL_TYPES vs
 *       CELLS, POINT_DATA vs POINTS), XML Piece/DataArray counts against the
 *       budget, a binary STL's triangle count against its size; VTK is given
 *       bytes we read, never a path a file names (pieces, steps: the folder
 *       rule above).
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

/* One imported piece: a glTF primitive instance (node x primitive; with
 * keep_scene: one per primitive of each mesh, in mesh space), an OBJ shape
 * (o / g; its material is that of its first face), or the whole PLY. Its
 * faces and vertices are contiguous. */
typedef struct tlod_import_part {
  char name[64]; /* node, mesh or shape name; may be truncated */
  uint32_t first_face, face_count;
  uint32_t first_vertex, vertex_count;
  float base_color[4]; /* glTF baseColorFactor; OBJ Kd + d; default 1,1,1,1 */
  bool had_normals;    /* false: this part's normals are zero (core recomputes) */
  uint32_t mesh;       /* index into meshes[] */
  uint32_t material;   /* index into materials[]; UINT32_MAX: none */
  uint32_t node;       /* flattened mode: the node it was instanced at; keep_scene: UINT32_MAX */
} tlod_import_part;

#define TLOD_IMPORT_NONE UINT32_MAX
#define TLOD_IMPORT_MAX_ATTRIBUTES 8
/* Decoded images larger than this many pixels are refused (a warning), before anything is allocated. */
#define TLOD_IMPORT_MAX_IMAGE_PIXELS ((uint64_t)64 << 20)

/* A vertex attribute besides position and normal, for ALL vertices of the
 * result: parts without it hold zeros (COLOR_0: ones). */
typedef struct tlod_import_attribute {
  char name[32];       /* "TEXCOORD_0", "TEXCOORD_1", "COLOR_0", "TANGENT" */
  uint32_t components; /* TEXCOORD 2, COLOR 4 (vec3 colours get alpha 1), TANGENT 4 (xyz, w = handedness) */
  float* data;         /* components floats per vertex (normalised integers converted to float) */
} tlod_import_attribute;

/* A glTF mesh (OBJ/PLY: the one mesh): its parts are contiguous. */
typedef struct tlod_import_mesh {
  char name[64];
  uint32_t first_part, part_count;
} tlod_import_mesh;

/* A glTF node (OBJ/PLY: one node holding the one mesh), rest pose. */
typedef struct tlod_import_node {
  char name[64];
  uint32_t parent, mesh, skin; /* TLOD_IMPORT_NONE: none */
  float translation[3];
  float rotation[4]; /* unit quaternion x y z w */
  float scale[3];    /* TRS as in the file; a node given by matrix: decomposed (exact for T*R*S matrices) */
  float local[16];   /* column-major: the file's matrix, or T * R * S */
  float world[16];   /* column-major: parent's world * local */
} tlod_import_node;

typedef enum tlod_import_alpha_mode {
  TLOD_IMPORT_ALPHA_OPAQUE = 0,
  TLOD_IMPORT_ALPHA_MASK,
  TLOD_IMPORT_ALPHA_BLEND
} tlod_import_alpha_mode;

typedef struct tlod_import_material {
  char name[64];
  float base_color[4];          /* baseColorFactor (OBJ: Kd, d), linear */
  uint32_t base_color_texture;  /* index into textures[]; TLOD_IMPORT_NONE: none */
  uint32_t base_color_texcoord; /* index into the result's attributes[] of its UVs; TLOD_IMPORT_NONE: none */
  tlod_import_alpha_mode alpha_mode;
  float alpha_cutoff; /* MASK: default 0.5 */
  bool double_sided;
  /* pbrMetallicRoughness metallicFactor and roughnessFactor (glTF defaults 1 and 1: kept so that a round trip
   * through tlod_export_scene_file() looks the same in a PBR viewer); OBJ: 0 and 1 (Kd is a diffuse colour). */
  float metallic, roughness;
} tlod_import_material;

typedef struct tlod_import_texture {
  uint32_t image;                             /* index into images[]; TLOD_IMPORT_NONE: none */
  int wrap_s, wrap_t, min_filter, mag_filter; /* glTF sampler values (GL enums); 0: unset */
} tlod_import_texture;

typedef struct tlod_import_image {
  char uri[256]; /* as written in the file, possibly truncated; "" when embedded (bufferView, data: URI) */
  char mime[32]; /* "image/png", "image/jpeg" (from the file or sniffed), "" unknown */
  uint32_t width, height;
  uint8_t* rgba;    /* width * height RGBA8, top row first; NULL: missing, refused or undecodable (a warning) */
  uint8_t* encoded; /* the image file's bytes (for re-embedding on export); NULL when it could not be read */
  size_t encoded_size;
} tlod_import_image;

typedef enum tlod_import_anim_path {
  TLOD_IMPORT_PATH_TRANSLATION = 0,
  TLOD_IMPORT_PATH_ROTATION,
  TLOD_IMPORT_PATH_SCALE
} tlod_import_anim_path;

typedef enum tlod_import_interp {
  TLOD_IMPORT_INTERP_LINEAR = 0,
  TLOD_IMPORT_INTERP_STEP,
  TLOD_IMPORT_INTERP_CUBICSPLINE
} tlod_import_interp;

typedef struct tlod_import_channel {
  uint32_t node;
  tlod_import_anim_path path;
  tlod_import_interp interp;
  uint32_t key_count; /* >= 1 */
  float* times;       /* key_count seconds, finite, strictly increasing */
  /* key_count * n floats, n = 3 (translation, scale) or 4 (rotation x y z w);
   * CUBICSPLINE: key_count * 3 * n, per key in-tangent, value, out-tangent */
  float* values;
} tlod_import_channel;

typedef struct tlod_import_animation {
  char name[64];
  uint32_t channel_count;
  tlod_import_channel* channels;
} tlod_import_animation;

typedef struct tlod_import_skin {
  char name[64];
  uint32_t joint_count;
  uint32_t* joints;    /* node indices */
  float* inverse_bind; /* 16 per joint, column-major; identity when the file has none */
} tlod_import_skin;

/* A result field (VTK point or cell data, issue 14): per vertex of the
 * result, components floats; cell data averaged onto the points (the mean
 * over the cells around each point, docs/vtk.md). A series (.pvd, numbered
 * files) holds every step: step s of vertex v at data[(s * vertex_count + v)
 * * components], ranges over all steps. Node-only vertices carry their
 * point's values. Non-finite values are refused (an error naming the array
 * and the tuple). */
#define TLOD_IMPORT_MAX_FIELDS 16
#define TLOD_IMPORT_MAX_FIELD_COMPONENTS 9
typedef struct tlod_import_field {
  char name[64];                               /* the array's name ("stress"), may be truncated */
  char units[32];                              /* "" if the file gives none (a "NAME [UNITS]" or "NAME (UNITS)" name) */
  uint32_t components;                         /* 1..TLOD_IMPORT_MAX_FIELD_COMPONENTS */
  bool from_cells;                             /* cell data, averaged to points */
  float* data;                                 /* step_count (>= 1) x vertex_count x components */
  float min[TLOD_IMPORT_MAX_FIELD_COMPONENTS]; /* per component, over all steps */
  float max[TLOD_IMPORT_MAX_FIELD_COMPONENTS];
  float magnitude_min, magnitude_max; /* of the Euclidean norm (1 component: |value|) */
} tlod_import_field;

/* What a VTK import read and did (issue 14, `tlod info`; docs/vtk.md).
 * cell_types: every type present, by increasing id (at most 32 listed).
 * Timings: read_ms = VTK's reader and the conversion to arrays (all steps),
 * boundary_ms = extraction and compaction, fields_ms = fields. */
#define TLOD_IMPORT_MAX_CELL_TYPES 32
typedef struct tlod_import_cell_count {
  uint32_t vtk_type; /* VTK cell type id (12 = hexahedron) */
  char name[32];     /* "hexahedron", "quadratic tetra", ... */
  uint64_t count;
} tlod_import_cell_count;
typedef struct tlod_import_vtk_info {
  uint64_t points, cells; /* as in the file (a series: step 0) */
  uint32_t cell_type_count;
  tlod_import_cell_count cell_types[TLOD_IMPORT_MAX_CELL_TYPES];
  uint64_t volume_cells;          /* 3D cells whose faces were collected */
  uint64_t boundary_triangles;    /* boundary (or surface) triangle faces kept */
  uint64_t boundary_quads;        /* boundary (or surface) quad faces kept */
  uint64_t second_order_faces;    /* faces with mid-edge nodes */
  uint64_t interior_faces;        /* faces shared by two volume cells (dropped; counted once per pair) */
  uint64_t non_manifold_faces;    /* faces of three or more cells (kept once, a warning) */
  uint64_t cells_reoriented;      /* volume cells given with negative orientation (faces flipped) */
  uint64_t degenerate_cells;      /* cells with repeated points that collapse flat (or second-order), dropped */
  uint64_t cells_collapsed;       /* linear cells with repeated points kept as the solid/face they collapse to */
  uint64_t polygons_triangulated; /* polygons with > 4 corners fan-triangulated */
  uint64_t strips_converted;      /* triangle strips converted to triangles */
  uint64_t cells_ignored;         /* vertex and line cells (no surface) */
  double read_ms, boundary_ms, fields_ms; /* time in VTK's reader, in boundary extraction, in fields */
} tlod_import_vtk_info;

#define TLOD_IMPORT_WARNINGS_SIZE 1024

typedef struct tlod_import_result {
  uint32_t vertex_count;
  float* positions; /* xyz, world space (node transforms applied); keep_scene: mesh space */
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
  uint32_t polygons_triangulated; /* OBJ/PLY faces with > 4 corners fan-triangulated */
  uint32_t strips_fans_converted; /* glTF primitives in TRIANGLE_STRIP/FAN mode converted to triangles */
  uint32_t primitives_skipped;    /* glTF primitives left out (no POSITION, lines, points; see warnings) */
  uint32_t attribute_count;       /* 0..TLOD_IMPORT_MAX_ATTRIBUTES */
  tlod_import_attribute attributes[TLOD_IMPORT_MAX_ATTRIBUTES];
  uint16_t* joints; /* 4 per vertex (JOINTS_0, indices into the part's skin's joints); NULL when no part is skinned */
  float* weights;   /* 4 per vertex (WEIGHTS_0, sum 1); zeros for unskinned parts */
  uint32_t mesh_count;
  tlod_import_mesh* meshes;
  uint32_t node_count;
  tlod_import_node* nodes;
  uint32_t material_count;
  tlod_import_material* materials;
  uint32_t texture_count;
  tlod_import_texture* textures;
  uint32_t image_count;
  tlod_import_image* images;
  uint32_t animation_count;
  tlod_import_animation* animations;
  uint32_t skin_count;
  tlod_import_skin* skins;
  uint32_t weights_renormalised; /* vertices whose weights summed within 2e-2 of 1, rescaled */
  /* VTK (issue 14); NULL / 0 for the other formats. */
  uint32_t* face_nodes; /* TLOD_FACE_NODES per face (tlod_mesh_desc.face_nodes); NULL: no second-order face */
  uint32_t field_count;
  tlod_import_field* fields;
  tlod_import_vtk_info* vtk;
  /* A time series (.pvd, or numbered files FOO_0000.vtu, FOO_0001.vtu ...):
   * step_count >= 2 steps of the same cells; step_times[s] (seconds, the
   * .pvd's timestep, else s), step_positions: step_count x vertex_count x 3
   * (step 0 == positions). 0 / NULL for a single file. */
  uint32_t step_count;
  float* step_times;
  float* step_positions;
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
  /* false: geometry flattened into world space, one part per node x primitive
   * (as before). true: each glTF mesh's geometry once, in mesh space, and
   * the nodes instancing it; skinned meshes keep their bind pose without the
   * bind-pose warning (the caller animates). */
  bool keep_scene;
  /* Long imports (VTK): called with a stage ("read", "boundary", "fields",
   * "step 3/10": reading a series' steps) and its done fraction 0..1 (not
   * decreasing within a stage; "boundary" ends with 1), at most about 20
   * times a second, from the importing thread; NULL: none. */
  void (*progress)(void* user, const char* stage, double fraction);
  void* progress_user;
} tlod_import_desc;

/* Reads a mesh file; the format comes from the extension (.gltf .glb .obj
 * .ply .vtk .vtu .vtp .pvtu .pvd .stl, case-insensitive; anything else:
 * TLOD_ERROR_UNSUPPORTED).
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

/* Mesh and scene export (tlod_export_file, tlod_export_scene_file): its manual is tlod_export.h. */
#include "tlod_export.h"

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_TOOLS_IMPORT_H */
