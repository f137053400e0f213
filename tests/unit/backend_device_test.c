/*
 * backend_device_test.c -- the device API's dispatch, on the "null" and
 * "cpu" backends (no GPU): every entry point, the registry, wrong use
 * (each an INVALID_ARGUMENT / UNSUPPORTED naming the item at fault) and the
 * counters. Public headers only (tesslod/backend.h, tesslod/cpu.h).
 */
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "tesslod/backend.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_alloc.h"

/* An object: mesh, surface, scheduler with a planned draw list. */
typedef struct object {
  shape sh;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_scheduler* sched;
  const tlod_draw_list* dl;
} object;

static tlod_view_desc test_view(void) {
  /* eye (0, -4, 1) looking at the origin, 60 degrees, 320 x 240 */
  tlod_view_desc v = {.viewport_width = 320, .viewport_height = 240};
  const float view[16] = {
      1, 0, 0, 0, 0, 0.242535625f, -0.970142500f, 0, 0, 0.970142500f, 0.242535625f, 0, 0, 0, -4.123105626f, 1};
  const float f = 1.732050808f, n = 0.1f, fa = 20.0f;
  const float proj[16] = {f / (320.0f / 240.0f), 0, 0, 0, 0, f, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0,
                          2 * fa * n / (n - fa), 0};
  memcpy(v.view, view, sizeof view);
  memcpy(v.proj, proj, sizeof proj);
  return v;
}

static bool object_make(object* o, tlod_context* ctx, shape sh, const tlod_patterns* pat, const char* label) {
  memset(o, 0, sizeof *o);
  o->sh = sh;
  tlod_mesh_desc md = shape_mesh_desc(&o->sh);
  if (tlod_mesh_create(ctx, &md, &o->mesh) != TLOD_SUCCESS) return false;
  if (tlod_surface_create(ctx, o->mesh, &(tlod_surface_desc){.label = label}, &o->surf) != TLOD_SUCCESS) return false;
  if (tlod_scheduler_create(ctx, o->surf, pat, &(tlod_scheduler_desc){0}, &o->sched) != TLOD_SUCCESS) return false;
  tlod_view_desc v = test_view();
  if (tlod_scheduler_update(o->sched, &(tlod_frame_desc){.views = &v, .view_count = 1}) != TLOD_SUCCESS) return false;
  o->dl = tlod_scheduler_draw_list(o->sched, 0);
  return o->dl != NULL;
}

static void object_free(object* o) {
  tlod_scheduler_destroy(o->sched);
  tlod_surface_destroy(o->surf);
  tlod_mesh_destroy(o->mesh);
  shape_free(&o->sh);
}

static tlod_draw_desc view_desc(const tlod_draw_item* items, uint32_t count) {
  tlod_view_desc v = test_view();
  tlod_draw_desc d = {.items = items, .item_count = count, .viewport = {0, 0, 320, 240}};
  memcpy(d.view, v.view, sizeof d.view);
  memcpy(d.proj, v.proj, sizeof d.proj);
  return d;
}

static bool has(const char* haystack, const char* needle) { return strstr(haystack, needle) != NULL; }

TEST(test_registry) {
  const char* names = tlod_backend_names();
  printf("  tlod_backend_names() = \"%s\"\n", names);
  CHECK(has(names, "cpu") && has(names, "null"));
  CHECK_MSG(!has(names, "metal"), "'%s' advertises a backend that does not exist", names);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  tlod_device* dev = (tlod_device*)1;
  tlod_result r = tlod_device_create(ctx, &(tlod_device_desc){.backend = "metal", .patterns = pat}, &dev);
  const char* msg = tlod_context_last_error(ctx);
  CHECK_MSG(r == TLOD_ERROR_UNSUPPORTED && dev == NULL, "%s", tlod_result_string(r));
  CHECK_MSG(has(msg, "'metal'") && has(msg, names), "message does not name what the build has: %s", msg);
  printf("  metal: %s\n", msg);
  /* every listed name creates */
  char list[64];
  snprintf(list, sizeof list, "%s", names);
  for (char* name = strtok(list, ","); name; name = strtok(NULL, ",")) {
    if (!strcmp(name, "gl") || !strcmp(name, "vulkan"))
      continue; /* need a GL context / Vulkan device: tests/gl, tests/vk */
    r = tlod_device_create(ctx, &(tlod_device_desc){.backend = name, .patterns = pat}, &dev);
    CHECK_MSG(r == TLOD_SUCCESS, "%s: %s", name, tlod_context_last_error(ctx));
    CHECK(!strcmp(tlod_device_backend(dev), name));
    tlod_device_destroy(dev);
  }
  /* NULL backend name: cpu */
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.patterns = pat}, &dev) == TLOD_SUCCESS);
  CHECK(!strcmp(tlod_device_backend(dev), "cpu"));
  tlod_device_destroy(dev);
  tlod_device_destroy(NULL);
  CHECK(!strcmp(tlod_device_backend(NULL), ""));
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
}

TEST(test_create_wrong_use) {
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  tlod_device* dev = NULL;
  CHECK(tlod_device_create(NULL, &(tlod_device_desc){.patterns = pat}, &dev) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.patterns = pat}, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(has(tlod_context_last_error(ctx), "out is NULL"));
  CHECK(tlod_device_create(ctx, NULL, &dev) == TLOD_ERROR_INVALID_ARGUMENT && !dev);
  CHECK(has(tlod_context_last_error(ctx), "desc is NULL"));
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = "null"}, &dev) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(has(tlod_context_last_error(ctx), "desc.patterns"), "%s", tlod_context_last_error(ctx));
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = "null", .patterns = pat, .gl.surface_types = 1u << 9},
                           &dev) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(has(tlod_context_last_error(ctx), "surface_types"));
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
}

/* Every entry point on "null", with the counts it keeps. */
TEST(test_null_counts) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = NULL;
  tlod_context_desc cd = {.thread_count = 1};
  cd.allocator.alloc_fn = counting_alloc;
  cd.allocator.free_fn = counting_free;
  cd.allocator.user_data = &counter;
  CHECK(tlod_context_create(&cd, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  enum { N = 5 };
  object obj[N];
  for (int k = 0; k < N; k++) {
    char label[16];
    snprintf(label, sizeof label, "obj%d", k);
    CHECK(object_make(&obj[k], ctx, k % 2 ? shape_torus(8, 6) : shape_icosphere(1), pat, label));
  }
  long allocs_before = counter.allocs;
  tlod_device* dev = NULL;
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = "null", .patterns = pat, .label = "n"}, &dev) ==
        TLOD_SUCCESS);
  tlod_device_stats st = tlod_device_query_stats(dev);
  CHECK(st.surfaces_created == 0 && st.draws == 0 && st.gl.program_links == 0 && st.gpu_ms < 0.0);
  tlod_device_surface* ds[N];
  for (int k = 0; k < N; k++)
    CHECK(tlod_device_create_surface(dev, obj[k].surf, &ds[k]) == TLOD_SUCCESS);
  CHECK(tlod_device_update_surface(dev, ds[1]) == TLOD_SUCCESS);
  CHECK(tlod_device_update_surface(dev, ds[3]) == TLOD_SUCCESS);
  tlod_draw_item items[N];
  uint64_t want_triangles = 0;
  for (int k = 0; k < N; k++) {
    items[k] = (tlod_draw_item){.surface = ds[k], .draw_list = obj[k].dl};
    want_triangles += obj[k].dl->pattern_triangles + obj[k].dl->strip_triangles;
  }
  tlod_draw_desc d = view_desc(items, N);
  const int frames = 3;
  for (int f = 0; f < frames; f++)
    CHECK_MSG(tlod_device_draw(dev, &d) == TLOD_SUCCESS, "%s", tlod_context_last_error(ctx));
  d.item_count = 2; /* a smaller draw: stats follow the last one */
  CHECK(tlod_device_draw(dev, &d) == TLOD_SUCCESS);
  st = tlod_device_query_stats(dev);
  uint64_t two = obj[0].dl->pattern_triangles + obj[0].dl->strip_triangles + obj[1].dl->pattern_triangles +
                 obj[1].dl->strip_triangles;
  printf("  null: %llu surfaces, %llu updates, %llu draws, %llu items, %llu triangles in all (last draw %llu)\n",
         (unsigned long long)st.surfaces_created, (unsigned long long)st.surface_updates, (unsigned long long)st.draws,
         (unsigned long long)st.items_drawn, (unsigned long long)st.triangles_drawn, (unsigned long long)st.triangles);
  CHECK(st.surfaces_created == N && st.surfaces_live == N && st.surface_updates == 2);
  CHECK(st.draws == (uint64_t)frames + 1 && st.items_drawn == (uint64_t)frames * N + 2 && st.items == 2);
  CHECK(st.triangles == two && st.triangles_drawn == frames * want_triangles + two);
  CHECK(st.gl.program_links == 0 && st.gl.pattern_uploads == 0 && st.draw_calls == 0);
  tlod_draw_item_stats is = tlod_device_query_item_stats(dev, 1);
  CHECK(is.triangles == obj[1].dl->pattern_triangles + obj[1].dl->strip_triangles && is.vertices > 0);
  is = tlod_device_query_item_stats(dev, 2); /* past the last draw's items */
  CHECK(is.triangles == 0 && is.vertices == 0);
  /* a model matrix and a colour are accepted as they are */
  items[0].has_model = true;
  const float m[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
  memcpy(items[0].model, m, sizeof m);
  items[0].has_color = true;
  CHECK(tlod_device_draw(dev, &d) == TLOD_SUCCESS);
  uint8_t px[4];
  CHECK(tlod_device_read_image(dev, 1, 1, px) == TLOD_ERROR_UNSUPPORTED);
  CHECK(has(tlod_context_last_error(ctx), "null device has no image"));
  CHECK(tlod_cpu_device_mesh(dev, 0) == NULL);
  tlod_device_destroy_surface(dev, ds[4]);
  tlod_device_destroy_surface(dev, NULL);
  st = tlod_device_query_stats(dev);
  CHECK(st.surfaces_live == N - 1 && st.surfaces_destroyed == 1);
  tlod_device_destroy(dev); /* destroys the other four */
  for (int k = 0; k < N; k++)
    object_free(&obj[k]);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees: the device leaks through the context",
            counter.allocs, counter.frees);
  CHECK(counter.allocs > allocs_before);
}

/* Wrong use of surfaces and draws: the same answer on every backend. */
static void wrong_use(const char* backend) {
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_patterns *pat = NULL, *small = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 1}, &small) == TLOD_SUCCESS);
  object a, b;
  CHECK(object_make(&a, ctx, shape_icosphere(1), pat, "sphere"));
  CHECK(object_make(&b, ctx, shape_torus(8, 6), pat, "torus"));
  tlod_device *dev = NULL, *other = NULL, *low = NULL;
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = backend, .patterns = pat, .label = "mine"}, &dev) ==
        TLOD_SUCCESS);
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = backend, .patterns = pat, .label = "theirs"}, &other) ==
        TLOD_SUCCESS);
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = backend, .patterns = small, .label = "low"}, &low) ==
        TLOD_SUCCESS);
  tlod_draw_item item = {.draw_list = a.dl};
  tlod_draw_desc d = view_desc(&item, 1);
  const char* e;
#define WRONG(call, want, text)                                                                                        \
  do {                                                                                                                 \
    tlod_result _r = (call);                                                                                           \
    e = tlod_context_last_error(ctx);                                                                                  \
    CHECK_MSG(_r == (want), "%s: %s gives %s (%s)", backend, #call, tlod_result_string(_r), e);                        \
    CHECK_MSG(has(e, text), "%s: %s: message '%s' lacks '%s'", backend, #call, e, text);                               \
  } while (0)
  /* draw before any surface */
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "no surface yet");
  tlod_device_surface *sa = NULL, *sb = NULL, *theirs = NULL, *sl = NULL;
  WRONG(tlod_device_create_surface(dev, NULL, &sa), TLOD_ERROR_INVALID_ARGUMENT, "surface is NULL");
  WRONG(tlod_device_create_surface(dev, a.surf, NULL), TLOD_ERROR_INVALID_ARGUMENT, "out is NULL");
  CHECK(tlod_device_create_surface(NULL, a.surf, &sa) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_device_create_surface(dev, a.surf, &sa) == TLOD_SUCCESS);
  CHECK(tlod_device_create_surface(dev, b.surf, &sb) == TLOD_SUCCESS);
  CHECK(tlod_device_create_surface(other, a.surf, &theirs) == TLOD_SUCCESS);
  CHECK(tlod_device_create_surface(low, a.surf, &sl) == TLOD_SUCCESS);
  /* the desc and the item list */
  WRONG(tlod_device_draw(dev, NULL), TLOD_ERROR_INVALID_ARGUMENT, "desc is NULL");
  CHECK(tlod_device_draw(NULL, &d) == TLOD_ERROR_INVALID_ARGUMENT);
  d.items = NULL;
  d.item_count = 0;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "item_count is 0");
  d.item_count = 3;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "items is NULL with item_count 3");
  d.items = &item;
  d.item_count = 1;
  /* items */
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "item 0: surface is NULL");
  tlod_draw_item two[2] = {{.surface = sa, .draw_list = a.dl}, {.surface = theirs, .draw_list = a.dl}};
  d.items = two;
  d.item_count = 2;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT,
        "item 1: surface 'sphere' belongs to another device ('theirs', not 'mine')");
  two[1] = (tlod_draw_item){.surface = sb};
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "item 1: draw_list is NULL");
  two[1].draw_list = a.dl; /* the sphere's list for the torus */
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "item 1: draw list of");
  two[1].draw_list = b.dl;
  two[1].has_model = true; /* an all-zero model is used as given, and is finite */
  CHECK(tlod_device_draw(dev, &d) == TLOD_SUCCESS);
  two[1].model[5] = NAN;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "item 1: model[5] is not finite");
  two[1].has_model = false; /* ignored then */
  CHECK(tlod_device_draw(dev, &d) == TLOD_SUCCESS);
  /* the view */
  d.viewport[2] = 0;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "viewport 0 x 240 is empty");
  d.viewport[2] = 320;
  d.debug = TLOD_DEBUG_NUM;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "unknown debug view");
  d.debug = TLOD_DEBUG_NONE;
  d.proj[0] = INFINITY;
  WRONG(tlod_device_draw(dev, &d), TLOD_ERROR_INVALID_ARGUMENT, "proj[0] is not finite");
  d = view_desc(two, 2);
  /* a draw list past the device's patterns */
  tlod_draw_item deep = {.surface = sl, .draw_list = a.dl};
  tlod_draw_desc dd = view_desc(&deep, 1);
  uint32_t deepest = 0;
  for (uint32_t k = 0; k < a.dl->bucket_count; k++)
    deepest = a.dl->buckets[k].level > deepest ? a.dl->buckets[k].level : deepest;
  CHECK_MSG(deepest > 1, "the test view plans level %u at most: nothing past the low device's patterns", deepest);
  WRONG(tlod_device_draw(low, &dd), TLOD_ERROR_INVALID_ARGUMENT, "outside the device's patterns");
  /* surfaces of another device */
  WRONG(tlod_device_update_surface(dev, theirs), TLOD_ERROR_INVALID_ARGUMENT, "belongs to another device");
  WRONG(tlod_device_update_surface(dev, NULL), TLOD_ERROR_INVALID_ARGUMENT, "ds is NULL");
  tlod_device_destroy_surface(dev, theirs); /* refused, not destroyed */
  CHECK(has(tlod_context_last_error(ctx), "belongs to another device"));
  CHECK(tlod_device_query_stats(other).surfaces_live == 1);
  /* read back */
  uint8_t px[4];
  WRONG(tlod_device_read_image(dev, 0, 1, px), TLOD_ERROR_INVALID_ARGUMENT, "empty image");
  WRONG(tlod_device_read_image(dev, 1, 1, NULL), TLOD_ERROR_INVALID_ARGUMENT, "rgba is NULL");
  WRONG(tlod_device_read_image(dev, 1, 1, px), TLOD_ERROR_UNSUPPORTED, "no image");
  /* nothing counted for the refused calls */
  tlod_device_stats st = tlod_device_query_stats(dev);
  CHECK_MSG(st.draws == 2 && st.surfaces_created == 2 && st.surface_updates == 0, "%s: draws %llu", backend,
            (unsigned long long)st.draws);
  printf("  %s: every wrong use refused; last message: %s\n", backend, e);
#undef WRONG
  tlod_device_destroy(dev);
  tlod_device_destroy(other);
  tlod_device_destroy(low);
  object_free(&a);
  object_free(&b);
  tlod_patterns_destroy(pat);
  tlod_patterns_destroy(small);
  tlod_context_destroy(ctx);
}

TEST(test_wrong_use_null) { wrong_use("null"); }
TEST(test_wrong_use_cpu) { wrong_use("cpu"); }

/* The cpu device realises each item as tlod_cpu_tessellate does. */
TEST(test_cpu_device_meshes) {
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  object a, b;
  CHECK(object_make(&a, ctx, shape_icosphere(1), pat, "sphere"));
  CHECK(object_make(&b, ctx, shape_quad_sphere(3), pat, "quads"));
  tlod_device* dev = NULL;
  CHECK(tlod_device_create(ctx, &(tlod_device_desc){.backend = "cpu", .patterns = pat}, &dev) == TLOD_SUCCESS);
  tlod_device_surface *sa = NULL, *sb = NULL;
  CHECK(tlod_device_create_surface(dev, a.surf, &sa) == TLOD_SUCCESS);
  CHECK(tlod_device_create_surface(dev, b.surf, &sb) == TLOD_SUCCESS);
  tlod_draw_item items[2] = {{.surface = sa, .draw_list = a.dl}, {.surface = sb, .draw_list = b.dl}};
  tlod_draw_desc d = view_desc(items, 2);
  for (int f = 0; f < 2; f++)
    CHECK(tlod_device_draw(dev, &d) == TLOD_SUCCESS);
  const object* objs[2] = {&a, &b};
  uint64_t sum = 0;
  for (uint32_t k = 0; k < 2; k++) {
    const tlod_cpu_mesh* m = tlod_cpu_device_mesh(dev, k);
    CHECK(m);
    tlod_cpu_mesh* direct = NULL;
    CHECK(tlod_cpu_tessellate(ctx, objs[k]->surf, pat, &(tlod_cpu_tessellate_desc){.draw_list = objs[k]->dl},
                              &direct) == TLOD_SUCCESS);
    CHECK(m->triangle_count == direct->triangle_count && m->vertex_count == direct->vertex_count);
    CHECK(!memcmp(m->positions, direct->positions, sizeof(float) * 3 * m->vertex_count));
    CHECK(!memcmp(m->indices, direct->indices, sizeof(uint32_t) * 3 * m->triangle_count));
    CHECK(tlod_device_query_item_stats(dev, k).triangles == m->triangle_count);
    sum += m->triangle_count;
    tlod_cpu_mesh_destroy(ctx, direct);
  }
  CHECK(tlod_cpu_device_mesh(dev, 2) == NULL);
  CHECK(tlod_device_query_stats(dev).triangles == sum);
  printf("  cpu: 2 items realised, %llu triangles, equal to tlod_cpu_tessellate\n", (unsigned long long)sum);
  tlod_device_destroy(dev);
  object_free(&a);
  object_free(&b);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
}

int main(void) {
  RUN(test_registry);
  RUN(test_create_wrong_use);
  RUN(test_null_counts);
  RUN(test_wrong_use_null);
  RUN(test_wrong_use_cpu);
  RUN(test_cpu_device_meshes);
  TEST_END();
}
