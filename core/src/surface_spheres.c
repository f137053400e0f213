/* tesslod::core -- the bounding spheres of Phong surfaces without error
 * tables (TLOD_ERROR_TABLES_NONE), at creation and on a refresh: the only
 * per-patch values such a patch computes, and the only ones that move with
 * the mesh. Computed for a block of patches at once by the kernel of
 * surface_spheres.inc (per instruction set), which states the rule; every
 * level gives the same bits. */
#include <math.h>

#include "patch_lanes.h"

typedef void (*sphere_kernel)(const _tlod_patch_lanes* L, uint32_t n, float* restrict center_x,
                              float* restrict center_y, float* restrict center_z, float* restrict radius);

#define KERNEL_FILE "surface_spheres.inc"
#include "simd_instances.inc"
#undef KERNEL_FILE

void _tlod_phong_spheres(const tlod_surface* s, tlod_simd simd, const uint32_t* patches, uint32_t count) {
  sphere_kernel k = KERNEL_FOR(spheres, simd);
  const uint8_t* corners = s->mesh->face_corners;
  _tlod_patch_lanes L;
  float cx[PATCH_LANES], cy[PATCH_LANES], cz[PATCH_LANES], radius[PATCH_LANES];
  for (uint32_t at = 0, n; at < count; at += n) {
    L.corners = corners[patches[at]];
    for (n = 0; at + n < count && n < PATCH_LANES && corners[patches[at + n]] == L.corners; n++)
      _tlod_lanes_gather(s, &L, n, patches[at + n]);
    k(&L, n, cx, cy, cz, radius);
    for (uint32_t r = 0; r < n; r++) {
      tlod_patch_info* info = &s->info[patches[at + r]];
      info->center[0] = cx[r], info->center[1] = cy[r], info->center[2] = cz[r];
      info->radius = radius[r];
    }
  }
}
