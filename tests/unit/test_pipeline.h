/* Shared by the contract tests: a shape's mesh, default surface, patterns
 * and scheduler in a context of one thread, made and freed together. */
#ifndef TLOD_TEST_PIPELINE_H
#define TLOD_TEST_PIPELINE_H

#include "shapes.h"
#include "tesslod/lod.h"
#include "test_context.h"

typedef struct test_pipeline {
  tlod_context* ctx;
  shape sh;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
  tlod_scheduler* sched;
} test_pipeline;

/* Frees everything, the context last; a half-made pipeline too. */
static inline void test_pipeline_free(test_pipeline* p) {
  tlod_scheduler_destroy(p->sched);
  tlod_patterns_destroy(p->pat);
  tlod_surface_destroy(p->surf);
  tlod_mesh_destroy(p->mesh);
  shape_free(&p->sh);
  tlod_context_destroy(p->ctx);
  memset(p, 0, sizeof *p);
}

/* Takes the shape; false when any step failed (free it anyway). */
static inline bool test_pipeline_make(test_pipeline* p, shape sh, uint32_t max_level, tlod_scheduler_desc sd) {
  memset(p, 0, sizeof *p);
  p->sh = sh;
  p->ctx = new_context(1, NULL, NULL);
  tlod_mesh_desc md = shape_mesh_desc(&p->sh);
  return p->ctx && tlod_mesh_create(p->ctx, &md, &p->mesh) == TLOD_SUCCESS &&
         tlod_surface_create(p->ctx, p->mesh, NULL, &p->surf) == TLOD_SUCCESS &&
         tlod_patterns_create(p->ctx, &(tlod_patterns_desc){.max_level = max_level}, &p->pat) == TLOD_SUCCESS &&
         tlod_scheduler_create(p->ctx, p->surf, p->pat, &sd, &p->sched) == TLOD_SUCCESS;
}

#endif
