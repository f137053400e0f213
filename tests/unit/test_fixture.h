/* Shared by unit tests: one shape's mesh, surface and patterns (max level 6)
 * in a context, made and freed with the library's reason printed. */
#ifndef TLOD_TEST_FIXTURE_H
#define TLOD_TEST_FIXTURE_H

#include <stdio.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/lod.h"

typedef struct fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
} fixture;

static inline void fixture_free(fixture* fx) {
  tlod_surface_destroy(fx->surf);
  tlod_mesh_destroy(fx->mesh);
  tlod_patterns_destroy(fx->pat);
  fx->surf = NULL, fx->mesh = NULL, fx->pat = NULL;
}

/* Mesh, surface and patterns (max level 6) of a shape in ctx; false with the
 * reason printed (and nothing left allocated). */
static inline bool fixture_make(fixture* fx, tlod_context* ctx, const shape* s, tlod_surface_type type) {
  memset(fx, 0, sizeof *fx);
  fx->ctx = ctx;
  tlod_mesh_desc md = shape_mesh_desc(s);
  tlod_result r = tlod_mesh_create(ctx, &md, &fx->mesh);
  if (r == TLOD_SUCCESS) r = tlod_surface_create(ctx, fx->mesh, &(tlod_surface_desc){.type = type}, &fx->surf);
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 6}, &fx->pat);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "fixture %s: %s: %s\n", s->name, tlod_result_string(r), tlod_context_last_error(ctx));
    fixture_free(fx);
    return false;
  }
  return true;
}

/* lod.h: vertex_depth holds d_i for every vertex of a visible patch (the
 * others only culled patches use may be stale on the fast path): those,
 * bitwise. */
static inline bool visible_depths_equal(const tlod_draw_list* a, const tlod_draw_list* b, const tlod_mesh* m) {
  for (uint32_t q = 0; q < a->instance_count; q++) {
    uint32_t c[4], n = tlod_mesh_face_corners(m, a->instances[q].patch, c);
    for (uint32_t j = 0; j < n; j++)
      if (memcmp(&a->vertex_depth[c[j]], &b->vertex_depth[c[j]], sizeof(float))) return false;
  }
  return true;
}

#endif
