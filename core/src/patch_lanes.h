/* Private to tesslod::core: a block of patches of one corner count as
 * structure-of-arrays lanes per corner (positions, normals, alphas as the
 * surface's corner gather gives them; L->corners is the block's corner
 * count, set before the gather), shared by the kernels in lanes of
 * patches (surface_interiors.c, surface_spheres.c). */
#ifndef TESSLOD_PATCH_LANES_H
#define TESSLOD_PATCH_LANES_H

#include "surface_eval.h"

enum { PATCH_LANES = 64 };

typedef struct _tlod_patch_lanes {
  uint32_t corners;
  float px[4][PATCH_LANES], py[4][PATCH_LANES], pz[4][PATCH_LANES];
  float nx[4][PATCH_LANES], ny[4][PATCH_LANES], nz[4][PATCH_LANES];
  float alpha[4][PATCH_LANES];
} _tlod_patch_lanes;

/* Lane r: the corners of a patch as _tlod_patch_corners() gathers them,
 * read straight from the mesh into the lanes (no _tlod_corners between). */
static inline void _tlod_lanes_gather(const tlod_surface* s, _tlod_patch_lanes* L, uint32_t r, uint32_t patch) {
  const tlod_mesh* m = s->mesh;
  for (uint32_t i = 0; i < L->corners; i++) {
    uint32_t v = m->faces[patch][i];
    const float *p = m->positions[v], *n = m->normals[v];
    L->px[i][r] = p[0], L->py[i][r] = p[1], L->pz[i][r] = p[2];
    L->nx[i][r] = n[0], L->ny[i][r] = n[1], L->nz[i][r] = n[2];
    L->alpha[i][r] = s->alpha[v];
  }
}

/* surface_spheres.c: the bounding spheres (center, radius) of Phong
 * patches without tables (surface_spheres.inc states the rule), at creation
 * and on a refresh; the other fields of their tlod_patch_info (every bound
 * +INFINITY) do not depend on the mesh and are written by surface.c. */
void _tlod_phong_spheres(const tlod_surface* s, tlod_simd simd, const uint32_t* patches, uint32_t count);

#endif
