/* tesslod::lod -- connection patterns: strips zipping two edge polylines.
 *
 * This work is based on:
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006, sec. 4 (connection
 *   patterns generated once per level pair and kept for every strip). */
#include "patterns_internal.h"

/* Whether point references r and q are a point of a and one of b at the
 * same parameter (i / na == j / nb, compared as i * nb == j * na). */
static bool same_parameter(uint32_t na, uint32_t nb, uint32_t r, uint32_t q) {
  if ((r <= na) == (q <= na)) return false;
  uint32_t i = r <= na ? r : q, j = (r <= na ? q : r) - na - 1;
  return (uint64_t)i * nb == (uint64_t)j * na;
}

/* A triangle left out: one with both first or both last points (the
 * shared corners: degenerate on every edge), or, exact, any with a point
 * of a and one of b at the same parameter. */
static bool left_out(uint32_t na, uint32_t nb, const uint32_t tri[3], bool exact) {
  for (int k = 0; k < 3; k++) {
    uint32_t r = tri[k], q = tri[(k + 1) % 3];
    if (!same_parameter(na, nb, r, q)) continue;
    uint32_t i = r <= na ? r : q;
    if (exact || i == 0 || i == na) return true;
  }
  return false;
}

/* Zips a (points 0..na) and b (0..nb, in a's direction) by their parameters
 * i / na and j / nb, compared exactly as i * nb vs j * na. Ties advance a,
 * so the pattern is the same on every run. Triangles left_out() are not
 * written. */
static uint32_t zip(uint32_t na, uint32_t nb, bool exact, uint32_t (*out)[3]) {
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
    if (left_out(na, nb, tri, exact)) continue;
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
      p->connect_exact[la][lb] = tlod_context_alloc(p->ctx, sizeof(uint32_t[3]) * (na + nb));
      if (!p->connect[la][lb] || !p->connect_exact[la][lb])
        return tlod_context_fail(p->ctx, TLOD_ERROR_OUT_OF_MEMORY,
                                 "tlod_patterns_create: out of memory (connection patterns)");
      p->connect_count[la][lb] = zip(na, nb, false, p->connect[la][lb]);
      p->connect_exact_count[la][lb] = zip(na, nb, true, p->connect_exact[la][lb]);
    }
  }
  return TLOD_SUCCESS;
}

void _tlod_patterns_free_connections(tlod_patterns* p) {
  for (uint32_t la = 0; la <= TLOD_MAX_LEVEL; la++)
    for (uint32_t lb = 0; lb <= TLOD_MAX_LEVEL; lb++)
      tlod_context_free(p->ctx, p->connect[la][lb]), tlod_context_free(p->ctx, p->connect_exact[la][lb]);
}

/* One (la, lb) entry of a family of connection patterns, checked. */
static const uint32_t* connection_of(const tlod_patterns* p, bool exact, uint32_t la, uint32_t lb, uint32_t* count) {
  bool ok = p && la <= p->max_level && lb <= p->max_level;
  if (count) *count = ok ? (exact ? p->connect_exact_count : p->connect_count)[la][lb] : 0;
  return ok ? &(exact ? p->connect_exact : p->connect)[la][lb][0][0] : NULL;
}

const uint32_t* tlod_patterns_connection(const tlod_patterns* p, uint32_t la, uint32_t lb, uint32_t* triangle_count) {
  return connection_of(p, false, la, lb, triangle_count);
}

const uint32_t* tlod_patterns_connection_exact(const tlod_patterns* p, uint32_t la, uint32_t lb,
                                               uint32_t* triangle_count) {
  return connection_of(p, true, la, lb, triangle_count);
}

const uint32_t* tlod_draw_strip_connection(const tlod_patterns* p, const tlod_draw_strip* strip,
                                           uint32_t* triangle_count) {
  if (!strip) {
    if (triangle_count) *triangle_count = 0;
    return NULL;
  }
  return connection_of(p, strip->exact, strip->level_a, strip->level_b, triangle_count);
}
