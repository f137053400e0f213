/* tesslod::lod -- connection patterns: strips zipping two edge polylines.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006, sec. 4 (connection
 *   patterns generated once per level pair and kept for every strip). */
#include "patterns_internal.h"

/* Zips a (points 0..na) and b (0..nb, in a's direction) by their parameters
 * i / na and j / nb, compared exactly as i * nb vs j * na. Ties advance a,
 * so the pattern is the same on every run. The first triangle touches both
 * first points and the last both last points: the shared corners make them
 * degenerate, so they are left out. */
static uint32_t zip(uint32_t na, uint32_t nb, uint32_t (*out)[3]) {
  uint32_t i = 0, j = 0, count = 0;
  const uint32_t b0 = na + 1;
  while (i < na || j < nb) {
    bool step_a = j == nb || (i < na && (uint64_t)(i + 1) * nb <= (uint64_t)(j + 1) * na);
    uint32_t tri[3];
    if (step_a) {
      tri[0] = i + 1, tri[1] = i, tri[2] = b0 + j;
      i++;
    } else {
      tri[0] = b0 + j, tri[1] = b0 + j + 1, tri[2] = i;
      j++;
    }
    bool first_corner = (tri[0] == 0 || tri[1] == 0 || tri[2] == 0) && (tri[0] == b0 || tri[1] == b0 || tri[2] == b0);
    bool last_corner =
        (tri[0] == na || tri[1] == na || tri[2] == na) && (tri[0] == b0 + nb || tri[1] == b0 + nb || tri[2] == b0 + nb);
    if (first_corner || last_corner) continue;
    out[count][0] = tri[0], out[count][1] = tri[1], out[count][2] = tri[2];
    count++;
  }
  return count;
}

tlod_result _tlod_patterns_build_connections(tlod_patterns* p) {
  for (uint32_t la = 0; la <= p->max_level; la++) {
    for (uint32_t lb = 0; lb <= p->max_level; lb++) {
      uint32_t na = 1u << la, nb = 1u << lb;
      p->connect[la][lb] = tlod_context_alloc(p->ctx, sizeof(uint32_t[3]) * (na + nb));
      if (!p->connect[la][lb])
        return tlod_context_fail(p->ctx, TLOD_ERROR_OUT_OF_MEMORY,
                                 "tlod_patterns_create: out of memory (connection patterns)");
      p->connect_count[la][lb] = zip(na, nb, p->connect[la][lb]);
    }
  }
  return TLOD_SUCCESS;
}

void _tlod_patterns_free_connections(tlod_patterns* p) {
  for (uint32_t la = 0; la <= TLOD_MAX_LEVEL; la++)
    for (uint32_t lb = 0; lb <= TLOD_MAX_LEVEL; lb++)
      tlod_context_free(p->ctx, p->connect[la][lb]);
}

const uint32_t* tlod_patterns_connection(const tlod_patterns* p, uint32_t la, uint32_t lb, uint32_t* triangle_count) {
  bool ok = p && la <= p->max_level && lb <= p->max_level;
  if (triangle_count) *triangle_count = ok ? p->connect_count[la][lb] : 0;
  return ok ? &p->connect[la][lb][0][0] : NULL;
}
