/* Shared by the unit and GL tests of the lod module: the surface types'
 * short names and the scheduler calls that print the library's reason when
 * they fail (the caller checks the NULL). */
#ifndef TLOD_TEST_LOD_H
#define TLOD_TEST_LOD_H

#include <stdio.h>
#include <string.h>

#include "tesslod/lod.h"

static inline const char* type_name(tlod_surface_type t) {
  return t == TLOD_SURFACE_FLAT        ? "flat"
         : t == TLOD_SURFACE_PN        ? "pn"
         : t == TLOD_SURFACE_QUADRATIC ? "quadratic"
                                       : "phong";
}

/* A scheduler, or NULL with the reason printed. */
static inline tlod_scheduler* scheduler_create(tlod_context* ctx, const tlod_surface* surf, const tlod_patterns* pat,
                                               tlod_scheduler_desc d) {
  tlod_scheduler* s = NULL;
  tlod_result r = tlod_scheduler_create(ctx, surf, pat, &d, &s);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_scheduler_create: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
    return NULL;
  }
  return s;
}

/* One frame; its first view's draw list, or NULL with the reason printed. */
static inline const tlod_draw_list* scheduler_plan(tlod_context* ctx, tlod_scheduler* s, const tlod_frame_desc* f) {
  tlod_result r = tlod_scheduler_update(s, f);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_scheduler_update: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
    return NULL;
  }
  return tlod_scheduler_draw_list(s, 0);
}

/* Whether two draw lists are bitwise equal in everything but stage_ms
 * (vertices: the mesh's vertex count); else why, in why[n]. */
static inline bool draw_lists_equal(const tlod_draw_list* a, const tlod_draw_list* b, uint32_t vertices, char* why,
                                    size_t n) {
#define DIFF(cond, what)                                                                                               \
  do {                                                                                                                 \
    if (cond) {                                                                                                        \
      snprintf(why, n, "%s", what);                                                                                    \
      return false;                                                                                                    \
    }                                                                                                                  \
  } while (0)
  DIFF(a->patch_count != b->patch_count || a->instance_count != b->instance_count ||
           a->bucket_count != b->bucket_count || a->strip_count != b->strip_count,
       "counts differ");
  DIFF(memcmp(a->levels, b->levels, a->patch_count) != 0, "levels differ");
  DIFF(memcmp(a->e_max, b->e_max, sizeof(float) * a->patch_count) != 0, "e_max differs");
  DIFF(memcmp(a->vertex_depth, b->vertex_depth, sizeof(float) * vertices) != 0, "vertex depths differ");
  DIFF(memcmp(a->instances, b->instances, sizeof(tlod_draw_instance) * a->instance_count) != 0, "instances differ");
  DIFF(memcmp(a->buckets, b->buckets, sizeof(tlod_draw_bucket) * a->bucket_count) != 0, "buckets differ");
  for (uint32_t k = 0; k < a->strip_count; ++k) {
    const tlod_draw_strip *x = &a->strips[k], *y = &b->strips[k];
    DIFF(x->patch_a != y->patch_a || x->patch_b != y->patch_b || x->edge_a != y->edge_a || x->edge_b != y->edge_b ||
             x->level_a != y->level_a || x->level_b != y->level_b || x->crease != y->crease,
         "strips differ");
  }
  DIFF(a->pattern_triangles != b->pattern_triangles || a->strip_triangles != b->strip_triangles ||
           a->culled != b->culled || memcmp(a->level_histogram, b->level_histogram, sizeof a->level_histogram) != 0,
       "statistics differ");
  DIFF(memcmp(&a->e_max_min, &b->e_max_min, sizeof(float)) != 0 ||
           memcmp(&a->e_max_max, &b->e_max_max, sizeof(float)) != 0 ||
           memcmp(&a->effective_epsilon, &b->effective_epsilon, sizeof(float)) != 0,
       "e_max range or effective epsilon differ");
#undef DIFF
  return true;
}

#endif
