/* A downstream C11 program built only against an installed tesslod (tests/install):
 * context -> 2-triangle mesh -> Phong surface -> patterns -> CPU tessellation at level 2.
 * Two triangles at level 2 give 2 * 4^2 = 32 triangles (a flat square: no crease, no strip).
 * Built with TLOD_CONSUMER_GL=1 (the GL backend is installed), it also draws the square with the
 * "gl" backend in a headless EGL context (consumer_gl.c). */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <tesslod/core.h>
#include <tesslod/cpu.h>
#include <tesslod/lod.h>

#if TLOD_CONSUMER_GL
#include "consumer_gl.h"
#endif

static tlod_context* g_ctx;

static int fail(const char* what, tlod_result r) {
  fprintf(stderr, "consumer: %s failed: %s: %s\n", what, tlod_result_string(r),
          g_ctx ? tlod_context_last_error(g_ctx) : "");
  return EXIT_FAILURE;
}

int main(void) {
  /* The unit square in z = 0, split along its diagonal, counter-clockwise. */
  static const float positions[4 * 3] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  static const float normals[4 * 3] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  static const uint32_t indices[2 * 3] = {0, 1, 2, 0, 2, 3};
  const uint32_t level = 2;
  const uint32_t expected = 32;

  tlod_result r = tlod_context_create(&(tlod_context_desc){.label = "consumer"}, &g_ctx);
  if (r != TLOD_SUCCESS) return fail("tlod_context_create", r);

  tlod_mesh* mesh = NULL;
  r = tlod_mesh_create(g_ctx,
                       &(tlod_mesh_desc){.positions = positions,
                                         .normals = normals,
                                         .vertex_count = 4,
                                         .indices = indices,
                                         .index_count = 6,
                                         .face_type = TLOD_FACE_TRIANGLES,
                                         .label = "square"},
                       &mesh);
  if (r != TLOD_SUCCESS) return fail("tlod_mesh_create", r);

  tlod_surface* surface = NULL;
  r = tlod_surface_create(g_ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &surface);
  if (r != TLOD_SUCCESS) return fail("tlod_surface_create", r);

  tlod_patterns* patterns = NULL;
  r = tlod_patterns_create(g_ctx, &(tlod_patterns_desc){.max_level = level}, &patterns);
  if (r != TLOD_SUCCESS) return fail("tlod_patterns_create", r);

  tlod_cpu_mesh* out = NULL;
  r = tlod_cpu_tessellate(g_ctx, surface, patterns, &(tlod_cpu_tessellate_desc){.level = level}, &out);
  if (r != TLOD_SUCCESS) return fail("tlod_cpu_tessellate", r);

  int ok = out->triangle_count == expected;
  for (uint32_t i = 0; ok && i < out->vertex_count * 3; i++)
    ok = isfinite(out->positions[i]);
  printf("consumer: tesslod %d: %" PRIu32 " patches, level %" PRIu32 " -> %" PRIu32 " triangles (%" PRIu32
         " pattern, %" PRIu32 " strip), %" PRIu32 " vertices: %s\n",
         TLOD_VERSION, tlod_surface_patch_count(surface), level, out->triangle_count, out->pattern_triangles,
         out->strip_triangles, out->vertex_count, ok ? "OK" : "WRONG");
  if (!ok) fprintf(stderr, "consumer: expected %" PRIu32 " triangles with finite positions\n", expected);
#if TLOD_CONSUMER_GL
  ok = consumer_gl(g_ctx, surface, patterns) && ok;
#endif

  tlod_cpu_mesh_destroy(g_ctx, out);
  tlod_patterns_destroy(patterns);
  tlod_surface_destroy(surface);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(g_ctx);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
