/* Private to tesslod::core (and read by tests that say so): object layouts and plumbing. */
#ifndef TESSLOD_CORE_INTERNAL_H
#define TESSLOD_CORE_INTERNAL_H

#include <stdarg.h>

#include "tesslod/core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define _TLOD_PRINTF TLOD_PRINTF_FORMAT

typedef struct _tlod_pool _tlod_pool;

struct tlod_context {
  tlod_context_desc desc; /* resolved */
  _tlod_pool* pool;       /* NULL when desc.parallel_for.func is set or one thread */
  char label[64];
  char last_error[512];
};

/* Core's own spelling of the public context plumbing (tesslod/core.h,
 * "For the layers above core"): allocation through the context's hooks,
 * errors naming the element, logging, parallel-for, the clock. */
/* simd.c: the best instruction set of this processor; a desc's cap resolved. */
tlod_simd _tlod_simd_best(void);
tlod_simd _tlod_simd_resolve(tlod_simd wanted);

#define _tlod_alloc tlod_context_alloc
#define _tlod_calloc tlod_context_calloc
#define _tlod_free tlod_context_free
#define _tlod_fail tlod_context_fail
#define _tlod_log tlod_context_log
#define _tlod_now_ms tlod_now_ms
#define _tlod_parallel_for tlod_context_parallel_for
#define _tlod_worker_count tlod_context_worker_count

/* count elements of size bytes, not zeroed (for arrays every element of
 * which is written before it is read: the context's calloc is a memset
 * pass of its own); NULL where count * size overflows. */
static inline void* _tlod_alloc_array(const tlod_context* ctx, size_t count, size_t size) {
  return size != 0 && count > SIZE_MAX / size ? NULL : _tlod_alloc(ctx, count * size);
}

/* Built-in thread pool (thread_pool.c). */
tlod_result _tlod_pool_create(tlod_context* ctx, uint32_t threads, _tlod_pool** out);
void _tlod_pool_destroy(tlod_context* ctx, _tlod_pool* pool);
void _tlod_pool_run(_tlod_pool* pool, tlod_task_fn fn, void* data, uint32_t count);

#define _TLOD_NONE UINT32_MAX

struct tlod_mesh {
  tlod_context* ctx;
  char label[64];
  uint64_t generation;        /* tlod_mesh_view.generation */
  uint64_t smooth_generation; /* tlod_mesh_view.smooth_generation */
  tlod_mesh_desc desc;        /* resolved; array pointers cleared */

  uint32_t vertex_count;
  float (*positions)[3];
  float (*normals)[3];      /* unit length, always present */
  float* alphas;            /* per vertex, NULL when the desc had none */
  uint32_t* weld_id;        /* smallest vertex index with the same (welded) position */
  uint8_t* normal_computed; /* 1 where the normal was computed, not given */

  uint32_t face_count;        /* kept faces */
  uint32_t (*faces)[4];       /* corner vertex indices; [3] unused for triangles */
  uint8_t* face_corners;      /* 3 or 4 */
  uint32_t* face_input;       /* input face index */
  tlod_edge_link (*links)[4]; /* per face edge */

  /* Input vertex behind each vertex appended by a crease split (index
   * v - input_vertex_count); NULL when nothing was split. */
  uint32_t* split_source;

  /* Vertex attributes (mesh_attributes.c): vertex-major vec4s, padded
   * (0, 0, 0, 1); NULL when attribute_count is 0. */
  uint32_t attribute_count;
  float (*attributes)[4];
  tlod_attribute_info attribute_info[TLOD_MAX_ATTRIBUTES];

  /* Second-order nodes (mesh_nodes.c), all NULL when the desc had none:
   * per kept face the resolved nodes (given, or shared from the neighbour;
   * _TLOD_NONE), the bit mask of the slots the desc gave, and per vertex 1
   * for a node of some face that is a corner of none. */
  uint32_t (*face_nodes)[TLOD_FACE_NODES];
  uint8_t* node_given;
  uint8_t* node_only;

  /* Smooth normals' per-position sums (mesh_normals.c), made by the first
   * tlod_mesh_update that recomputes normals and kept: no allocation per
   * update. NULL before, and with creases. */
  double (*normal_sum)[4];

  tlod_mesh_info info;
  tlod_finding findings[TLOD_MAX_FINDINGS];
};

/* Adds a finding (counted past the limit). */
void _tlod_mesh_add_finding(tlod_mesh* mesh, tlod_finding_kind kind, uint32_t element, uint32_t element2,
                            const char* fmt, ...) _TLOD_PRINTF(5, 6);

/* mesh_adjacency.c: weld ids alone, and the smooth flags after normals change. */
tlod_result _tlod_mesh_weld(tlod_mesh* mesh);
void _tlod_mesh_refresh_smooth(tlod_mesh* mesh); /* smooth_generation grows if a flag moved */
/* mesh_normals.c: normals with crease splits; appended vertices' sources go
 * to *split_source. */
tlod_result _tlod_mesh_compute_normals_split(tlod_mesh* mesh, uint32_t** split_source);
/* mesh_angles.c: w[i] = the angle atan2(sqrt(y2[i]), x[i]) in [0, pi] (0
 * when both are 0), bitwise the same at every simd level. */
void _tlod_corner_angles(tlod_simd simd, const double* y2, const double* x, double* w, uint32_t n);
/* mesh_angles.c: the unit normals (and lengths of the area vectors) of up
 * to _TLOD_FACE_LANES faces in lanes, as mesh_normals.c face_cross: quads
 * the diagonals' cross product, triangles (corner 0 repeated as corner 3)
 * the edges'; redo = 1 where a quad's diagonals are near parallel (the
 * scalar code's two-triangle case); and the flat corners' y2 and x.
 * Bitwise the same at every level. */
enum { _TLOD_FACE_LANES = 64 };
typedef struct _tlod_face_lanes {
  double p[12][_TLOD_FACE_LANES]; /* corner c's x, y, z at rows 3c .. 3c + 2 */
  double quad[_TLOD_FACE_LANES];  /* 1 for a quad, 0 for a triangle */
  double n[3][_TLOD_FACE_LANES], len[_TLOD_FACE_LANES], redo[_TLOD_FACE_LANES];
  /* Flat corner c's tangents a = e_c, b = -e_prev (e_i = p_{i+1} - p_i):
   * |a x b|^2 and a . b, as mesh_normals.c's corner angles need them. */
  double y2[4][_TLOD_FACE_LANES], x[4][_TLOD_FACE_LANES];
} _tlod_face_lanes;
void _tlod_face_normals(tlod_simd simd, _tlod_face_lanes* lanes, uint32_t n);
/* Makes mesh->normal_sum (no creases): _tlod_mesh_compute_normals then
 * cannot fail. */
tlod_result _tlod_mesh_normals_prepare(tlod_mesh* mesh);
/* mesh_adjacency.c: fills weld_id, links and the edge counts of info. */
tlod_result _tlod_mesh_build_adjacency(tlod_mesh* mesh);
/* mesh_normals.c: computes normals of the vertices marked in normal_computed
 * (all when mode is ANGLE/AREA), with the desc's crease angle. */
tlod_result _tlod_mesh_compute_normals(tlod_mesh* mesh);

/* mesh_attributes.c: the desc's attributes checked before anything is
 * allocated (label names the mesh); copied after the crease splits (split
 * vertices take their source's values); whether two vertices carry bitwise
 * equal attributes (true without attributes). */
tlod_result _tlod_mesh_check_attributes(tlod_context* ctx, const char* label, const tlod_mesh_desc* d);
tlod_result _tlod_mesh_copy_attributes(tlod_mesh* mesh, const tlod_mesh_desc* d);
bool _tlod_mesh_same_attributes(const tlod_mesh* mesh, uint32_t a, uint32_t b);

/* mesh_nodes.c: the desc's face nodes checked before anything is allocated
 * (face_size 0: MIXED); copied for the kept faces (curved_faces counted,
 * node-only vertices marked); shared across linked edges after adjacency
 * (nodes_shared counted); whether a vertex is node-only; whether edge e of
 * f and edge ge of g carry bitwise equal node positions (or both none). */
tlod_result _tlod_mesh_check_nodes(tlod_context* ctx, const char* label, const tlod_mesh_desc* d, uint32_t face_size,
                                   uint32_t input_faces);
tlod_result _tlod_mesh_copy_nodes(tlod_mesh* mesh, const uint32_t* face_nodes);
void _tlod_mesh_share_nodes(tlod_mesh* mesh);
bool _tlod_mesh_is_node_only(const tlod_mesh* mesh, uint32_t v);
bool _tlod_mesh_same_nodes(const tlod_mesh* mesh, uint32_t f, uint32_t e, uint32_t g, uint32_t ge);

/* Per-patch precomputed data of a quadratic face (quadratic.c): the
 * resolved nodes M0..M3 of its edges and its centre C (quads), and whether
 * the face had a given node (the record's info[1]). */
typedef struct _tlod_quad_patch {
  float node[5][3];
  uint32_t given;
} _tlod_quad_patch;

/* Per-patch precomputed data of a PN triangle: 10 cubic control points and
 * the 3 quadratic normal-field mid-edge normals. Order:
 * b300 b030 b003 b210 b120 b021 b012 b102 b201 b111 (corners i, j, k). */
typedef struct _tlod_pn_patch {
  float b[10][3];
  float n[3][3]; /* n110, n011, n101 */
} _tlod_pn_patch;

struct tlod_surface {
  tlod_context* ctx;
  const tlod_mesh* mesh;
  tlod_surface_desc desc; /* resolved */
  uint32_t patch_count;
  tlod_patch_info* info;
  _tlod_pn_patch* pn;     /* PN only */
  _tlod_quad_patch* quad; /* QUADRATIC only */
  float* alpha;           /* per mesh vertex: the shape factor used */
  float (*snapshot)[6];   /* vertex positions and normals the patches were built from */
  uint8_t* changed;       /* tlod_surface_refresh's flags, per vertex then per patch; made at the first */
  char label[64];
  uint64_t generation; /* tlod_surface_view.generation */
};

/* One canonical edge function (docs/design.md invariant 1): the point at
 * parameter t from mesh vertex a to vertex b, where weld_id[a] < weld_id[b].
 * The same inputs give bitwise equal outputs on every patch sharing the edge. */
void _tlod_edge_eval(const tlod_surface* s, uint32_t a, uint32_t b, float t, float pos[3], float nrm[3]);
/* Point on edge e of a patch, t_end = weight of the edge's end corner
 * ((e + 1) % n); corners are returned exactly, other points through
 * _tlod_edge_eval in canonical direction. */
void _tlod_patch_edge_point(const tlod_surface* s, uint32_t patch, uint32_t edge, float t_end, float pos[3],
                            float nrm[3]);
/* General (interior) evaluation with no edge routing. */
void _tlod_patch_eval(const tlod_surface* s, uint32_t patch, float u, float v, tlod_surface_point* out);

#ifdef __cplusplus
}
#endif
#endif
