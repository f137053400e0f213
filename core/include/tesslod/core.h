/*
 * tesslod/core.h -- context, meshes and curved surfaces (module tesslod::core)
 *
 * WHAT IT DOES
 *   Turns a coarse triangle or quad mesh into curved patches that can be
 *   evaluated at any (u, v):
 *     - Phong tessellation on triangles (Boubekeur & Alexa 2008), global or
 *       per-vertex shape factor alpha;
 *     - Phong tessellation on quads (Dupuy), with analytic tangent frames;
 *     - curved PN triangles (Vlachos et al. 2001): cubic geometry, quadratic
 *       normal field;
 *     - flat patches (the input itself), for comparisons;
 *   and carries per-vertex attributes (texture coordinates, colours, ...)
 *   across each patch with its corner weights ("Vertex attributes").
 *   Meshes are validated once at creation; what can be repaired (bad
 *   normals, degenerate faces) is repaired and counted, never silently.
 *
 * DOES NOT
 *   - know about cameras, levels of detail or GPUs (see tesslod/lod.h and the
 *     backends);
 *   - read files (the `tlod` tool's importers do that);
 *   - keep process-global state: several contexts may coexist.
 *
 * STEP BY STEP
 *   1. tlod_context_create(&(tlod_context_desc){0}, &ctx)
 *   2. tlod_mesh_create(ctx, &(tlod_mesh_desc){ .positions = ..., ... }, &mesh)
 *      -> on failure tlod_context_last_error(ctx) names the element at fault.
 *   3. tlod_surface_create(ctx, mesh, &(tlod_surface_desc){ .type = ... }, &surf)
 *   4. tlod_surface_eval(surf, patch, u, v, &point)
 *   5. tlod_surface_destroy(surf); tlod_mesh_destroy(mesh);
 *      tlod_context_destroy(ctx)
 *   Modules built on core (lod, backends) read meshes and surfaces through
 *   tlod_mesh_query_view() / tlod_surface_query_view() (re-queried after an
 *   update or refresh), evaluate whole patterns with tlod_surface_eval_grid()
 *   and allocate, fail and log through tlod_context_alloc() & co. (section
 *   "For the layers above core" at the end).
 *
 * THREADING AND ALLOCATION (AND LOGGING)
 *   A context and everything made from it belong to one thread at a time.
 *   Const queries and tlod_surface_eval() may be called from many threads at
 *   once. Work spread over threads inside a call goes through the context's
 *   parallel-for (the desc's callback, or a small built-in pool) and gives the
 *   same result for any thread count. Every allocation goes through the
 *   desc's allocator. Messages go to the desc's logger.
 *
 * CONTRACT: WHAT IS CHECKED, WHAT IS UNDEFINED (lod.h, patterns.h and
 * backend.h follow the same policy; each lists its own checks)
 *   Checked, in every function of this header:
 *   - NULL handles: create, update, refresh, eval and records calls return
 *     TLOD_ERROR_INVALID_ARGUMENT; destroy(NULL) is a no-op; queries return a
 *     value that is no data (0, NULL, "", a zeroed struct, UINT32_MAX for an
 *     index, TLOD_FINDING_NUM). The plumbing at the end with a NULL context:
 *     alloc gives NULL, free and log do nothing, parallel_for runs on the
 *     caller as worker 0.
 *   - NULL out pointers, a NULL mesh desc: TLOD_ERROR_INVALID_ARGUMENT; *out
 *     is set to NULL first whenever out is not NULL. A NULL context or
 *     surface desc means all defaults.
 *   - Ranges: a face, vertex, edge, finding or patch index past the end
 *     gives the query's no-data value; tlod_surface_eval(),
 *     tlod_surface_eval_grid() and tlod_surface_patch_records() return
 *     TLOD_ERROR_INVALID_ARGUMENT and write nothing (eval: *out zeroed).
 *     Enums outside their range, strides below an element, non-finite or
 *     negative parameters, an allocator with one hook of the two, more
 *     than TLOD_MAX_WORKERS workers: TLOD_ERROR_INVALID_ARGUMENT naming the
 *     field.
 *   - Mesh data: an index >= vertex_count, a position not finite or beyond
 *     TLOD_POSITION_LIMIT, a non-finite alpha or attribute value:
 *     TLOD_ERROR_INVALID_MESH naming the face or vertex (and attribute). Zero-length or non-finite normals,
 *     degenerate faces (repeated or coincident corners, zero area) and
 *     alphas outside [0, 1] are repaired and counted (tlod_mesh_info).
 *   A failure is recorded in tlod_context_last_error() (and logged), except
 *   with no context to hold it (a NULL context; tlod_context_create's
 *   refusals go to the desc's logger) and in the two eval calls, which may
 *   run on many threads at once.
 *   Undefined (not checked):
 *   - an object used after its destroy, a context destroyed before its
 *     objects, a mesh destroyed before its surfaces, objects of two contexts
 *     mixed in one call;
 *   - arrays shorter than their counts and strides say (input arrays, out
 *     buffers such as eval_grid's 3 floats per point);
 *   - calls on one context or its objects from two threads at once, apart
 *     from the const queries and evals named under THREADING (and those
 *     while tlod_mesh_update() or tlod_surface_refresh() runs);
 *   - hooks that break their contract: an allocator returning unaligned or
 *     shared memory, a parallel_for that skips or repeats a chunk;
 *   - NULL pointers given to the pure helpers (tlod_patch_error_bound(),
 *     tlod_grid_point_kind()'s param).
 *
 * PARAMETERS (u, v)
 *   Triangle (i, j, k): p(u, v) has barycentric weight u on i, v on j and
 *   w = 1 - u - v on k. Quad (0, 1, 2, 3): bilinear weights (1-u)(1-v),
 *   u(1-v), uv, (1-u)v. A point with a barycentric exactly 0 (a quad
 *   coordinate exactly 0 or 1) is an edge point and is evaluated by the one
 *   canonical edge function, so neighbouring patches produce bitwise equal
 *   positions there when the edge is smooth (same positions, normals and
 *   alphas on both sides). Corners return the input vertex exactly.
 */
#ifndef TESSLOD_CORE_H
#define TESSLOD_CORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TLOD_API
#define TLOD_API
#endif

#define TLOD_VERSION 1000 /* 1.0.0 */

/* ------------------------------------------------------------------------ */
/* Results                                                                  */
/* ------------------------------------------------------------------------ */

typedef enum tlod_result {
  TLOD_SUCCESS = 0,
  TLOD_ERROR_INVALID_ARGUMENT, /* wrong API use: NULL pointer, bad enum, ... */
  TLOD_ERROR_OUT_OF_MEMORY,
  TLOD_ERROR_INVALID_MESH, /* data that cannot be repaired: index out of range, NaN position */
  TLOD_ERROR_UNSUPPORTED,  /* valid request this build or surface cannot do */
  TLOD_ERROR_IO,           /* file could not be read or written */
  TLOD_ERROR_PARSE,        /* malformed file */
  TLOD_ERROR_BACKEND,      /* a backend could not start or failed */
  TLOD_RESULT_NUM,
  _TLOD_RESULT_FORCE_U32 = 0x7FFFFFFF
} tlod_result;

/* Short constant name of a result ("TLOD_ERROR_INVALID_MESH"). */
TLOD_API const char* tlod_result_string(tlod_result result);

/* ------------------------------------------------------------------------ */
/* Context                                                                  */
/* ------------------------------------------------------------------------ */

typedef struct tlod_context tlod_context;

/* Allocator hooks. Both NULL: malloc/free; one without the other:
 * tlod_context_create() refuses (TLOD_ERROR_INVALID_ARGUMENT, the desc's
 * logger names the missing hook). alloc returns memory aligned to at least
 * 16 bytes or NULL; free accepts NULL. */
typedef struct tlod_allocator {
  void* (*alloc_fn)(size_t size, void* user_data);
  void (*free_fn)(void* ptr, void* user_data);
  void* user_data;
} tlod_allocator;

typedef enum tlod_log_level {
  TLOD_LOG_ERROR = 0,
  TLOD_LOG_WARNING = 1,
  TLOD_LOG_INFO = 2,
  TLOD_LOG_DEBUG = 3,
  _TLOD_LOG_FORCE_U32 = 0x7FFFFFFF
} tlod_log_level;

/* Log callback. NULL func: messages are dropped (errors are still available
 * through tlod_context_last_error()). */
typedef struct tlod_logger {
  void (*func)(tlod_log_level level, const char* message, void* user_data);
  void* user_data;
} tlod_logger;

/* A range of work [begin, end) run by one worker; worker < thread count. */
typedef void (*tlod_task_fn)(void* task_data, uint32_t begin, uint32_t end, uint32_t worker);

/* An engine's job system: run fn over [0, count) split in chunks of any size,
 * return when every chunk has run. worker ids must stay below worker_count
 * (0 == 1; above TLOD_MAX_WORKERS: refused, each worker has scratch memory). */
#define TLOD_MAX_WORKERS 1024u
typedef struct tlod_parallel_for {
  void (*func)(tlod_task_fn fn, void* task_data, uint32_t count, void* user_data);
  uint32_t worker_count;
  void* user_data;
} tlod_parallel_for;

/* Instruction sets the hot loops (the scheduler's per-patch passes, the CPU
 * evaluator's kernels) choose from at run time. Every level gives bitwise
 * the same results as SCALAR (the kernels keep the scalar operation order,
 * and nothing is contracted into FMAs): a level changes speed only. */
typedef enum tlod_simd {
  TLOD_SIMD_DEFAULT = 0, /* the best this processor has */
  TLOD_SIMD_SCALAR,      /* plain C, no vector instructions chosen by tesslod */
  TLOD_SIMD_SSE2,        /* x86-64 baseline */
  TLOD_SIMD_AVX2,        /* AVX2 (256-bit) */
  TLOD_SIMD_AVX512,      /* AVX-512 F, BW, DQ and VL (512-bit) */
  TLOD_SIMD_NUM,
  _TLOD_SIMD_FORCE_U32 = 0x7FFFFFFF
} tlod_simd;

typedef struct tlod_context_desc {
  tlod_allocator allocator; /* default: malloc/free */
  tlod_logger logger;       /* default: none */
  /* Threads of the built-in pool when parallel_for.func is NULL.
   * 0 == number of online CPUs (at most 64); 1 == run on the caller only. */
  uint32_t thread_count;
  tlod_parallel_for parallel_for; /* default: built-in pool */
  const char* label;              /* shows up in log messages; default "tesslod" */
  /* The highest instruction set the hot loops may use; DEFAULT: the best
   * this processor has. A level the processor lacks is lowered to the best
   * it has (tlod_context_simd() tells); a value >= TLOD_SIMD_NUM is refused. */
  tlod_simd simd;
} tlod_context_desc;

/* Creates a context. desc may be NULL (all defaults). Fails with
 * TLOD_ERROR_INVALID_ARGUMENT (out NULL, one allocator hook without the
 * other, parallel_for.worker_count > TLOD_MAX_WORKERS) or
 * TLOD_ERROR_OUT_OF_MEMORY; there is no context to hold a last
 * error then, so the message goes to desc->logger. */
TLOD_API tlod_result tlod_context_create(const tlod_context_desc* desc, tlod_context** out);
/* Destroys a context; NULL is a no-op. Every object made from it must be
 * destroyed first. */
TLOD_API void tlod_context_destroy(tlod_context* ctx);
/* The desc with every default resolved. */
TLOD_API tlod_context_desc tlod_context_query_desc(const tlod_context* ctx);
/* The instruction set the hot loops of this context use (never DEFAULT). */
TLOD_API tlod_simd tlod_context_simd(const tlod_context* ctx);
/* Message of the last failed call on this context, naming the element at
 * fault ("face 17: index 4096 out of range (4000 vertices)"); "" if none. */
TLOD_API const char* tlod_context_last_error(const tlod_context* ctx);

/* ------------------------------------------------------------------------ */
/* Mesh                                                                     */
/* ------------------------------------------------------------------------ */

typedef struct tlod_mesh tlod_mesh;

typedef enum tlod_face_type {
  TLOD_FACE_DEFAULT = 0, /* == TLOD_FACE_TRIANGLES */
  TLOD_FACE_TRIANGLES,   /* 3 indices a face */
  TLOD_FACE_QUADS,       /* 4 indices a face, counter-clockwise */
  TLOD_FACE_MIXED,       /* face_sizes[f] is 3 or 4 */
  TLOD_FACE_NUM,
  _TLOD_FACE_FORCE_U32 = 0x7FFFFFFF
} tlod_face_type;

/* Computed normals: per face corner a unit normal, weighted by the corner
 * angle or the face area, summed around the vertex's welded position. A
 * face with a given mid-edge node (tlod_mesh_desc.face_nodes) uses at a
 * corner the tangents of its quadratic edges (4 M - 3 P_i - P_j), i.e. the
 * curved face's corner normal and angle; its edges without a given node
 * count as flat. Other faces use the flat face normal. */
typedef enum tlod_normal_mode {
  TLOD_NORMALS_DEFAULT = 0, /* == KEEP */
  /* Use the given normals, normalised. Zero-length or non-finite ones are
   * recomputed (angle-weighted) and counted. Without normals: ANGLE. */
  TLOD_NORMALS_KEEP,
  TLOD_NORMALS_ANGLE, /* recompute, weighted by the corner angle (Phong paper) */
  TLOD_NORMALS_AREA,  /* recompute, weighted by face area */
  TLOD_NORMALS_NUM,
  _TLOD_NORMALS_FORCE_U32 = 0x7FFFFFFF
} tlod_normal_mode;

/* Largest |coordinate| of a position, world units: mesh create and update
 * refuse a vertex outside it (TLOD_ERROR_INVALID_MESH naming the vertex).
 * Chosen so that float maths on positions cannot overflow: PN control points
 * lie within 5.2x this of the origin (Euclidean), so squared distances
 * between them stay below 1.1e38 < FLT_MAX (3.4e38). */
#define TLOD_POSITION_LIMIT 1e18f

/* ---- Vertex attributes (issue 11) ----
 * Extra per-vertex data carried through tessellation: texture coordinates,
 * colours, tangents, a scalar result field. Each attribute is 1..4 floats a
 * vertex; core stores it as a vec4 (components past the attribute's are
 * (0, 0, 0, 1), as GL fills a vertex attribute). Across a patch an attribute
 * is interpolated with the patch's corner weights: barycentric (u, v, w) on
 * triangles, bilinear on quads (PARAMETERS above), whatever the surface
 * type; the curved geometry does not bend it. On an edge the value comes
 * from one canonical edge function (the linear blend of the two end
 * vertices' values from the smaller weld id), so both patches of an edge
 * whose corners carry bitwise equal values produce bitwise equal values.
 * Vertices with one position, normal and alpha but different attribute
 * values (a UV or colour seam) keep the geometry closed: such an edge stays
 * smooth and is flagged seam (tlod_edge_link), and each side interpolates
 * its own values. Attributes are copied at creation; tlod_mesh_update()
 * leaves them as they are (crease-split vertices carry their source's). */
#define TLOD_MAX_ATTRIBUTES 8
typedef struct tlod_attribute_desc {
  const float* data;   /* required: `components` floats per vertex, finite */
  uint32_t components; /* 1..4 */
  uint32_t stride;     /* bytes; 0 == 4 * components; below that: refused */
  const char* name;    /* optional ("TEXCOORD_0"); copied, at most 31 chars kept */
} tlod_attribute_desc;

typedef struct tlod_mesh_desc {
  const float* positions;   /* required: xyz per vertex, finite, |x| <= TLOD_POSITION_LIMIT */
  uint32_t position_stride; /* bytes; 0 == 12 */
  const float* normals;     /* optional: xyz per vertex */
  uint32_t normal_stride;   /* bytes; 0 == 12 */
  const float* alphas;      /* optional: Phong shape factor per vertex, [0, 1] */
  uint32_t alpha_stride;    /* bytes; 0 == 4 */
  uint32_t vertex_count;

  const uint32_t* indices; /* required */
  uint32_t index_count;    /* a multiple of 3 (TRIANGLES), 4 (QUADS), or sum of face_sizes */
  tlod_face_type face_type;
  const uint8_t* face_sizes; /* MIXED only: 3 or 4 per face */
  uint32_t face_count;       /* MIXED only */

  tlod_normal_mode normal_mode;
  /* With computed normals: a vertex's faces whose normals differ by more
   * than this many degrees get separate normals (a crease). 0 == no creases
   * (one smooth normal per welded position). */
  float crease_angle_deg;
  /* Positions closer than this (each coordinate) are welded into one for
   * adjacency. 0 == bitwise-equal positions only. */
  float weld_epsilon;
  const char* label; /* names the mesh in messages; default "mesh" */
  /* Optional vertex attributes (see above), 0..TLOD_MAX_ATTRIBUTES. More,
   * attributes NULL with a count, components outside 1..4, NULL data or a
   * stride below 4 * components: TLOD_ERROR_INVALID_ARGUMENT naming the
   * attribute ("attribute 2 'COLOR_0': components 5 (1..4)"); a value not
   * finite: TLOD_ERROR_INVALID_MESH naming the vertex and the attribute. */
  const tlod_attribute_desc* attributes;
  uint32_t attribute_count;
  /* Optional second-order nodes (issue 14; TLOD_SURFACE_QUADRATIC), 5 per
   * input face: the mid-edge node of edges 0..3 (edge e from corner e to
   * corner (e + 1) % n; a triangle's [3] unused) and the centre node
   * ([4], quads: a 9-node face; TLOD_NO_NODE: an 8-node or linear face).
   * A node is a vertex index < vertex_count, or TLOD_NO_NODE; slots a face
   * does not have (a triangle's [3] and [4]) are ignored. A node index out
   * of range, equal to a corner of its face or to another node of it:
   * TLOD_ERROR_INVALID_MESH naming the input face and the node slot
   * ("face 7: node 2: index 99 out of range (40 vertices)"). Node-only
   * vertices (a node of some kept face, a corner of none) are not "unused"
   * and get no normal work: a valid given normal is kept, else (0, 0, 1),
   * never counted as repaired or computed. Node positions count in the
   * bbox and are updated by tlod_mesh_update() like any vertex. After
   * adjacency a linked edge without a node takes its neighbour's given
   * node (tlod_mesh_info.nodes_shared; tlod_mesh_view.face_nodes shows the
   * result), and an edge whose two sides have bitwise different node
   * positions is not smooth. NULL: no face has nodes. Other surface types
   * ignore the nodes. */
  const uint32_t* face_nodes;
} tlod_mesh_desc;

#define TLOD_NO_NODE UINT32_MAX
#define TLOD_FACE_NODES 5

/* What validation found and repaired. Counts are of input elements. */
typedef struct tlod_mesh_info {
  uint32_t input_vertex_count;
  uint32_t input_face_count;
  uint32_t face_count;               /* faces kept */
  uint32_t triangle_count;           /* of the kept faces */
  uint32_t quad_count;               /* of the kept faces */
  uint32_t welded_vertex_count;      /* distinct positions */
  uint32_t degenerate_faces_dropped; /* repeated index or zero area */
  uint32_t normals_repaired;         /* given normal zero-length or non-finite: recomputed */
  uint32_t normals_computed;         /* vertices whose normal was computed (no input or mode) */
  uint32_t unused_vertices;          /* referenced by no kept face */
  uint32_t edge_count;               /* distinct welded edges */
  uint32_t boundary_edges;           /* one face */
  uint32_t non_manifold_edges;       /* three or more faces, or inconsistent orientation */
  uint32_t crease_edges;             /* two faces, but split normals (or alphas) */
  uint32_t attribute_seam_edges;     /* smooth edges with split attributes (tlod_edge_link.seam) */
  uint32_t curved_faces;             /* kept faces with at least one given node (face_nodes) */
  uint32_t nodes_shared;             /* face edges without a node that took their neighbour's */
  uint32_t finding_count;            /* findings stored (at most TLOD_MAX_FINDINGS) */
  uint32_t findings_dropped;         /* findings past the limit */
  bool closed;                       /* no boundary and no non-manifold edge */
  float bbox_min[3];
  float bbox_max[3];
} tlod_mesh_info;

#define TLOD_MAX_FINDINGS 64

typedef enum tlod_finding_kind {
  TLOD_FINDING_DEGENERATE_FACE = 0, /* element = face (input index) */
  TLOD_FINDING_NORMAL_REPAIRED,     /* element = vertex */
  TLOD_FINDING_UNUSED_VERTEX,       /* element = vertex */
  TLOD_FINDING_BOUNDARY_EDGE,       /* element = face, element2 = edge in face */
  TLOD_FINDING_NON_MANIFOLD_EDGE,   /* element = face, element2 = edge in face */
  TLOD_FINDING_ALPHA_CLAMPED,       /* element = vertex */
  TLOD_FINDING_NUM,
  _TLOD_FINDING_FORCE_U32 = 0x7FFFFFFF
} tlod_finding_kind;

typedef struct tlod_finding {
  tlod_finding_kind kind;
  uint32_t element;
  uint32_t element2;
  char message[96];
} tlod_finding;

/* Validates and copies the arrays into a new mesh. On failure *out is NULL
 * and tlod_context_last_error() names the element at fault. */
TLOD_API tlod_result tlod_mesh_create(tlod_context* ctx, const tlod_mesh_desc* desc, tlod_mesh** out);
TLOD_API void tlod_mesh_destroy(tlod_mesh* mesh);
TLOD_API tlod_mesh_info tlod_mesh_query_info(const tlod_mesh* mesh);
/* Finding i < info.finding_count. */
TLOD_API tlod_finding tlod_mesh_query_finding(const tlod_mesh* mesh, uint32_t i);

/* Kept faces, in input order (dropped faces are left out). */
TLOD_API uint32_t tlod_mesh_face_count(const tlod_mesh* mesh);
/* Input face index of kept face f (to map results back to the caller's faces). */
TLOD_API uint32_t tlod_mesh_face_input_index(const tlod_mesh* mesh, uint32_t face);
/* Corner count (3 or 4) and corner vertex indices of kept face f. */
TLOD_API uint32_t tlod_mesh_face_corners(const tlod_mesh* mesh, uint32_t face, uint32_t out[4]);
TLOD_API uint32_t tlod_mesh_vertex_count(const tlod_mesh* mesh);
/* Final (normalised, repaired) normal, position and welded position id of a vertex. */
TLOD_API void tlod_mesh_vertex(const tlod_mesh* mesh, uint32_t vertex, float position[3], float normal[3]);
TLOD_API uint32_t tlod_mesh_vertex_weld_id(const tlod_mesh* mesh, uint32_t vertex);

/* Edge e (0..corners-1) of face f runs from corner e to corner (e+1)%n.
 * Neighbour across it, or UINT32_MAX for a boundary or non-manifold edge. */
typedef struct tlod_edge_link {
  uint32_t face; /* neighbouring kept face, UINT32_MAX if none */
  uint8_t edge;  /* its edge index */
  bool smooth;   /* both sides have bitwise equal normals and alphas */
  /* smooth geometry, but some attribute differs (bitwise) between the two
   * sides at a corner: a UV or colour seam. Always false when !smooth. */
  bool seam;
} tlod_edge_link;
TLOD_API tlod_edge_link tlod_mesh_edge_link(const tlod_mesh* mesh, uint32_t face, uint32_t edge);

/* The mesh's attributes: their count, and attribute a's name (as given, at
 * most 31 chars; "" without one) and components; zeroed past the end. */
typedef struct tlod_attribute_info {
  char name[32];
  uint32_t components;
} tlod_attribute_info;
TLOD_API uint32_t tlod_mesh_attribute_count(const tlod_mesh* mesh);
TLOD_API tlod_attribute_info tlod_mesh_query_attribute(const tlod_mesh* mesh, uint32_t a);

/* Updates positions and/or normals of every vertex in place (dynamic meshes:
 * skinning, FEM). Topology is kept; either pointer may be NULL. NULL
 * normals with computed normals: they are recomputed. */
TLOD_API tlod_result tlod_mesh_update(tlod_mesh* mesh, const float* positions, uint32_t position_stride,
                                      const float* normals, uint32_t normal_stride);

/* Replaces the values of one vertex attribute (a result field's next time
 * step) in place: data holds the attribute's `components` floats per input
 * vertex (stride bytes apart; 0 == 4 * components), crease-split vertices
 * take their source's. Positions, normals, nodes and the other attributes
 * are untouched; the seam flags (tlod_edge_link.seam) are recomputed.
 * Surfaces hold no attribute data, so tlod_mesh_eval_attributes_grid() and
 * tlod_mesh_patch_attributes() give the new values at once; a device picks
 * them up on its next tlod_device_update_surface(). Checked, nothing
 * written on failure: NULL mesh (TLOD_ERROR_INVALID_ARGUMENT, no last
 * error), attribute >= the attribute count, NULL data or a stride below an
 * element (TLOD_ERROR_INVALID_ARGUMENT naming the attribute), a value not
 * finite (TLOD_ERROR_INVALID_MESH naming the vertex and the attribute). */
TLOD_API tlod_result tlod_mesh_update_attribute(tlod_mesh* mesh, uint32_t attribute, const float* data,
                                                uint32_t stride);

/* ------------------------------------------------------------------------ */
/* Surfaces                                                                 */
/* ------------------------------------------------------------------------ */

typedef struct tlod_surface tlod_surface;

typedef enum tlod_surface_type {
  TLOD_SURFACE_DEFAULT = 0, /* == PHONG */
  TLOD_SURFACE_FLAT,        /* the input faces (bilinear quads) */
  TLOD_SURFACE_PHONG,       /* Phong triangles and Phong quads */
  TLOD_SURFACE_PN,          /* PN triangles; quads are not supported */
  /* Second-order (isoparametric quadratic) faces, exact (issue 14): a face
   * with nodes (tlod_mesh_desc.face_nodes) is the 6-node triangle or the
   * 9-node biquadratic quad through them (8-node serendipity quads: the
   * biquadratic with the serendipity centre, the same surface); a face
   * without a node on an edge takes the neighbour's node there, else the
   * Phong node (so a linear face is its Phong patch, docs/design.md
   * "Quadratic faces"). Shading normal: interpolated corner normals
   * (TLOD_SHADING_NORMAL_TRUE: from the analytic tangents). Edges use the
   * canonical quadratic edge through the edge's node, so two faces sharing
   * corners and node (given, shared or both Phong) agree bitwise there. */
  TLOD_SURFACE_QUADRATIC,
  TLOD_SURFACE_NUM,
  _TLOD_SURFACE_FORCE_U32 = 0x7FFFFFFF
} tlod_surface_type;

typedef enum tlod_shading_normal {
  TLOD_SHADING_NORMAL_DEFAULT = 0,  /* == INTERPOLATED (PN: the quadratic field) */
  TLOD_SHADING_NORMAL_INTERPOLATED, /* Phong: normalize(sum of weights * normals) */
  TLOD_SHADING_NORMAL_TRUE,         /* normalize(dP/du x dP/dv) */
  TLOD_SHADING_NORMAL_NUM,
  _TLOD_SHADING_NORMAL_FORCE_U32 = 0x7FFFFFFF
} tlod_shading_normal;

/* Where the Phong shape factor alpha of each vertex comes from. */
typedef enum tlod_alpha_mode {
  TLOD_ALPHA_DEFAULT = 0, /* 0.75 at every vertex (the Phong paper's choice) */
  TLOD_ALPHA_GLOBAL,      /* desc.alpha at every vertex; 0 is a real value (the flat patch) */
  TLOD_ALPHA_PER_VERTEX,  /* the mesh's per-vertex alphas (the mesh must have them) */
  TLOD_ALPHA_NUM,
  _TLOD_ALPHA_FORCE_U32 = 0x7FFFFFFF
} tlod_alpha_mode;

/* How a surface makes its per-patch error tables (tlod_patch_info below;
 * docs/design.md 3.5b). Both are rigorous upper bounds of the true deviation
 * of every level's pattern; they trade build time against triangles drawn. */
typedef enum tlod_error_tables {
  TLOD_ERROR_TABLES_DEFAULT = 0, /* == MEASURED */
  /* Levels 0..TLOD_ERROR_TABLE_LEVELS-1 measured per patch (bound / true
   * deviation about 1.0-1.4): the fewest triangles at a given screen error.
   * Build (and refresh) time against CLOSED_FORM on one thread: Phong
   * per-vertex alpha about 2.6x, PN 2.0x, Phong one alpha 1.7x, flat 1.0x
   * (BENCHMARKS.md "Surface build cost of the error tables"). */
  TLOD_ERROR_TABLES_MEASURED,
  /* error_table[l] = error_bound * 4^-l + error_slack, nothing measured: the
   * cheapest build, for meshes refreshed every frame (skinning, simulation),
   * but a looser bound (1.3-8x the true deviation), so the level rule picks
   * finer levels. Never below the MEASURED table of the same patch (whose
   * entries are capped by it). */
  TLOD_ERROR_TABLES_CLOSED_FORM,
  /* No error bound at all, for users that pick levels themselves (a uniform
   * level: tlod_cpu_tessellate, the scheduler's UNIFORM, FLAT or SILHOUETTE
   * policies) on meshes refreshed every frame: error_table[], error_tail
   * are +INFINITY and error_slack 0, so tlod_patch_error_bound() returns
   * +INFINITY at every level ("unknown"); Phong surfaces also leave
   * error_bound and d_max at +INFINITY and keep only a (looser, still
   * rigorous) bounding sphere: the cheapest build and refresh. PN and
   * QUADRATIC surfaces still compute error_bound (their sphere needs the
   * net). tlod_scheduler_create() refuses it for the ERROR and HYBRID
   * policies (INVALID_ARGUMENT), whose level rule needs the bounds. */
  TLOD_ERROR_TABLES_NONE,
  TLOD_ERROR_TABLES_NUM,
  _TLOD_ERROR_TABLES_FORCE_U32 = 0x7FFFFFFF
} tlod_error_tables;

typedef struct tlod_surface_desc {
  tlod_surface_type type;
  tlod_alpha_mode alpha_mode; /* default: 0.75 everywhere */
  float alpha;                /* TLOD_ALPHA_GLOBAL only: [0, 1]; ignored otherwise */
  tlod_shading_normal shading_normal;
  const char* label;
  tlod_error_tables error_tables; /* default: MEASURED; a value >= NUM is refused (INVALID_ARGUMENT) */
} tlod_surface_desc;

/* ---- Per-level error tables (issue #9; maths: docs/design.md "Error tables") ----
 * Levels 0..TLOD_ERROR_TABLE_LEVELS-1 are measured per patch when the
 * surface is built or refreshed (unless the desc asks for
 * TLOD_ERROR_TABLES_CLOSED_FORM); above them a rigorous tail decays as 4^-l. */
#define TLOD_ERROR_TABLE_LEVELS 3

/* Per-patch precomputed data, in kept-face order. */
typedef struct tlod_patch_info {
  uint32_t corner_count; /* 3 or 4 */
  /* Bound on the distance between the surface and its flat (level 0)
   * patch, world units. The level-l pattern deviates by at most
   * error_bound * 4^-l. PN: max(9/4 * d'_max (Schwarz et al.), the
   * second-derivative bound); Phong: docs/design.md section 3.5; QUADRATIC: section 3.12.
   * Superseded by the error table below (tlod_patch_error_bound()). */
  float error_bound;
  float d_max;     /* PN: max tangent control point distance; Phong: alpha-scaled max |d_e|;
                      QUADRATIC: max |2 (M_e - mid_e)| (triangles), = error_bound (quads) */
  float center[3]; /* bounding sphere of the curved patch */
  float radius;
  /* -- error tables (superseding error_bound; the scheduler's level rule
   * reads them through tlod_patch_error_bound()). error_table[l]: upper
   * bound, world units, of max |S(u,v) - P_l(u,v)| over the patch, P_l the
   * level-l pattern's piecewise-linear interpolant of the surface (as the
   * pattern draws it: 4^l triangles, quads 2 * 4^l with the pattern's
   * diagonal), float evaluation rounding included; non-increasing in l,
   * and >= every tail value below. Measured, or with
   * TLOD_ERROR_TABLES_CLOSED_FORM error_bound * 4^-l + error_slack (the
   * desc's error_tables); the measured entry is never above that. */
  float error_table[TLOD_ERROR_TABLE_LEVELS];
  float error_tail;  /* level l >= TLOD_ERROR_TABLE_LEVELS: error_tail * 4^-l + error_slack */
  float error_slack; /* float rounding of the evaluation (included in every value) */
} tlod_patch_info;

/* The world-space bound on |surface - level-l pattern| of a patch, any level
 * (0..10, tesslod/lod.h TLOD_MAX_LEVEL): error_table[level], or the tail;
 * +INFINITY for a surface made with TLOD_ERROR_TABLES_NONE (no bound known).
 * Pure; non-increasing in level, so a level rule is a compare ladder:
 * the first level whose bound (times the projection scale) meets the
 * tolerance; no transcendental function is needed (4^-l is a power of two). */
TLOD_API float tlod_patch_error_bound(const tlod_patch_info* info, uint32_t level);

typedef struct tlod_surface_point {
  float position[3];
  float normal[3];    /* unit shading normal */
  float tangent[3];   /* dP/du (not normalised) */
  float bitangent[3]; /* dP/dv (not normalised) */
} tlod_surface_point;

/* Precomputes every patch of the mesh (the mesh must outlive the surface). */
TLOD_API tlod_result tlod_surface_create(tlod_context* ctx, const tlod_mesh* mesh, const tlod_surface_desc* desc,
                                         tlod_surface** out);
TLOD_API void tlod_surface_destroy(tlod_surface* surface);
TLOD_API tlod_surface_desc tlod_surface_query_desc(const tlod_surface* surface);
TLOD_API const tlod_mesh* tlod_surface_mesh(const tlod_surface* surface);
TLOD_API uint32_t tlod_surface_patch_count(const tlod_surface* surface);
TLOD_API tlod_patch_info tlod_surface_patch(const tlod_surface* surface, uint32_t patch);
/* Recomputes patch data after tlod_mesh_update(); only patches touching a
 * changed vertex are recomputed. Returns the count recomputed in *updated
 * (may be NULL). */
TLOD_API tlod_result tlod_surface_refresh(tlod_surface* surface, uint32_t* updated);

/* Evaluates patch at (u, v): see PARAMETERS above. Thread-safe. NULL
 * surface or out, patch >= the patch count, or u, v not finite:
 * TLOD_ERROR_INVALID_ARGUMENT and *out (if any) zeroed; no last error is
 * recorded (the call may run on many threads at once). */
TLOD_API tlod_result tlod_surface_eval(const tlod_surface* surface, uint32_t patch, float u, float v,
                                       tlod_surface_point* out);

/* ------------------------------------------------------------------------ */
/* Enum names                                                               */
/* ------------------------------------------------------------------------ */

/* One table per enum, (value, name): the names tools parse and print. The
 * DEFAULT value has no name of its own; *_name() gives its resolved value's. */
#define TLOD_SURFACE_TYPE_NAMES(X)                                                                                     \
  X(TLOD_SURFACE_FLAT, "flat")                                                                                         \
  X(TLOD_SURFACE_PHONG, "phong") X(TLOD_SURFACE_PN, "pn") X(TLOD_SURFACE_QUADRATIC, "quadratic")
#define TLOD_SHADING_NORMAL_NAMES(X)                                                                                   \
  X(TLOD_SHADING_NORMAL_INTERPOLATED, "interpolated") X(TLOD_SHADING_NORMAL_TRUE, "true")
#define TLOD_ALPHA_MODE_NAMES(X) X(TLOD_ALPHA_GLOBAL, "global") X(TLOD_ALPHA_PER_VERTEX, "per-vertex")
#define TLOD_NORMAL_MODE_NAMES(X)                                                                                      \
  X(TLOD_NORMALS_KEEP, "keep") X(TLOD_NORMALS_ANGLE, "angle") X(TLOD_NORMALS_AREA, "area")
#define TLOD_SIMD_NAMES(X)                                                                                             \
  X(TLOD_SIMD_SCALAR, "scalar") X(TLOD_SIMD_SSE2, "sse2") X(TLOD_SIMD_AVX2, "avx2") X(TLOD_SIMD_AVX512, "avx512")

/* Name of a value ("phong"); NULL for a value outside the enum. */
TLOD_API const char* tlod_surface_type_name(tlod_surface_type type);
TLOD_API const char* tlod_shading_normal_name(tlod_shading_normal mode);
TLOD_API const char* tlod_alpha_mode_name(tlod_alpha_mode mode);
TLOD_API const char* tlod_normal_mode_name(tlod_normal_mode mode);
TLOD_API const char* tlod_simd_name(tlod_simd simd); /* DEFAULT: the name of this processor's best */
/* Value of a name (exact, case-sensitive); false (and *out untouched) when
 * the name is none of the table's. */
TLOD_API bool tlod_surface_type_from_name(const char* name, tlod_surface_type* out);
TLOD_API bool tlod_shading_normal_from_name(const char* name, tlod_shading_normal* out);
TLOD_API bool tlod_alpha_mode_from_name(const char* name, tlod_alpha_mode* out);
TLOD_API bool tlod_normal_mode_from_name(const char* name, tlod_normal_mode* out);
TLOD_API bool tlod_simd_from_name(const char* name, tlod_simd* out);

/* ------------------------------------------------------------------------ */
/* For the layers above core (lod, backends) and for backend authors        */
/* ------------------------------------------------------------------------ */
/*
 * Everything a module built on core needs, so that no module reads core's
 * private structs: the context's allocator, error and parallel-for, a
 * read-only view of a mesh's and a surface's arrays (for hot loops: no call
 * per element), packed per-patch records in the layout GPU shaders read,
 * and the evaluation of a whole pattern of points on one patch through the
 * canonical edge function.
 */

#if defined(__GNUC__)
#define TLOD_PRINTF_FORMAT(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define TLOD_PRINTF_FORMAT(fmt, args)
#endif

/* size bytes through the context's allocator (16-byte aligned), NULL when
 * it fails. _calloc zeroes and checks count * size for overflow. size 0
 * allocates 1 byte. Free with tlod_context_free(); NULL is a no-op. */
TLOD_API void* tlod_context_alloc(const tlod_context* ctx, size_t size);
TLOD_API void* tlod_context_calloc(const tlod_context* ctx, size_t count, size_t size);
TLOD_API void tlod_context_free(const tlod_context* ctx, void* ptr);
/* Records a printf-formatted message as the context's last error, sends it
 * to the logger as an error and returns result (for `return tlod_context_fail(...)`). */
TLOD_API tlod_result tlod_context_fail(tlod_context* ctx, tlod_result result, const char* fmt, ...)
    TLOD_PRINTF_FORMAT(3, 4);
/* Sends a printf-formatted message to the logger, prefixed with the context's label. */
TLOD_API void tlod_context_log(const tlod_context* ctx, tlod_log_level level, const char* fmt, ...)
    TLOD_PRINTF_FORMAT(3, 4);
/* Runs fn over [0, count) on the context's workers (the engine's job system
 * or the built-in pool) and returns when every chunk has run. */
TLOD_API void tlod_context_parallel_for(const tlod_context* ctx, tlod_task_fn fn, void* task_data, uint32_t count);
/* Upper bound on the worker ids fn receives (>= 1). */
TLOD_API uint32_t tlod_context_worker_count(const tlod_context* ctx);
/* Monotonic wall clock in milliseconds, for stage timings. */
TLOD_API double tlod_now_ms(void);

/* Read-only arrays of a mesh. Valid until the mesh is updated
 * (tlod_mesh_update) or destroyed; positions and normals change in place on
 * update, the rest never. Faces are the kept faces, in input order. */
typedef struct tlod_mesh_view {
  uint32_t vertex_count;
  const float (*positions)[3];
  const float (*normals)[3];        /* unit length */
  const uint32_t* weld_id;          /* smallest vertex index with the same (welded) position */
  uint32_t face_count;              /* kept faces == patches */
  const uint32_t (*faces)[4];       /* corner vertex indices; [3] unused for triangles */
  const uint8_t* face_corners;      /* 3 or 4 */
  const tlod_edge_link (*links)[4]; /* per face edge, see tlod_mesh_edge_link() */
  const uint32_t* face_input_index; /* input face of each kept face */
  uint32_t attribute_count;         /* 0..TLOD_MAX_ATTRIBUTES */
  /* vertex-major: attribute a of vertex v at [v * attribute_count + a];
   * components past the attribute's are (0, 0, 0, 1) as in GL; NULL when
   * attribute_count is 0. Never changed by an update. */
  const float (*attributes)[4];
  /* Per kept face the resolved nodes (tlod_mesh_desc.face_nodes, with the
   * neighbours' nodes shared onto edges that had none): vertex indices or
   * TLOD_NO_NODE; NULL when the desc had no face_nodes. */
  const uint32_t (*face_nodes)[TLOD_FACE_NODES];
  /* Starts at 1 and grows by one on every successful tlod_mesh_update or
   * tlod_mesh_update_attribute: equal generations, equal arrays (a
   * scheduler or backend may skip work for an unchanged mesh). */
  uint64_t generation;
  /* Grows by one on each update that changed some link's smooth flag
   * (new normals on a mesh with crease-split vertices or nodes): equal
   * generations, equal smooth flags. */
  uint64_t smooth_generation;
} tlod_mesh_view;
TLOD_API tlod_mesh_view tlod_mesh_query_view(const tlod_mesh* mesh);

/* Per patch and corner, the attribute vec4s as GPU shaders read them: patch
 * p (counted from first), corner c, attribute a at
 * out[(p * 4 + c) * attribute_count + a]; corner 3 of a triangle zero. A
 * mesh without attributes writes nothing. NULL mesh:
 * TLOD_ERROR_INVALID_ARGUMENT; patches past the end, or out NULL with
 * something to write: TLOD_ERROR_INVALID_ARGUMENT (last error recorded),
 * nothing written. */
TLOD_API tlod_result tlod_mesh_patch_attributes(const tlod_mesh* mesh, uint32_t first, uint32_t count, float (*out)[4]);

/* Read-only arrays of a surface. Valid until the surface is refreshed or
 * destroyed (refresh rewrites the patch data in place). */
typedef struct tlod_surface_view {
  tlod_surface_type type; /* resolved */
  uint32_t patch_count;   /* == the mesh's face count */
  const tlod_patch_info* patches;
  const float* vertex_alpha; /* per mesh vertex: the Phong shape factor in use (0 for FLAT) */
  /* Starts at 1 and grows by one on every tlod_surface_refresh that rebuilt
   * at least one patch: equal generations, equal patches. */
  uint64_t generation;
} tlod_surface_view;
TLOD_API tlod_surface_view tlod_surface_query_view(const tlod_surface* surface);

/* One patch as GPU shaders read it: std430-compatible (every member a
 * multiple of 16 bytes, no padding), 368 bytes. Unused entries are zero. */
typedef struct tlod_patch_record {
  float corner[4][4]; /* corner positions xyz, w = the corner's alpha */
  float normal[4][4]; /* corner unit normals xyz, w = 0 */
  uint32_t weld[4];   /* corner weld ids (canonical edge direction) */
  uint32_t info[4];   /* [0] corner count (3 or 4), [1..3] zero */
  /* PN: b300 b030 b003 b210 b120 b021 b012 b102 b201 b111, w = 0.
   * QUADRATIC: [0..3] the node of edge 0..3 (given, shared, or the Phong
   * node), [4] the centre node of a quad (given; else from an 8-node
   * face's serendipity rule; else the Phong quad's centre), as positions
   * (Lagrange nodes, not Bezier points), w = 0; info[1] = 1 when the face
   * had a given node. */
  float pn_control[10][4];
  float pn_normal[3][4]; /* PN: mid-edge normals n110 n011 n101, w = 0 */
} tlod_patch_record;
#if defined(__cplusplus) && __cplusplus >= 201103L
static_assert(sizeof(tlod_patch_record) == 23 * 16, "tlod_patch_record is the std430 Patch");
#elif defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
_Static_assert(sizeof(tlod_patch_record) == 23 * 16, "tlod_patch_record is the std430 Patch");
#endif
/* Writes the records of patches [first, first + count) to out. Patches past
 * the end: TLOD_ERROR_INVALID_ARGUMENT (nothing written). */
TLOD_API tlod_result tlod_surface_patch_records(const tlod_surface* surface, uint32_t first, uint32_t count,
                                                tlod_patch_record* out);

/* Where grid point (i, j) lies on a patch, on the grid of 2^grid_log2
 * segments per edge (triangles: u = i / 2^g, v = j / 2^g, i + j <= 2^g;
 * quads: 0 <= i, j <= 2^g): 0..3 a corner (triangle i, j, k; quad 0..3),
 * TLOD_GRID_EDGE + e on edge e (from corner e to corner (e + 1) % n;
 * *param = the end corner's weight times 2^g), TLOD_GRID_INTERIOR inside
 * (*param untouched); TLOD_GRID_OFF for a point off the grid or grid_log2 >
 * TLOD_GRID_MAX_LOG2 (15: coordinates are uint16_t). Pure. */
#define TLOD_GRID_EDGE 4u
#define TLOD_GRID_INTERIOR 8u
#define TLOD_GRID_OFF 16u
#define TLOD_GRID_MAX_LOG2 15u
TLOD_API uint32_t tlod_grid_point_kind(uint32_t corner_count, uint32_t grid_log2, uint32_t i, uint32_t j,
                                       uint32_t* param);

/* Evaluates count grid points of one patch: point k has grid coordinates
 * ij[0], ij[1] of the uint16_t pair at (const char*)ij + k * ij_stride (so a
 * pattern vertex array can be passed as it is). Corners are the mesh's
 * vertices exactly, edge points come from the canonical edge function
 * (bitwise equal on both patches of a smooth edge), interior points from the
 * patch's formula with its corners gathered once. positions and normals
 * receive 3 floats per point; normals may be NULL. Thread-safe.
 * TLOD_ERROR_INVALID_ARGUMENT, nothing written and no last error recorded:
 * NULL surface, patch >= the patch count, grid_log2 > 15, ij or positions
 * NULL with count > 0, or a point off the grid (i + j > 2^g for triangles,
 * i or j > 2^g for quads). */
TLOD_API tlod_result tlod_surface_eval_grid(const tlod_surface* surface, uint32_t patch, uint32_t grid_log2,
                                            const uint16_t* ij, size_t ij_stride, uint32_t count, float* positions,
                                            float* normals);

/* The batch form of tlod_surface_eval_grid() for points strictly inside
 * the patch (neither corner nor edge): count points (u[k], v[k]), each
 * u = i / 2^g and v = j / 2^g computed in float for an interior grid point,
 * evaluated with the instruction set simd (one the processor has, e.g.
 * tlod_context_simd(ctx); TLOD_SIMD_DEFAULT and SCALAR: plain C). The
 * results are bitwise those of tlod_surface_eval_grid() at the same points,
 * at every simd level. positions and normals receive 3 floats per point;
 * normals NULL: no normal is computed. Thread-safe.
 * TLOD_ERROR_INVALID_ARGUMENT, nothing written: NULL surface, patch >= the
 * patch count, u, v or positions NULL with count > 0.
 * UNDEFINED (not checked, the caller's pattern tables classify the points):
 * a point on the patch's boundary or off it gives the patch formula's value
 * there, not the canonical edge function's. */
TLOD_API tlod_result tlod_surface_eval_interior(const tlod_surface* surface, uint32_t patch, tlod_simd simd,
                                                uint32_t count, const float* u, const float* v, float* positions,
                                                float* normals);

/* tlod_surface_eval_interior() with normals NULL for many patches at once,
 * in lanes of patches (a coarse level has few interior points per patch):
 * point k (k < count) of every patch patches[r] (r < patch_count) is at
 * (u[k], v[k]) and goes to positions + 3 * (first[r] + k). The positions
 * are bitwise tlod_surface_eval_interior()'s at every simd level; triangles
 * and quads may mix (consecutive patches of one corner count share lanes).
 * Thread-safe. TLOD_ERROR_INVALID_ARGUMENT, nothing written: NULL surface,
 * a NULL array with patch_count and count > 0, a patch >= the patch count.
 * UNDEFINED as tlod_surface_eval_interior(): points on or off the boundary. */
TLOD_API tlod_result tlod_surface_eval_interiors(const tlod_surface* surface, tlod_simd simd, uint32_t patch_count,
                                                 const uint32_t* patches, uint32_t count, const float* u,
                                                 const float* v, const uint32_t* first, float* positions);

/* The batch form of tlod_surface_eval_grid() for points on one edge of a
 * patch: point k at param[k] / 2^grid_log2, the weight of the edge's end
 * corner ((edge + 1) % n), as tlod_grid_point_kind() gives it. Bitwise the
 * values tlod_surface_eval_grid() gives there (the canonical edge
 * function); the edge's own data (PN: its cubic control points and
 * mid-edge normal) is computed once for all points. positions and normals:
 * 3 floats per point, normals may be NULL. Thread-safe.
 * TLOD_ERROR_INVALID_ARGUMENT, nothing written: NULL surface, patch >= the
 * patch count, edge >= the face's corner count, grid_log2 > 15, param or
 * positions NULL with count > 0, a param 0 or >= 2^grid_log2 (a corner or
 * off the edge). */
TLOD_API tlod_result tlod_surface_eval_edge(const tlod_surface* surface, uint32_t patch, uint32_t edge,
                                            uint32_t grid_log2, uint32_t count, const uint32_t* param, float* positions,
                                            float* normals);

/* tlod_surface_eval_edge() with normals NULL for many edges at once, in
 * lanes of edges (a coarse level has few points per edge): edge r is edge
 * edges[r] of patch patches[r], r < edge_count; every edge's point k is at
 * param[k] / 2^grid_log2 (k < count) and goes to positions + 3 * (first[r]
 * + k). The positions are bitwise tlod_surface_eval_edge()'s at every simd
 * level (the instruction set, as tlod_surface_eval_interior() takes it).
 * Thread-safe. TLOD_ERROR_INVALID_ARGUMENT, nothing written: NULL surface,
 * grid_log2 > 15, a NULL array with edge_count and count > 0, a patch or
 * edge out of range, a param 0 or >= 2^grid_log2. */
TLOD_API tlod_result tlod_surface_eval_edges(const tlod_surface* surface, tlod_simd simd, uint32_t grid_log2,
                                             uint32_t edge_count, const uint32_t* patches, const uint8_t* edges,
                                             uint32_t count, const uint32_t* param, const uint32_t* first,
                                             float* positions);

/* Attributes at count grid points of one patch, with the grid and ij
 * arguments of tlod_surface_eval_grid(): corners are the vertex's values
 * exactly, edge points come from the canonical edge function (bitwise equal
 * on both patches of an edge that is not a seam), interior points are
 * barycentric (triangles: u * A_i + v * A_j + (1 - u - v) * A_k, u = i /
 * 2^g) or bilinear (quads). out: count * attribute_count vec4s, point k's
 * attribute a at out[k * attribute_count + a]. A mesh without attributes
 * writes nothing. Thread-safe; the checks of tlod_surface_eval_grid()
 * (NULL mesh, patch >= the patch count, grid_log2 > 15, ij NULL with count
 * > 0, a point off the grid; out NULL with attributes to write):
 * TLOD_ERROR_INVALID_ARGUMENT, nothing written, no last error recorded. */
TLOD_API tlod_result tlod_mesh_eval_attributes_grid(const tlod_mesh* mesh, uint32_t patch, uint32_t grid_log2,
                                                    const uint16_t* ij, size_t ij_stride, uint32_t count,
                                                    float (*out)[4]);

#ifdef __cplusplus
}
#endif
#endif /* TESSLOD_CORE_H */
