/*
 * tesslod/cpu.h -- CPU reference tessellator (module tesslod::cpu)
 *
 * WHAT IT DOES
 *   Evaluates a surface through the refinement patterns of tesslod/lod.h and
 *   returns a plain indexed triangle mesh: positions, unit shading normals,
 *   the patch each triangle came from. Each patch may have its own level;
 *   where the two sides of an edge differ (levels, or split normals at a
 *   crease) a connection strip zips the two edge polylines together, so a
 *   closed input gives a closed output. Points are evaluated with
 *   tlod_surface_eval_grid() (corners exact, edge points through the
 *   canonical edge function), so the mesh is what a GPU backend draws. The
 *   "cpu" device of tesslod/backend.h is this tessellator behind the device
 *   API (its meshes: tlod_cpu_device_mesh()).
 *
 * DOES NOT
 *   - draw, or know about GPUs;
 *   - decide levels (give a level, levels per patch, or a scheduler's draw
 *     list);
 *   - read core's private data: it uses the public views of tesslod/core.h
 *     only, like any module built on core.
 *
 * STEP BY STEP
 *   1. tlod_patterns_create() reaching the largest level asked for;
 *   2. tlod_cpu_tessellate(ctx, surface, patterns, &(tlod_cpu_tessellate_desc){
 *      .level = 3 }, &mesh), or .draw_list = tlod_scheduler_draw_list(...);
 *   3. per frame: tlod_cpu_tessellate_into(ctx, ..., mesh) reuses the arrays;
 *   4. tlod_cpu_mesh_destroy(ctx, mesh).
 *
 * THREADING AND ALLOCATION
 *   One call at a time per context. Work is spread over the context's
 *   parallel-for (tlod_context_parallel_for()); the result does not depend
 *   on the thread count. Every allocation, the result's arrays included,
 *   goes through the context's allocator; _into grows the arrays only when
 *   they are too small.
 *
 * OUTPUT VERTICES
 *   welded (default): a vertex shared by several patches is emitted once when
 *     its position, normal, alpha and attributes are the same on every side
 *     (at a crease or an attribute seam each side keeps its own vertex; their
 *     positions are bitwise equal).
 *   no_weld: every patch emits its own pattern vertices, as a GPU draws them;
 *     invariant 1 (docs/design.md) makes shared positions bitwise equal, so
 *     welding the output by exact position gives back a closed mesh.
 *
 * FAST PATH (default; .reference = true turns it off)
 *   The output is bitwise the reference evaluator's for every surface type,
 *   level, draw list, option, instruction set (tlod_context_simd(), chosen
 *   by the context desc's .simd) and thread count. Interior points go
 *   through tlod_surface_eval_interior() (vectorised kernels per patch),
 *   each shared edge point is evaluated once, by its owner, through the
 *   canonical edge function; corners come from the mesh; indices are the
 *   pattern's template plus the patch's offset, remapped only where they
 *   name a corner or edge point. A patch with a geomorph blend below 1,
 *   attributes, or no_weld takes the point-by-point write of the reference
 *   after the same vectorised evaluation. With no_normals the positions of
 *   many patches go in lanes across patches and across edges
 *   (tlod_surface_eval_interiors(), tlod_surface_eval_edges(): a coarse
 *   level has too few points per patch or edge to fill lanes), bitwise the
 *   per-patch calls.
 *
 * KEPT TOPOLOGY (tlod_cpu_tessellate_into, fast path)
 *   The mesh remembers the topology of its last call: when the levels (or
 *   the draw list's levels, and the edges its blends make shared), the
 *   surface mesh's faces, edge links (creases, seams, smooth flags), weld
 *   ids and the order its split vertices' normals and alphas sort in, the
 *   pattern grid, the thread count and no_weld are the same (compared
 *   exactly, against copies), the indices, triangle_patch, vertex_patch and
 *   vertex_uv are left as written and only positions and normals are
 *   rewritten (strips are redone: their folds compare positions). The
 *   result is bitwise what a fresh call gives. Hence the arrays of a mesh
 *   passed to _into are read-only to the caller. Meshes with attributes and .reference calls always take the
 *   full path. A kept no_normals call without a draw list evaluates from
 *   two lists made at the first such call (the owned edges and the patches
 *   with interior points, with their output ids).
 *
 * VERTEX ATTRIBUTES AND (PATCH, U, V)
 *   Every output vertex carries the mesh's attributes (tesslod/core.h,
 *   "Vertex attributes"), evaluated with tlod_mesh_eval_attributes_grid() at
 *   the vertex's pattern point: corners exact, edge points bitwise equal on
 *   both sides of an edge that is not a seam, interiors barycentric /
 *   bilinear. Welding also requires equal attributes: on a seam (a smooth
 *   edge with split attributes, tlod_edge_link.seam) each side keeps its own
 *   vertices, at bitwise equal positions, and no strip is needed when both
 *   sides have one level. Connection strips take every attribute from side
 *   a of the strip (the patch whose edge comes first: patch_a of a draw
 *   list strip, else the smaller patch): a point of b's polyline whose
 *   attributes differ from a's at that edge point (a seam, or a crease with
 *   split attributes) gets an extra output vertex, b's position and normal
 *   with a's attributes, so no strip smears two sides of a seam (the GL
 *   strips do the same). Attributes are not geomorphed: they are affine in
 *   (u, v) on triangles, so a new vertex's own value already equals the
 *   parents' midpoint it starts from and blending would only cost time; on
 *   quads the same holds for parents along a u or v line, and diagonal
 *   parents differ by the bilinear twist term (a slight change of the
 *   texture lookup while blending, never a gap: positions alone decide
 *   closedness).
 *   vertex_patch / vertex_uv give each output vertex's patch and (u, v) on
 *   it (core.h PARAMETERS): the patch that evaluated it (a welded corner:
 *   the first drawn patch having it; a strip's extra vertex: b's patch), so
 *   tlod_surface_eval(surface, vertex_patch[v], u, v) gives its position
 *   (bitwise for every point without a geomorph blend below 1). Corners no
 *   drawn patch uses (unused mesh vertices, patches left out) have patch
 *   UINT32_MAX and (u, v) (0, 0). A mesh without attributes costs nothing
 *   more than the (patch, u, v) writes.
 */
#ifndef TESSLOD_CPU_H
#define TESSLOD_CPU_H

#include "tesslod/core.h"
#include "tesslod/lod.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tlod_cpu_tessellate_desc {
  uint32_t level;       /* uniform level when levels == NULL */
  const int8_t* levels; /* optional: level per patch; -1 leaves the patch out */
  /* optional: a scheduler's draw list (tesslod/lod.h) realised exactly: its
   * levels, geomorph blends and strips; level and levels are then ignored. */
  const tlod_draw_list* draw_list;
  bool no_weld;    /* see OUTPUT VERTICES */
  bool no_stitch;  /* leave out connection strips (shows the cracks) */
  bool no_normals; /* skip the normal evaluation */
  /* The straightforward evaluator, point by point: the oracle the fast path
   * (FAST PATH above) is tested against; same output, bit for bit. */
  bool reference;
} tlod_cpu_tessellate_desc;

typedef struct tlod_cpu_mesh {
  uint32_t vertex_count;
  float* positions; /* xyz per vertex */
  float* normals;   /* xyz per vertex; NULL with no_normals */
  uint32_t triangle_count;
  uint32_t* indices;                           /* 3 per triangle, counter-clockwise as the input */
  uint32_t* triangle_patch;                    /* patch of each triangle; UINT32_MAX for strip triangles */
  uint32_t pattern_triangles;                  /* triangles from refinement patterns */
  uint32_t strip_triangles;                    /* triangles from connection strips */
  uint32_t strips;                             /* edges that needed a strip */
  uint32_t folds_skipped;                      /* strip triangles left out: two corners at one position */
  uint32_t vertex_capacity, triangle_capacity; /* allocated, for tlod_cpu_tessellate_into */
  /* See VERTEX ATTRIBUTES: attribute_count vec4s per vertex, vertex v's
   * attribute a at [v * attribute_count + a] (the mesh view's layout); NULL
   * without attributes. */
  uint32_t attribute_count;
  float (*attributes)[4];
  uint32_t* vertex_patch; /* patch (kept face) of each output vertex, UINT32_MAX for an unused corner */
  float (*vertex_uv)[2];  /* (u, v) of each output vertex on vertex_patch */
  /* Private: the kept topology (KEPT TOPOLOGY), made by the first _into
   * call through the context's allocator; NULL in a zeroed struct. */
  struct tlod_cpu_keep* keep;
} tlod_cpu_mesh;

/* Tessellates every patch of the surface. patterns must reach the largest
 * level asked for. The result is allocated through the context's allocator
 * and freed with tlod_cpu_mesh_destroy(). */
TLOD_API tlod_result tlod_cpu_tessellate(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                                         const tlod_cpu_tessellate_desc* desc, tlod_cpu_mesh** out);
/* The same into a mesh from an earlier call (or a zeroed struct), whose arrays are reused when large
 * enough and grown otherwise: a per-frame caller then pays no allocation or
 * page faults, and an unchanged topology is not rewritten (KEPT TOPOLOGY).
 * On failure the mesh is left empty (counts 0). */
TLOD_API tlod_result tlod_cpu_tessellate_into(tlod_context* ctx, const tlod_surface* surface,
                                              const tlod_patterns* patterns, const tlod_cpu_tessellate_desc* desc,
                                              tlod_cpu_mesh* mesh);
TLOD_API void tlod_cpu_mesh_destroy(tlod_context* ctx, tlod_cpu_mesh* mesh);

#ifdef __cplusplus
}
#endif
#endif
