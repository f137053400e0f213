/* Private to tesslod::core: a block of patches of one corner count as
 * structure-of-arrays lanes per corner (positions, normals, alphas as the
 * surface's corner gather gives them), shared by the kernels in lanes of
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

/* Lane r: the corners of a patch as _tlod_patch_corners() gathers them. */
static inline void _tlod_lanes_gather(const tlod_surface* s, _tlod_patch_lanes* L, uint32_t r, uint32_t patch) {
  _tlod_corners c;
  _tlod_patch_corners(s, patch, &c);
  for (uint32_t i = 0; i < c.n; i++) {
    L->px[i][r] = c.p[i].x, L->py[i][r] = c.p[i].y, L->pz[i][r] = c.p[i].z;
    L->nx[i][r] = c.nrm[i].x, L->ny[i][r] = c.nrm[i].y, L->nz[i][r] = c.nrm[i].z;
    L->alpha[i][r] = c.alpha[i];
  }
}

/* surface_spheres.c: the bounding spheres (center, radius) of Phong
 * patches without tables, bitwise build_phong_untabled's; the other fields
 * of their tlod_patch_info (every bound +INFINITY) do not depend on the
 * mesh and stay as the surface's creation wrote them. */
void _tlod_phong_spheres(const tlod_surface* s, tlod_simd simd, const uint32_t* patches, uint32_t count);

#endif
