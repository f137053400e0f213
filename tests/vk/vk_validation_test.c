/*
 * vk_validation_test.c -- the "vulkan" device under the Khronos validation
 * layer (synchronization validation on) raises no error and no warning over
 * a 100-frame playback of an animated multi-object scene, a resize and the
 * shutdown (owned by the Vulkan tests). Public API only, plus one raw
 * Vulkan call in the detector check.
 *
 * The scene (built here): on device A (pattern path) an icosphere (Phong),
 * a torus (PN, back faces culled), a soft cube (flat), a lat-long sphere
 * with a 4 x 4 checker texture (opaque) and the same surface drawn again as
 * MASK (the checker's transparent texels cut away), a translucent sphere
 * (BLEND) and a deforming sphere (PN) whose mesh is updated every frame
 * (tlod_mesh_update + tlod_surface_refresh + tlod_device_update_surface);
 * on device B (hardware_tessellation, same platform, same command buffer)
 * a sphere and a torus. Every model matrix changes every frame, the camera
 * orbits, some frames draw wireframe or a debug view, and the framebuffer
 * is resized at frame 50 (tlod_platform_resize). Frames are 2 in flight:
 * the platform waits each slot's fence, tesslod never waits.
 *
 * Checked: every call succeeds; the images show the scene (coverage) before
 * and after the resize; tlod_platform_validation_messages() == 0 after the
 * playback, after every tesslod object is destroyed, and while the platform
 * destroys the VkDevice (where the object tracker reports leaked objects:
 * the process total, tlod_platform_validation_messages(NULL), does not
 * grow). Detector check: a platform whose layer sees one
 * deliberately invalid call (vkCreateBuffer with usage 0) counts it.
 */
#include <vulkan/vulkan.h>

#include "vk_test.h"

#define W0 160
#define H0 120
#define W1 200
#define H1 150
#define FRAMES 100
#define RESIZE_AT 50
#define MAX_LEVEL 4
#define A_ITEMS 7
#define B_ITEMS 2

/* ---- matrices ------------------------------------------------------------ */

/* Column-major T(t) * Rz(angle) * Rx(tilt) * S(s). */
static void model_matrix(float m[16], const double t[3], double angle, double tilt, double s) {
  double c = cos(angle), n = sin(angle), ct = cos(tilt), st = sin(tilt);
  double r[9] = {c, n, 0, -n * ct, c * ct, st, n * st, -c * st, ct}; /* columns of Rz * Rx */
  memset(m, 0, 16 * sizeof *m);
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      m[4 * col + row] = (float)(r[3 * col + row] * s);
  for (int k = 0; k < 3; ++k)
    m[12 + k] = (float)t[k];
  m[15] = 1.0f;
}

/* ---- the scene ------------------------------------------------------------- */

typedef struct object {
  fixture fx;
  tlod_scheduler* sch;
  tlod_draw_item item;
  double at[3], scale, spin;
} object;

typedef struct scene {
  shape sphere, small_sphere, torus, cube, wobble;
  uv_sphere uvs;
  float *wobble_pos, *wobble_nrm;
  tlod_device_texture* checker;
  object a[A_ITEMS], b[B_ITEMS];
  tlod_draw_item a_items[A_ITEMS], b_items[B_ITEMS];
} scene;

/* A 4 x 4 checker: white opaque / orange transparent texels. */
static tlod_device_texture* make_checker(tlod_device* dev, tlod_context* ctx) {
  uint8_t texels[4 * 4 * 4];
  for (int i = 0; i < 16; ++i) {
    bool odd = ((i % 4) + (i / 4)) % 2;
    uint8_t px[4] = {255, odd ? 128 : 255, odd ? 0 : 255, odd ? 0 : 255};
    memcpy(texels + 4 * i, px, 4);
  }
  tlod_device_texture* tex = NULL;
  tlod_texture_desc td = {.width = 4, .height = 4, .rgba8 = texels, .srgb = true, .label = "checker"};
  tlod_result r = tlod_device_create_texture(dev, &td, &tex);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_device_create_texture: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return tex;
}

/* Its own scheduler on fx's surface, placed at (x, y, z), scaled. */
static bool object_place(object* o, const fixture* fx, double x, double y, double z, double scale) {
  o->sch = new_scheduler(fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
  o->at[0] = x, o->at[1] = y, o->at[2] = z;
  o->scale = scale;
  o->item.surface = fx->ds;
  o->item.has_model = true;
  return o->sch != NULL;
}

static bool object_make(object* o, tlod_context* ctx, const tlod_mesh_desc* md, tlod_surface_type type,
                        const tlod_patterns* pat, tlod_device* dev, double x, double y, double z, double scale) {
  memset(o, 0, sizeof *o);
  return fixture_make_desc(&o->fx, ctx, md, type, pat, dev) && object_place(o, &o->fx, x, y, z, scale);
}

static void object_free(object* o) {
  tlod_scheduler_destroy(o->sch);
  if (o->fx.mesh) fixture_free(&o->fx);
  memset(o, 0, sizeof *o);
}

/* A second object drawing another object's surface (its own scheduler). */
static bool object_share(object* o, const object* of, double x, double y, double z, double scale) {
  memset(o, 0, sizeof *o);
  return object_place(o, &of->fx, x, y, z, scale);
}

static void colour(tlod_draw_item* it, float r, float g, float b, float a) {
  it->has_color = true;
  it->color[0] = r, it->color[1] = g, it->color[2] = b, it->color[3] = a;
}

static void scene_free(scene* s, tlod_device* dev_a) {
  for (int k = 0; k < A_ITEMS; ++k)
    object_free(&s->a[k]); /* a[4] has no fixture of its own: a[3]'s surface */
  for (int k = 0; k < B_ITEMS; ++k)
    object_free(&s->b[k]);
  tlod_device_destroy_texture(dev_a, s->checker);
  shape_free(&s->sphere), shape_free(&s->small_sphere), shape_free(&s->torus), shape_free(&s->cube);
  shape_free(&s->wobble);
  uv_sphere_free(&s->uvs);
  free(s->wobble_pos), free(s->wobble_nrm);
  memset(s, 0, sizeof *s);
}

static void scene_make(scene* s, tlod_context* ctx, const tlod_patterns* pat, tlod_device* a, tlod_device* b) {
  memset(s, 0, sizeof *s);
  s->sphere = shape_icosphere(2), s->small_sphere = shape_icosphere(1), s->torus = shape_torus(16, 10);
  s->cube = shape_cube_soft(), s->wobble = shape_icosphere(2);
  CHECK(uv_sphere_make(&s->uvs, 10, 20));
  tlod_mesh_desc sphere = shape_mesh_desc(&s->sphere), small = shape_mesh_desc(&s->small_sphere);
  tlod_mesh_desc torus = shape_mesh_desc(&s->torus), cube = shape_mesh_desc(&s->cube);
  tlod_mesh_desc wobble = shape_mesh_desc(&s->wobble);
  CHECK(object_make(&s->a[0], ctx, &sphere, TLOD_SURFACE_PHONG, pat, a, -1.7, 0, 0, 0.8));
  CHECK(object_make(&s->a[1], ctx, &torus, TLOD_SURFACE_PN, pat, a, 1.7, 0, 0, 0.7));
  s->a[1].item.cull_back_faces = true;
  CHECK(object_make(&s->a[2], ctx, &cube, TLOD_SURFACE_FLAT, pat, a, 0, 1.7, 0, 0.9));
  colour(&s->a[2].item, 0.2f, 0.9f, 0.3f, 1.0f);
  CHECK(object_make(&s->a[3], ctx, &s->uvs.desc, TLOD_SURFACE_PHONG, pat, a, 0, -1.7, 0, 0.8));
  CHECK_MSG(s->checker = make_checker(a, ctx), "texture");
  s->a[3].item.base_color_texture = s->checker;
  CHECK(object_share(&s->a[4], &s->a[3], 0, 0, 1.6, 0.7));
  s->a[4].item.base_color_texture = s->checker;
  s->a[4].item.blend = TLOD_BLEND_MASK;
  CHECK(object_make(&s->a[5], ctx, &small, TLOD_SURFACE_PN, pat, a, 0.3, -0.3, 0.2, 0.9));
  s->a[5].item.blend = TLOD_BLEND_BLEND;
  colour(&s->a[5].item, 0.3f, 0.5f, 1.0f, 0.5f);
  CHECK(object_make(&s->a[6], ctx, &wobble, TLOD_SURFACE_PN, pat, a, 0, 0, -1.6, 0.8));
  s->wobble_pos = malloc(sizeof(float) * 3 * s->wobble.vertex_count);
  s->wobble_nrm = malloc(sizeof(float) * 3 * s->wobble.vertex_count);
  CHECK(s->wobble_pos && s->wobble_nrm);
  CHECK(object_make(&s->b[0], ctx, &sphere, TLOD_SURFACE_PN, pat, b, 1.7, 1.7, 0.5, 0.8));
  CHECK(object_make(&s->b[1], ctx, &torus, TLOD_SURFACE_PHONG, pat, b, -1.7, -1.7, -0.5, 0.7));
  colour(&s->b[1].item, 0.9f, 0.6f, 0.2f, 1.0f);
  for (int k = 0; k < A_ITEMS + B_ITEMS; ++k) {
    object* o = k < A_ITEMS ? &s->a[k] : &s->b[k - A_ITEMS];
    o->spin = 0.7 + 0.23 * k;
  }
}

/* The deforming object: a travelling wave along z, normals kept radial
 * (any unit normals do: the test is about the upload, not the shading). */
static void wobble(scene* s, tlod_context* ctx, tlod_device* dev, double t) {
  object* o = &s->a[6];
  for (uint32_t v = 0; v < s->wobble.vertex_count; ++v) {
    const float* p = s->wobble.positions + 3 * v;
    double f = 1.0 + 0.15 * sin(3.0 * p[2] + t * 0.004);
    for (int c = 0; c < 3; ++c)
      s->wobble_pos[3 * v + c] = (float)(p[c] * f), s->wobble_nrm[3 * v + c] = s->wobble.normals[3 * v + c];
  }
  tlod_result r = tlod_mesh_update(o->fx.mesh, s->wobble_pos, 0, s->wobble_nrm, 0);
  if (r == TLOD_SUCCESS) r = tlod_surface_refresh(o->fx.surf, NULL);
  if (r == TLOD_SUCCESS) r = tlod_device_update_surface(dev, o->fx.ds);
  CHECK_MSG(r == TLOD_SUCCESS, "deforming object: %s: %s", tlod_result_string(r), tlod_context_last_error(ctx));
}

/* Places and plans every object for frame time t; items[k] filled. */
static void plan_objects(object* objs, tlod_draw_item* items, int n, tlod_context* ctx, const tlod_view_desc* v,
                         double t) {
  for (int k = 0; k < n; ++k) {
    object* o = &objs[k];
    model_matrix(o->item.model, o->at, o->spin * t * 0.002, 0.3 * sin(t * 0.001 + k), o->scale);
    tlod_view_desc ov = object_view(v, o->item.model);
    tlod_frame_desc f = {.views = &ov, .view_count = 1, .dt_ms = 16.0f};
    o->item.draw_list = scheduler_plan(ctx, o->sch, &f);
    CHECK_MSG(o->item.draw_list, "object %d: no draw list", k);
    items[k] = o->item;
  }
}

static camera orbit_camera(double t, uint32_t w, uint32_t h) {
  double a = t * 0.0015;
  camera c = {.eye = {7.0 * cos(a), 7.0 * sin(a), 2.5 + sin(a * 0.7)},
              .up = {0, 0, 1},
              .fovy = 50.0 * SHAPES_PI / 180.0,
              .znear = 0.5,
              .zfar = 30.0,
              .width = w,
              .height = h,
              .aspect = (double)w / h};
  return c;
}

static void draw_desc(tlod_draw_desc* d, const tlod_draw_item* items, uint32_t n, const tlod_view_desc* v) {
  memset(d, 0, sizeof *d);
  d->items = items;
  d->item_count = n;
  memcpy(d->view, v->view, sizeof d->view);
  memcpy(d->proj, v->proj, sizeof d->proj);
  d->viewport[2] = v->viewport_width, d->viewport[3] = v->viewport_height;
}

/* The debug view / wireframe schedule of frame k. */
static void frame_style(int k, tlod_draw_desc* a, tlod_draw_desc* b) {
  static const tlod_debug_view views[4] = {TLOD_DEBUG_LEVELS, TLOD_DEBUG_SILHOUETTE, TLOD_DEBUG_STRIPS,
                                           TLOD_DEBUG_NONE};
  a->debug = k % 10 == 7 ? views[(k / 10) % 4] : TLOD_DEBUG_NONE;
  a->wireframe = k % 10 == 3;
  b->wireframe = k % 10 == 5;
  b->debug = k % 20 == 9 ? TLOD_DEBUG_LEVELS : TLOD_DEBUG_NONE;
}

/* One frame k: both devices record into the platform's command buffer. */
static void play_frame(vk_session* s, tlod_device* dev_b, scene* sc, int k, uint32_t w, uint32_t h, uint8_t* rgba) {
  double t = 16.0 * k;
  CALL(wobble(sc, s->ctx, s->dev, t));
  camera cam = orbit_camera(t, w, h);
  tlod_view_desc v = make_view(&cam);
  CALL(plan_objects(sc->a, sc->a_items, A_ITEMS, s->ctx, &v, t));
  CALL(plan_objects(sc->b, sc->b_items, B_ITEMS, s->ctx, &v, t));
  tlod_draw_desc da, db;
  draw_desc(&da, sc->a_items, A_ITEMS, &v);
  draw_desc(&db, sc->b_items, B_ITEMS, &v);
  frame_style(k, &da, &db);
  CHECK_MSG(vk_frame_begin(s->platform, &da), "frame %d", k);
  db.vk = da.vk;
  tlod_result ra = tlod_device_draw(s->dev, &da), rb = tlod_device_draw(dev_b, &db);
  CHECK_MSG(vk_frame_end(s->platform, rgba), "frame %d", k);
  CHECK_MSG(ra == TLOD_SUCCESS && rb == TLOD_SUCCESS, "frame %d: draw A %s, B %s: %s", k, tlod_result_string(ra),
            tlod_result_string(rb), tlod_context_last_error(s->ctx));
}

TEST(test_playback_is_validation_clean) {
  vk_session s;
  CHECK_MSG(vk_session_open(&s, W0, H0, MAX_LEVEL, "validation A", true, (tlod_device_vk_desc){0}),
            "no Vulkan device with the validation layer (see above)");
  tlod_device_vk_desc vb = vk_desc_of(s.platform);
  vb.hardware_tessellation = true;
  tlod_device* dev_b = new_vk_device(s.ctx, s.pat, "validation B (hardware)", vb);
  CHECK_MSG(dev_b, "second device (hardware_tessellation)");
  scene sc;
  CALL(scene_make(&sc, s.ctx, s.pat, s.dev, dev_b));
  uint8_t* rgba = malloc(4 * W1 * H1);
  CHECK(rgba);
  uint32_t w = W0, h = H0, covered_before = 0, covered_after = 0;
  char err[512] = "";
  for (int k = 0; k < FRAMES; ++k) {
    if (k == RESIZE_AT) {
      CHECK_MSG(tlod_platform_resize(s.platform, W1, H1, err, sizeof err), "resize: %s", err);
      w = W1, h = H1;
    }
    bool read = k == RESIZE_AT - 1 || k == FRAMES - 1;
    CALL(play_frame(&s, dev_b, &sc, k, w, h, read ? rgba : NULL));
    if (k == RESIZE_AT - 1) covered_before = covered_pixels(rgba, W0, H0);
    if (k == FRAMES - 1) covered_after = covered_pixels(rgba, W1, H1);
  }
  uint64_t after_play = tlod_platform_validation_messages(s.platform);
  printf("  %d frames (%ux%u, then %ux%u from frame %d): %u / %u pixels covered before / after the resize; %llu "
         "validation messages\n",
         FRAMES, W0, H0, W1, H1, RESIZE_AT, covered_before, covered_after, (unsigned long long)after_play);
  CHECK_MSG(covered_before > W0 * H0 / 10 && covered_after > W1 * H1 / 10, "the scene is not in the image");
  CHECK_MSG(tlod_platform_finish(s.platform) >= 0, "tlod_platform_finish");
  scene_free(&sc, s.dev);
  tlod_device_destroy(dev_b);
  tlod_device_destroy(s.dev);
  s.dev = NULL;
  uint64_t after_destroy = tlod_platform_validation_messages(s.platform);
  free(rgba);
  uint64_t process_before = tlod_platform_validation_messages(NULL);
  vk_session_close(&s);
  uint64_t at_device_destroy = tlod_platform_validation_messages(NULL) - process_before;
  CHECK_MSG(after_play == 0, "%llu validation messages during the playback (printed above)",
            (unsigned long long)after_play);
  CHECK_MSG(after_destroy == 0, "%llu validation messages by the end of tesslod's destroy calls",
            (unsigned long long)after_destroy);
  CHECK_MSG(at_device_destroy == 0,
            "%llu validation messages while the platform destroyed the VkDevice (object "
            "tracker: leaked objects; printed above)",
            (unsigned long long)at_device_destroy);
}

/* The layer is really on and counted: one invalid call is seen. */
TEST(test_detector_counts_an_invalid_call) {
  char err[512] = "";
  tlod_platform* p = vk_test_platform(64, 64, true, err, sizeof err);
  CHECK_MSG(p, "no Vulkan device with the validation layer: %s", err);
  tlod_platform_vk info;
  CHECK(tlod_platform_vk_info(p, &info));
  uint64_t before = tlod_platform_validation_messages(p);
  VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 256, .usage = 0};
  VkBuffer buf = VK_NULL_HANDLE;
  VkResult vr = vkCreateBuffer((VkDevice)info.device, &bi, NULL, &buf);
  if (vr == VK_SUCCESS) vkDestroyBuffer((VkDevice)info.device, buf, NULL);
  uint64_t after = tlod_platform_validation_messages(p);
  printf("  vkCreateBuffer with usage 0: %llu validation message(s) counted (expected)\n",
         (unsigned long long)(after - before));
  tlod_platform_destroy(p);
  CHECK_MSG(before == 0 && after > before, "the layer counted %llu messages before, %llu after an invalid call",
            (unsigned long long)before, (unsigned long long)after);
}

int main(void) {
  RUN(test_detector_counts_an_invalid_call);
  RUN(test_playback_is_validation_clean);
  VK_TEST_END();
}
