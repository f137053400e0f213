/* Linear blend skinning on the CPU for the tools (glTF 2.0 section 3.7.3
 * "Skins"): each vertex moves by sum_j w_j * (jointWorld_j * inverseBind_j)
 * of its four joints, its normal by the inverse transpose of that blend.
 * The skinned arrays then go into the tesslod mesh (tlod_mesh_update) and
 * surface (tlod_surface_refresh), which recompute only the patches that
 * touch a changed vertex. Why on the CPU: docs/play.md "Skinning". */
#ifndef TLOD_TOOLS_SKIN_APPLY_H
#define TLOD_TOOLS_SKIN_APPLY_H

#include <stdint.h>

#include "tesslod/core.h"

typedef struct skin_vertices {
  uint32_t vertex_count;
  const float* rest_positions; /* xyz per vertex, mesh space */
  const float* rest_normals;   /* xyz per vertex; NULL: no normals skinned */
  const uint16_t* joints;      /* 4 per vertex, indices into the joint matrices */
  const float* weights;        /* 4 per vertex, summing to 1 (the importer renormalises) */
} skin_vertices;

/* out[j] = joint_world[j] * inverse_bind[j]: the skinning matrices of a pose. */
void skin_joint_matrices(uint32_t joint_count, const float (*joint_world)[16], const float (*inverse_bind)[16],
                         float (*out)[16]);
/* Skins vertices [begin, end) into positions / normals (xyz per vertex,
 * indexed from 0 like the rest arrays). A joint index >= joint_count adds
 * nothing; a vertex whose weights add to 0 keeps its rest position and
 * normal, as does a normal whose blend is singular. Each vertex depends
 * only on its own inputs, so any split into ranges gives the same bits. */
void skin_range(const skin_vertices* v, uint32_t joint_count, const float (*joint_matrices)[16], uint32_t begin,
                uint32_t end, float* positions, float* normals);
/* skin_range over every vertex on ctx's workers (tlod_context_parallel_for,
 * chunks of 1024 vertices). */
void skin_apply(const tlod_context* ctx, const skin_vertices* v, uint32_t joint_count,
                const float (*joint_matrices)[16], float* positions, float* normals);

#endif
