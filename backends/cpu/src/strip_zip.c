/* tesslod::cpu -- connection strips: zipping two edge polylines by parameter.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006 (connection
 *   patterns between refinement patterns of different levels). */
#include "cpu_internal.h"

uint32_t _tlod_zip_polylines(const uint32_t* ta, uint32_t na, const uint32_t* tb, uint32_t nb, uint32_t (*out)[3]) {
  uint32_t i = 0, j = 0, count = 0;
  const uint32_t b0 = na + 1;
  while (i < na || j < nb) {
    /* Advance the side whose next point comes first; ties go to a, so the
     * result is the same on every run. */
    bool step_a = j == nb || (i < na && ta[i + 1] <= tb[j + 1]);
    if (step_a) {
      out[count][0] = i + 1;
      out[count][1] = i;
      out[count][2] = b0 + j;
      i++;
    } else {
      out[count][0] = b0 + j;
      out[count][1] = b0 + j + 1;
      out[count][2] = i;
      j++;
    }
    count++;
  }
  return count;
}
