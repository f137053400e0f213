/*
 * gl_device_test.c -- the "gl" device is made once: 20 objects (20 device
 * surfaces on one device, placed by model matrices) play several frames in
 * one draw per frame, and the program link count stays the device's
 * constant (2 per surface type in desc.gl.surface_types), not 20x; a second
 * "mode" (other schedulers, same device) links nothing and uploads no
 * pattern again. Also: an identity model draws the image of no model,
 * bitwise; item colours reach the image. Owned by the GL tests.
 */
#include "gl_test.h"

#define W 256
#define H 192
#define OBJECTS 20
#define FRAMES 4
#define MAX_LEVEL 5

typedef struct object {
  fixture fx;
  tlod_scheduler* sched;
} object;

/* The scene: a 5 x 4 grid of spheres and tori in the z = 0 plane. */
static void place(uint32_t k, float model[16]) {
  memset(model, 0, sizeof(float) * 16);
  model[0] = model[5] = model[10] = 0.45f;
  model[12] = -4.0f + 2.0f * (float)(k % 5);
  model[13] = -3.0f + 2.0f * (float)(k / 5);
  model[15] = 1.0f;
}

static bool play(tlod_device* dev, object* objs, tlod_draw_item* items, const tlod_view_desc* v, uint32_t* covered,
                 uint64_t* triangles) {
  for (int f = 0; f < FRAMES; f++) {
    uint64_t want = 0;
    for (uint32_t k = 0; k < OBJECTS; k++) {
      tlod_view_desc ov = object_view(v, items[k].model);
      const tlod_draw_list* dl = plan(&objs[k].fx, objs[k].sched, &ov, 16.0f);
      if (!dl) return false;
      items[k].draw_list = dl;
      want += dl->pattern_triangles + dl->strip_triangles;
    }
    clear_frame(W, H);
    tlod_draw_desc d = {.items = items, .item_count = OBJECTS, .viewport = {0, 0, W, H}};
    memcpy(d.view, v->view, sizeof d.view);
    memcpy(d.proj, v->proj, sizeof d.proj);
    tlod_result r = tlod_device_draw(dev, &d);
    if (r != TLOD_SUCCESS) {
      fprintf(stderr, "tlod_device_draw: %s: %s\n", tlod_result_string(r), tlod_context_last_error(objs[0].fx.ctx));
      return false;
    }
    tlod_device_stats st = tlod_device_query_stats(dev);
    if (st.triangles != want || st.items != OBJECTS) {
      fprintf(stderr, "frame %d: %llu triangles drawn, the draw lists have %llu; %u items\n", f,
              (unsigned long long)st.triangles, (unsigned long long)want, st.items);
      return false;
    }
    *triangles = want;
  }
  uint8_t* rgba = malloc(4 * W * H);
  if (!rgba) return false;
  gl_read_rgba(W, H, rgba);
  *covered = 0;
  for (uint32_t i = 0; i < W * H; ++i)
    *covered += !is_background(rgba + 4 * i);
  free(rgba);
  return true;
}

TEST(test_one_device_many_objects) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, MAX_LEVEL, "gl_device",
                            (tlod_device_gl_desc){.surface_types = 1u << TLOD_SURFACE_PHONG}),
            "no GL context or device (see above)");
  tlod_device_stats st = tlod_device_query_stats(gs.dev);
  const uint32_t links_per_device = st.gl.program_links;
  printf("  device created: %u program links, %u pattern upload (%llu bytes), %.1f ms\n", st.gl.program_links,
         st.gl.pattern_uploads, (unsigned long long)st.gl.pattern_bytes, st.gl.create_ms);
  CHECK_MSG(links_per_device == 2, "a phong-only device links %u programs (pattern + strip: 2)", links_per_device);
  CHECK(st.gl.pattern_uploads == 1);

  shape shapes[2] = {shape_icosphere(2), shape_torus(16, 10)};
  object objs[OBJECTS];
  tlod_draw_item items[OBJECTS];
  uint64_t patch_bytes = 0;
  for (uint32_t k = 0; k < OBJECTS; k++) {
    CHECK(fixture_make(&objs[k].fx, gs.ctx, &shapes[k % 2], TLOD_SURFACE_PHONG, gs.pat, gs.dev));
    objs[k].sched = new_scheduler(&objs[k].fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
    CHECK(objs[k].sched);
    items[k] = (tlod_draw_item){.surface = objs[k].fx.ds, .has_model = true};
    place(k, items[k].model);
    patch_bytes += sizeof(tlod_patch_record) * tlod_surface_patch_count(objs[k].fx.surf);
  }
  /* a surface type the device has no programs for */
  fixture pn;
  CHECK(fixture_make(&pn, gs.ctx, &shapes[0], TLOD_SURFACE_PN, gs.pat, NULL));
  tlod_device_surface* refused = NULL;
  tlod_result r = tlod_device_create_surface(gs.dev, pn.surf, &refused);
  CHECK_MSG(r == TLOD_ERROR_UNSUPPORTED && !refused, "pn surface on a phong-only device: %s", tlod_result_string(r));
  printf("  pn surface on the phong device: %s\n", tlod_context_last_error(gs.ctx));
  fixture_free(&pn);

  camera cam = camera_look(0.5, -9.0, 6.0, 0, 0, 0, 50, W, H);
  cam.znear = 1.0, cam.zfar = 30.0;
  tlod_view_desc v = make_view(&cam);
  uint32_t covered = 0;
  uint64_t triangles = 0;
  CHECK(play(gs.dev, objs, items, &v, &covered, &triangles));
  st = tlod_device_query_stats(gs.dev);
  printf("  mode 1: %u objects x %d frames in %llu draws: %u pixels covered, %llu triangles a frame, %u draw calls; "
         "program links %u, pattern uploads %u, patch bytes %llu\n",
         OBJECTS, FRAMES, (unsigned long long)st.draws, covered, (unsigned long long)triangles, st.draw_calls,
         st.gl.program_links, st.gl.pattern_uploads, (unsigned long long)st.gl.patch_bytes);
  CHECK_MSG(st.gl.program_links == links_per_device, "%u links after %u surfaces (want %u, the device's constant)",
            st.gl.program_links, OBJECTS, links_per_device);
  CHECK(st.gl.pattern_uploads == 1 && st.gl.patch_bytes == patch_bytes && st.surfaces_live == OBJECTS);
  CHECK(st.draws == FRAMES && st.items_drawn == (uint64_t)FRAMES * OBJECTS);
  /* gpu_ms names the draw it measured (read a few draws late, never this one) */
  CHECK_MSG(st.gpu_ms < 0.0 ? st.gpu_draw == 0 : st.gpu_draw >= 1 && st.gpu_draw < st.draws, "gpu_ms %.3f of draw %llu",
            st.gpu_ms, (unsigned long long)st.gpu_draw);
  CHECK_MSG(covered > 2000, "20 objects cover only %u pixels", covered);
  CHECK(glGetError() == GL_NO_ERROR);

  /* mode 2: other schedulers (uniform level 2), the same device and surfaces */
  for (uint32_t k = 0; k < OBJECTS; k++) {
    tlod_scheduler_destroy(objs[k].sched);
    objs[k].sched = new_scheduler(&objs[k].fx, (tlod_scheduler_desc){.policy = TLOD_POLICY_UNIFORM, .max_level = 2});
    CHECK(objs[k].sched);
  }
  uint32_t covered2 = 0;
  CHECK(play(gs.dev, objs, items, &v, &covered2, &triangles));
  st = tlod_device_query_stats(gs.dev);
  printf("  mode 2 (uniform:2): %u pixels covered, %llu triangles a frame; program links %u, pattern uploads %u\n",
         covered2, (unsigned long long)triangles, st.gl.program_links, st.gl.pattern_uploads);
  CHECK_MSG(st.gl.program_links == links_per_device && st.gl.pattern_uploads == 1 && st.gl.patch_bytes == patch_bytes,
            "mode 2 linked %u programs / uploaded patterns %u times / %llu patch bytes",
            st.gl.program_links - links_per_device, st.gl.pattern_uploads, (unsigned long long)st.gl.patch_bytes);
  CHECK(covered2 > 2000);

  /* surface refresh: one update re-uploads that surface only */
  CHECK(tlod_device_update_surface(gs.dev, objs[3].fx.ds) == TLOD_SUCCESS);
  st = tlod_device_query_stats(gs.dev);
  CHECK(st.surface_updates == 1 &&
        st.gl.patch_bytes == patch_bytes + sizeof(tlod_patch_record) * tlod_surface_patch_count(objs[3].fx.surf));
  CHECK(st.gl.program_links == links_per_device);

  for (uint32_t k = 0; k < OBJECTS; k++) {
    tlod_scheduler_destroy(objs[k].sched);
    fixture_free(&objs[k].fx);
  }
  for (int k = 0; k < 2; k++)
    shape_free(&shapes[k]);
  gl_session_close(&gs);
}

/* Identity model == no model, bitwise; has_color reaches the pixels; the
 * default device links 2 programs per surface type (4 types). */
TEST(test_model_and_colour) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, MAX_LEVEL, "gl_model", (tlod_device_gl_desc){0}),
            "no GL context or device (see above)");
  CHECK_MSG(tlod_device_query_stats(gs.dev).gl.program_links == 8,
            "default device: %u links (flat, phong, pn, quadratic: 8)",
            tlod_device_query_stats(gs.dev).gl.program_links);
  shape sph = shape_torus(16, 10);
  fixture fx;
  CHECK(fixture_make(&fx, gs.ctx, &sph, TLOD_SURFACE_PN, gs.pat, gs.dev));
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
  CHECK(sch);
  camera cam = camera_look(1.4, -2.4, 1.6, 0, 0, 0, 50, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
  CHECK(dl);
  uint8_t* img[3];
  for (int k = 0; k < 3; k++) {
    img[k] = malloc(4 * W * H);
    CHECK(img[k]);
  }
  one_draw d;
  one_draw_make(&d, fx.ds, dl, &v);
  for (int k = 0; k < 3; k++) {
    if (k == 1) {
      static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      d.item.has_model = true;
      memcpy(d.item.model, identity, sizeof identity);
    }
    if (k == 2) {
      d.item.has_color = true;
      d.item.color[0] = 1.0f, d.item.color[1] = 0.0f, d.item.color[2] = 0.0f, d.item.color[3] = 1.0f;
    }
    clear_frame(W, H);
    CHECK(tlod_device_draw(gs.dev, &d.desc) == TLOD_SUCCESS);
    CHECK(tlod_device_read_image(gs.dev, W, H, img[k]) == TLOD_SUCCESS);
  }
  uint32_t differ = 0, covered = 0, red = 0;
  for (uint32_t i = 0; i < W * H; ++i) {
    differ += memcmp(img[0] + 4 * i, img[1] + 4 * i, 4) != 0;
    covered += !is_background(img[0] + 4 * i);
    red += !is_background(img[2] + 4 * i) && img[2][4 * i + 1] == 0 && img[2][4 * i + 2] == 0 && img[2][4 * i] > 0;
  }
  printf("  identity model vs none: %u of %u covered pixels differ; red item: %u red pixels\n", differ, covered, red);
  CHECK(covered > 1000);
  CHECK_MSG(differ == 0, "the identity model changed %u pixels", differ);
  CHECK_MSG(red * 10 >= covered * 9, "only %u of %u pixels red", red, covered);
  for (int k = 0; k < 3; k++)
    free(img[k]);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  shape_free(&sph);
  gl_session_close(&gs);
}

int main(void) {
  RUN(test_one_device_many_objects);
  RUN(test_model_and_colour);
  GL_TEST_END();
}
