/* tesslod::lod -- where a pattern vertex lies on its patch (corner, edge with
 * its exact edge parameter, interior): what routes it to the canonical edge
 * function on the CPU and in the shaders alike. */
#include "tesslod/lod.h"

uint32_t tlod_pattern_vertex_kind(tlod_pattern_shape shape, uint32_t max_level, uint32_t i, uint32_t j,
                                  uint32_t* param) {
  uint32_t nn = 1u << max_level;
  if (shape == TLOD_PATTERN_TRIANGLE) {
    uint32_t w = nn - i - j;
    if (i == nn || j == nn || w == nn) return i == nn ? 0u : (j == nn ? 1u : 2u);
    if (w == 0) return *param = j, TLOD_PATTERN_KIND_EDGE + 0; /* i -> j: weight of j */
    if (i == 0) return *param = w, TLOD_PATTERN_KIND_EDGE + 1; /* j -> k: weight of k */
    if (j == 0) return *param = i, TLOD_PATTERN_KIND_EDGE + 2; /* k -> i: weight of i */
    return TLOD_PATTERN_KIND_INTERIOR;
  }
  bool ei = i == 0 || i == nn, ej = j == 0 || j == nn;
  if (ei && ej) return i == 0 ? (j == 0 ? 0u : 3u) : (j == 0 ? 1u : 2u);
  if (j == 0) return *param = i, TLOD_PATTERN_KIND_EDGE + 0;       /* 0 -> 1 */
  if (i == nn) return *param = j, TLOD_PATTERN_KIND_EDGE + 1;      /* 1 -> 2 */
  if (j == nn) return *param = nn - i, TLOD_PATTERN_KIND_EDGE + 2; /* 2 -> 3 */
  if (i == 0) return *param = nn - j, TLOD_PATTERN_KIND_EDGE + 3;  /* 3 -> 0 */
  return TLOD_PATTERN_KIND_INTERIOR;
}
