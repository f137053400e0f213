/* Shared by the unit and GL tests of the lod module: the surface types'
 * short names and the scheduler calls that print the library's reason when
 * they fail (the caller checks the NULL). */
#ifndef TLOD_TEST_LOD_H
#define TLOD_TEST_LOD_H

#include <stdio.h>

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

#endif
