/*
 * vk_device_test.c -- the "vulkan" device's own contract (tesslod/vulkan.h),
 * on the headless platform with the validation layer (every test ends with
 * zero messages):
 *   - every required desc.vk field refused by name when missing, bad
 *     frames_in_flight / samples refused, formats the device cannot use
 *     refused naming the field and the format;
 *   - a draw without a command buffer or with a frame index past
 *     frames_in_flight refused by name, recording nothing (the frame's image
 *     stays background); read_image is UNSUPPORTED;
 *   - a device with textured, blended and wireframe items, a texture and a
 *     surface destroyed while frames are in flight: every host allocation
 *     (tesslod's and Vulkan's, routed through the context) freed at destroy;
 *   - tlod_device_update_surface reaches every frame slot (each slot has its
 *     own copy: the moved object shows in slot 0 and in slot 1), and so
 *     does an attribute replaced by tlod_mesh_update_attribute (a quadratic
 *     surface on a device of that type only);
 *   - two draws in one frame (same frame index) append to the ring: both
 *     halves of the image are drawn.
 */
#include <vulkan/vulkan.h>

#include "quadratic_cube.h"
#include "test_alloc.h"
#include "vk_test.h"

#define W 96
#define H 72

/* Destroys the session (device before platform) and checks the validation
 * layer said nothing, destruction included. */
static void platform_clean(tlod_platform* p) {
  uint64_t messages = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  CHECK_MSG(messages == 0, "%llu validation messages (printed above)", (unsigned long long)messages);
}

static void close_clean(vk_session* s) {
  tlod_platform* p = s->platform;
  s->platform = NULL;
  vk_session_close(s);
  CALL(platform_clean(p));
}

static bool has(const char* s, const char* part) { return s && strstr(s, part) != NULL; }

static camera front_camera(void) { return camera_look(0, -4.0, 0.8, 0, 0, 0, 45, W, H); }

/* ---- desc.vk ---------------------------------------------------------------- */

typedef struct desc_case {
  const char* what;
  tlod_device_vk_desc vk;
  tlod_result want;
  const char* text;
} desc_case;

static void refuse(tlod_context* ctx, const tlod_patterns* pat, const desc_case* c) {
  tlod_device* dev = (tlod_device*)1;
  tlod_result r = tlod_device_create(ctx, &(tlod_device_desc){.backend = "vulkan", .patterns = pat, .vk = c->vk}, &dev);
  const char* msg = tlod_context_last_error(ctx);
  printf("  %-26s -> %s: %s\n", c->what, tlod_result_string(r), msg);
  CHECK_MSG(r == c->want && dev == NULL, "%s: %s", c->what, tlod_result_string(r));
  CHECK_MSG(has(msg, c->text), "%s: the message does not say '%s': %s", c->what, c->text, msg);
}

TEST(test_desc_fields_refused) {
  char err[512] = "";
  tlod_platform* p = vk_test_platform(W, H, true, err, sizeof err);
  CHECK_MSG(p, "no Vulkan device: %s", err);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = new_patterns(ctx, 4);
  CHECK(pat);
  tlod_device_vk_desc ok = vk_desc_of(p);
  desc_case cases[12];
  for (int i = 0; i < 12; i++)
    cases[i] = (desc_case){.vk = ok, .want = TLOD_ERROR_INVALID_ARGUMENT};
  cases[0].what = "instance NULL", cases[0].vk.instance = NULL, cases[0].text = "desc.vk.instance is required";
  cases[1].what = "physical_device NULL", cases[1].vk.physical_device = NULL;
  cases[1].text = "desc.vk.physical_device is required";
  cases[2].what = "device NULL", cases[2].vk.device = NULL, cases[2].text = "desc.vk.device is required";
  cases[3].what = "queue NULL", cases[3].vk.queue = NULL, cases[3].text = "desc.vk.queue is required";
  cases[4].what = "color_format 0", cases[4].vk.color_format = 0, cases[4].text = "desc.vk.color_format is required";
  cases[5].what = "depth_format 0", cases[5].vk.depth_format = 0, cases[5].text = "desc.vk.depth_format is required";
  cases[6].what = "frames_in_flight 9", cases[6].vk.frames_in_flight = 9;
  cases[6].text = "desc.vk.frames_in_flight 9";
  cases[7].what = "samples 3", cases[7].vk.samples = 3, cases[7].text = "desc.vk.samples 3";
  cases[8].what = "surface_types 0x100", cases[8].vk.surface_types = 0x100, cases[8].text = "desc.vk.surface_types";
  cases[9].what = "colour format D32", cases[9].vk.color_format = VK_FORMAT_D32_SFLOAT;
  cases[9].want = TLOD_ERROR_UNSUPPORTED, cases[9].text = "desc.vk.color_format 126";
  cases[10].what = "depth format RGBA8", cases[10].vk.depth_format = VK_FORMAT_R8G8B8A8_UNORM;
  cases[10].want = TLOD_ERROR_UNSUPPORTED, cases[10].text = "desc.vk.depth_format 37";
  cases[11].what = "samples 64", cases[11].vk.samples = 64;
  cases[11].want = TLOD_ERROR_UNSUPPORTED, cases[11].text = "desc.vk.samples 64";
  for (int i = 0; i < 12; i++)
    CALL(refuse(ctx, pat, &cases[i]));
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  CALL(platform_clean(p));
}

/* One object on a session of its own: its shape, fixture, scheduler, one
 * planned view and a one-item draw of it. */
typedef struct one_object {
  vk_session s;
  shape shp;
  fixture fx;
  tlod_scheduler* sch;
  tlod_view_desc v;
  const tlod_draw_list* dl;
  one_draw od;
} one_object;

static void object_open(one_object* o, shape shp, tlod_surface_type type, tlod_device_vk_desc opt,
                        tlod_scheduler_desc sd, const camera* cam) {
  memset(o, 0, sizeof *o);
  o->shp = shp;
  CHECK_MSG(vk_session_open(&o->s, W, H, sd.max_level, "vk_device", true, opt), "no Vulkan device");
  CHECK(fixture_make(&o->fx, o->s.ctx, &o->shp, type, o->s.pat, o->s.dev));
  o->sch = new_scheduler(&o->fx, sd);
  o->v = make_view(cam);
  CHECK(o->sch && (o->dl = plan(&o->fx, o->sch, &o->v, 16.0f)));
  one_draw_make(&o->od, o->fx.ds, o->dl, &o->v);
}

static void object_close(one_object* o) {
  tlod_scheduler_destroy(o->sch);
  fixture_free(&o->fx);
  shape_free(&o->shp);
  CALL(close_clean(&o->s));
}

/* ---- desc.vk of a draw ---------------------------------------------------------- */

TEST(test_draw_fields_refused) {
  one_object o;
  camera cam = front_camera();
  CALL(object_open(&o, shape_icosphere(2), TLOD_SURFACE_PN, (tlod_device_vk_desc){0},
                   (tlod_scheduler_desc){.max_level = 4}, &cam));
  vk_session s = o.s;
  one_draw od = o.od;
  od.desc.items = &od.item;
  CHECK(vk_frame_begin(s.platform, &od.desc));
  void* cmd = od.desc.vk.command_buffer;
  od.desc.vk.command_buffer = NULL;
  tlod_result r = tlod_device_draw(s.dev, &od.desc);
  const char* msg = tlod_context_last_error(s.ctx);
  printf("  no command buffer: %s\n", msg);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT && has(msg, "desc.vk.command_buffer"), "%s: %s", tlod_result_string(r),
            msg);
  od.desc.vk.command_buffer = cmd;
  uint32_t frames = vk_desc_of(s.platform).frames_in_flight;
  od.desc.vk.frame_index = frames;
  r = tlod_device_draw(s.dev, &od.desc);
  msg = tlod_context_last_error(s.ctx);
  printf("  frame index %u: %s\n", frames, msg);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT && has(msg, "desc.vk.frame_index"), "%s: %s", tlod_result_string(r), msg);
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba && vk_frame_end(s.platform, rgba));
  CHECK_MSG(covered_pixels(rgba, W, H) == 0, "a refused draw recorded something: %u pixels",
            covered_pixels(rgba, W, H));
  CHECK(tlod_device_query_stats(s.dev).draws == 0);
  uint8_t px[4];
  r = tlod_device_read_image(s.dev, 1, 1, px);
  CHECK_MSG(r == TLOD_ERROR_UNSUPPORTED, "read_image: %s", tlod_result_string(r));
  free(rgba);
  CALL(object_close(&o));
}

/* ---- everything freed -------------------------------------------------------- */

static const uint8_t checker[4 * 4 * 4] = {255, 0,   0, 255, 0,   255, 0, 255, 255, 0,   0, 255, 0,   255, 0, 255,
                                           0,   255, 0, 255, 255, 0,   0, 255, 0,   255, 0, 255, 255, 0,   0, 255,
                                           255, 0,   0, 255, 0,   255, 0, 255, 255, 0,   0, 255, 0,   255, 0, 255,
                                           0,   255, 0, 255, 255, 0,   0, 255, 0,   255, 0, 255, 255, 0,   0, 255};

/* Pixels whose red and green differ (the checker texture; shading is grey). */
static uint32_t coloured_pixels(const uint8_t* rgba) {
  uint32_t n = 0;
  for (uint32_t i = 0; i < W * H; i++)
    n += !is_background(rgba + 4 * i) && abs((int)rgba[4 * i] - (int)rgba[4 * i + 1]) > 40;
  return n;
}

typedef struct scene {
  fixture plain, textured;
  uv_sphere uv;
  tlod_scheduler *s0, *s1;
  tlod_device_texture* tex;
  tlod_draw_item items[3];
  tlod_draw_desc desc;
} scene;

static bool scene_make(scene* sc, tlod_context* ctx, const tlod_patterns* pat, tlod_device* dev, const shape* sph) {
  memset(sc, 0, sizeof *sc);
  if (!uv_sphere_make(&sc->uv, 8, 16) || !fixture_make(&sc->plain, ctx, sph, TLOD_SURFACE_PN, pat, dev) ||
      !fixture_make_desc(&sc->textured, ctx, &sc->uv.desc, TLOD_SURFACE_PHONG, pat, dev))
    return false;
  tlod_texture_desc td = {.width = 4, .height = 4, .rgba8 = checker, .label = "checker"};
  if (tlod_device_create_texture(dev, &td, &sc->tex) != TLOD_SUCCESS) return false;
  sc->s0 = new_scheduler(&sc->plain, (tlod_scheduler_desc){.max_level = 4});
  sc->s1 = new_scheduler(&sc->textured, (tlod_scheduler_desc){.max_level = 4});
  return sc->s0 && sc->s1;
}

static void scene_free(scene* sc, tlod_device* dev) {
  tlod_scheduler_destroy(sc->s0);
  tlod_scheduler_destroy(sc->s1);
  tlod_device_destroy_texture(dev, sc->tex);
  fixture_free(&sc->plain);
  fixture_free(&sc->textured);
  uv_sphere_free(&sc->uv);
}

/* Three items: a plain PN object on the left, a textured one on the right,
 * a half-transparent one (BLEND) in front. */
static bool scene_desc(scene* sc, bool wireframe) {
  camera cam = front_camera();
  tlod_view_desc v = make_view(&cam);
  static const float left[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1.1f, 0, 0, 1};
  static const float right[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1.1f, 0, 0, 1};
  tlod_view_desc vl = object_view(&v, left), vr = object_view(&v, right);
  const tlod_draw_list* dl0 = plan(&sc->plain, sc->s0, &vl, 16.0f);
  const tlod_draw_list* dl1 = plan(&sc->textured, sc->s1, &vr, 16.0f);
  if (!dl0 || !dl1) return false;
  memset(sc->items, 0, sizeof sc->items);
  sc->items[0] =
      (tlod_draw_item){.surface = sc->plain.ds, .draw_list = dl0, .has_model = true, .cull_back_faces = true};
  memcpy(sc->items[0].model, left, sizeof left);
  sc->items[1] = (tlod_draw_item){.surface = sc->textured.ds,
                                  .draw_list = dl1,
                                  .has_model = true,
                                  .base_color_texture = sc->tex,
                                  .blend = TLOD_BLEND_MASK};
  memcpy(sc->items[1].model, right, sizeof right);
  sc->items[2] = sc->items[0];
  sc->items[2].blend = TLOD_BLEND_BLEND;
  sc->items[2].has_color = true;
  sc->items[2].color[0] = sc->items[2].color[1] = sc->items[2].color[2] = 0.9f, sc->items[2].color[3] = 0.5f;
  memset(&sc->desc, 0, sizeof sc->desc);
  sc->desc.items = sc->items;
  sc->desc.item_count = 3;
  memcpy(sc->desc.view, v.view, sizeof v.view);
  memcpy(sc->desc.proj, v.proj, sizeof v.proj);
  sc->desc.viewport[2] = W, sc->desc.viewport[3] = H;
  sc->desc.wireframe = wireframe;
  sc->desc.light_dir[1] = -1.0f, sc->desc.light_dir[2] = 0.3f; /* towards the camera */
  return true;
}

static void draw_scene_frames(vk_session* s, scene* sc, int frames, uint8_t* rgba) {
  for (int f = 0; f < frames; f++) {
    CHECK(scene_desc(sc, f % 2 == 1));
    CHECK_MSG(vk_draw_frame(s->platform, s->dev, s->ctx, &sc->desc, rgba), "frame %d", f);
  }
}

TEST(test_destroy_frees_everything) {
  counting_allocator ca = {.fail_at = -1};
  vk_session s;
  memset(&s, 0, sizeof s);
  char err[512] = "";
  s.platform = vk_test_platform(W, H, true, err, sizeof err);
  CHECK_MSG(s.platform, "no Vulkan device: %s", err);
  tlod_context_desc cd = {.thread_count = 1, .allocator = {counting_alloc, counting_free, &ca}};
  CHECK(tlod_context_create(&cd, &s.ctx) == TLOD_SUCCESS);
  CHECK(s.pat = new_patterns(s.ctx, 4));
  long before = ca.allocs;
  CHECK(s.dev = new_vk_device(s.ctx, s.pat, "vk_frees", vk_desc_of(s.platform)));
  long at_create = ca.allocs - before;
  tlod_device_stats st = tlod_device_query_stats(s.dev);
  printf("  create: %ld host allocations through the context, %u memory blocks (%llu bytes), %u pipelines\n", at_create,
         st.vk.memory_blocks, (unsigned long long)st.vk.memory_bytes, st.vk.pipelines);
  CHECK_MSG(st.vk.memory_blocks > 0 && st.vk.memory_bytes > 0, "no device memory counted");
  shape sph = shape_icosphere(2);
  scene sc;
  CHECK(scene_make(&sc, s.ctx, s.pat, s.dev, &sph));
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  CALL(draw_scene_frames(&s, &sc, 4, rgba));
  st = tlod_device_query_stats(s.dev);
  printf("  4 frames: %u covered, %u checker pixels; last draw %u calls, %u sets, %llu upload bytes, ring %llu bytes, "
         "%u pipelines, gpu_ms %.3f (draw %llu)\n",
         covered_pixels(rgba, W, H), coloured_pixels(rgba), st.draw_calls, st.vk.descriptor_sets,
         (unsigned long long)st.vk.upload_bytes, (unsigned long long)st.vk.ring_bytes, st.vk.pipelines, st.gpu_ms,
         (unsigned long long)st.gpu_draw);
  CHECK(covered_pixels(rgba, W, H) > W * H / 10 && coloured_pixels(rgba) > 20);
  CHECK(st.vk.descriptor_sets == 3 && st.vk.upload_bytes > 3 * 256 && st.vk.ring_bytes >= st.vk.upload_bytes);
  /* The same scene in a slot that drew it before: its sets are kept, none written again. */
  CHECK_MSG(st.vk.descriptor_writes == 0, "frame 4 wrote %u descriptor sets (the same scene as frame 2 in its slot)",
            st.vk.descriptor_writes);
  CHECK(st.items == 3 && st.draw_calls > 3 && st.triangles > 0);
  /* Pattern buffers, the white texture, the checker, 2 rings and 2 x 2 x 2
   * surface buffers (11 objects) live in a few suballocated blocks. */
  CHECK_MSG(st.vk.memory_blocks <= 4, "%u VkDeviceMemory blocks for 11 buffers and images", st.vk.memory_blocks);
  CHECK_MSG(st.gpu_draw > 0 && st.gpu_ms >= 0.0, "no timestamp reading after 4 frames (gpu_draw %llu)",
            (unsigned long long)st.gpu_draw);
  /* Destroyed while the last frame may be in flight: retired, freed later. */
  tlod_device_destroy_texture(s.dev, sc.tex);
  sc.tex = NULL;
  sc.items[1].base_color_texture = NULL;
  fixture_free(&sc.plain);
  tlod_scheduler_destroy(sc.s0);
  sc.s0 = NULL;
  free(rgba);
  scene_free(&sc, s.dev);
  shape_free(&sph);
  tlod_platform* p = s.platform;
  s.platform = NULL;
  vk_session_close(&s);
  printf("  after destroy: %ld allocations, %ld frees\n", ca.allocs, ca.frees);
  CHECK_MSG(ca.allocs == ca.frees, "%ld allocations, %ld frees", ca.allocs, ca.frees);
  CHECK_MSG(at_create > 40, "only %ld allocations at create: Vulkan's host allocations do not reach the context",
            at_create);
  CALL(platform_clean(p));
}

/* ---- frame slots ------------------------------------------------------------- */

/* Mean column of the covered pixels. */
static double centroid_x(const uint8_t* rgba) {
  double sum = 0.0;
  uint32_t n = 0;
  for (uint32_t i = 0; i < W * H; i++)
    if (!is_background(rgba + 4 * i)) sum += i % W, n++;
  return n ? sum / n : -1.0;
}

static void move_mesh(fixture* fx, const shape* sph, float dx) {
  float* pos = malloc(sizeof(float) * 3 * sph->vertex_count);
  CHECK(pos);
  for (uint32_t i = 0; i < 3 * sph->vertex_count; i++)
    pos[i] = sph->positions[i] + (i % 3 == 0 ? dx : 0.0f);
  CHECK(tlod_mesh_update(fx->mesh, pos, 0, NULL, 0) == TLOD_SUCCESS);
  free(pos);
  CHECK(tlod_surface_refresh(fx->surf, NULL) == TLOD_SUCCESS);
  CHECK(tlod_device_update_surface(fx->dev, fx->ds) == TLOD_SUCCESS);
}

TEST(test_update_reaches_every_slot) {
  one_object o;
  camera cam = front_camera();
  CALL(object_open(&o, shape_icosphere(2), TLOD_SURFACE_PHONG, (tlod_device_vk_desc){0},
                   (tlod_scheduler_desc){.max_level = 3}, &cam));
  CHECK(vk_desc_of(o.s.platform).frames_in_flight == 2);
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  double x[4];
  uint32_t slot[4];
  for (int f = 0; f < 4; f++) {
    if (f == 2) CALL(move_mesh(&o.fx, &o.shp, 0.6f));
    CHECK(vk_draw_frame(o.s.platform, o.s.dev, o.s.ctx, &o.od.desc, rgba));
    x[f] = centroid_x(rgba);
    slot[f] = o.od.desc.vk.frame_index;
  }
  printf("  centroid x: slot %u %.2f, slot %u %.2f; after the update: slot %u %.2f, slot %u %.2f\n", slot[0], x[0],
         slot[1], x[1], slot[2], x[2], slot[3], x[3]);
  CHECK(slot[0] != slot[1] && slot[2] != slot[3]);
  CHECK(fabs(x[0] - x[1]) < 0.01 && fabs(x[2] - x[3]) < 0.01);
  CHECK_MSG(x[2] > x[0] + 4.0, "the update did not reach slot %u (%.2f -> %.2f)", slot[2], x[0], x[2]);
  free(rgba);
  CALL(object_close(&o));
}

/* A field's next time step (tlod_mesh_update_attribute) reaches every frame
 * slot at tlod_device_update_surface(), on a device of the quadratic type
 * only (the mask bit), through a fragment hook showing attribute 0. */
static bool centre_is(const uint8_t* rgba, const float rgb[3]) {
  const uint8_t* px = rgba + 4 * (W * (H / 2) + W / 2);
  for (int c = 0; c < 3; c++)
    if (abs((int)px[c] - (int)lroundf(rgb[c] * 255.0f)) > 2) return false;
  return true;
}

TEST(test_attribute_update_reaches_every_slot) {
  const float a[3] = {0.2f, 0.6f, 0.9f}, b[3] = {0.9f, 0.3f, 0.1f};
  vk_session s;
  tlod_device_vk_desc opt = {.surface_types = 1u << TLOD_SURFACE_QUADRATIC,
                             .fragment_hook =
                                 "vec4 tlod_shade(tlod_fragment f) { return vec4(f.attributes[0].rgb, 1.0); }\n"};
  CHECK_MSG(vk_session_open(&s, W, H, 3, "vk_device", true, opt), "no Vulkan device");
  qcube_coloured c;
  qcube_coloured_make(&c, a);
  fixture fx;
  CHECK(fixture_make_desc(&fx, s.ctx, &c.q.desc, TLOD_SURFACE_QUADRATIC, s.pat, s.dev));
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = 3});
  camera cam = front_camera();
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = NULL;
  CHECK(sch && (dl = plan(&fx, sch, &v, 16.0f)));
  one_draw od;
  one_draw_make(&od, fx.ds, dl, &v);
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  bool want_a[4], want_b[4];
  float next[QCUBE_VERTICES][3];
  for (int k = 0; k < QCUBE_VERTICES; k++)
    memcpy(next[k], b, sizeof b);
  for (int f = 0; f < 4; f++) {
    if (f == 2) {
      CHECK(tlod_mesh_update_attribute(fx.mesh, 0, &next[0][0], 0) == TLOD_SUCCESS);
      CHECK(tlod_device_update_surface(s.dev, fx.ds) == TLOD_SUCCESS);
    }
    CHECK(vk_draw_frame(s.platform, s.dev, s.ctx, &od.desc, rgba));
    want_a[f] = centre_is(rgba, a), want_b[f] = centre_is(rgba, b);
  }
  printf("  attribute update: frames 0-1 the first step %d %d, frames 2-3 (both slots) the next %d %d\n", want_a[0],
         want_a[1], want_b[2], want_b[3]);
  CHECK_MSG(want_a[0] && want_a[1] && want_b[2] && want_b[3], "the attribute update did not reach every slot");
  free(rgba);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  CALL(close_clean(&s));
}

/* Two views in one frame: the second draw appends to the frame's ring (it
 * must not overwrite what the first recorded). */
TEST(test_two_draws_in_one_frame) {
  one_object o;
  camera cam = camera_look(0, -4.0, 0.8, 0, 0, 0, 45, W / 2, H);
  CALL(object_open(&o, shape_icosphere(2), TLOD_SURFACE_PN, (tlod_device_vk_desc){0},
                   (tlod_scheduler_desc){.max_level = 4}, &cam));
  vk_session s = o.s;
  one_draw a, b;
  one_draw_make(&a, o.fx.ds, o.dl, &o.v);
  one_draw_make(&b, o.fx.ds, o.dl, &o.v);
  a.desc.viewport[2] = b.desc.viewport[2] = W / 2;
  b.desc.viewport[0] = W / 2;
  a.desc.light_dir[1] = b.desc.light_dir[1] = -1.0f; /* towards the camera */
  b.item.has_color = true;
  b.item.color[0] = 1.0f, b.item.color[3] = 1.0f; /* red: not a's grey */
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba && vk_frame_begin(s.platform, &a.desc));
  b.desc.vk = a.desc.vk;
  CHECK(tlod_device_draw(s.dev, &a.desc) == TLOD_SUCCESS && tlod_device_draw(s.dev, &b.desc) == TLOD_SUCCESS);
  CHECK(vk_frame_end(s.platform, rgba));
  uint32_t grey = 0, red = 0;
  for (uint32_t i = 0; i < W * H; i++) {
    const uint8_t* px = rgba + 4 * i;
    if (is_background(px)) continue;
    bool left = i % W < W / 2;
    grey += left && px[0] == px[1];
    red += !left && px[0] > px[1] + 40;
  }
  printf("  left half %u grey pixels, right half %u red pixels\n", grey, red);
  CHECK(grey > 200 && red > 200 && abs((int)grey - (int)red) < 40);
  free(rgba);
  CALL(object_close(&o));
}

/* Every debug view, with and without wireframe, on the pattern path and on
 * the hardware path (tessellation pipelines, batches): drawn, and clean. */
static void draw_views(bool hardware) {
  one_object o;
  tlod_device_vk_desc opt = {.hardware_tessellation = hardware};
  tlod_scheduler_desc sd = {.max_level = 5, .morph = hardware ? TLOD_MORPH_NONE : TLOD_MORPH_DEFAULT};
  camera cam = camera_look(0, -2.6, 1.4, 0, 0, 0, 45, W, H);
  CALL(object_open(&o, shape_torus(12, 8), TLOD_SURFACE_PN, opt, sd, &cam));
  vk_session s = o.s;
  one_draw od = o.od;
  od.desc.items = &od.item;
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  for (int k = 0; k < 2 * TLOD_DEBUG_NUM; k++) {
    od.desc.debug = (tlod_debug_view)(k % TLOD_DEBUG_NUM);
    od.desc.wireframe = k >= TLOD_DEBUG_NUM;
    CHECK_MSG(vk_draw_frame(s.platform, s.dev, s.ctx, &od.desc, rgba), "debug %d wireframe %d", k % TLOD_DEBUG_NUM,
              od.desc.wireframe);
    CHECK_MSG(covered_pixels(rgba, W, H) > W * H / 20, "debug %d wireframe %d: %u pixels", k % TLOD_DEBUG_NUM,
              od.desc.wireframe, covered_pixels(rgba, W, H));
  }
  tlod_device_stats st = tlod_device_query_stats(s.dev);
  printf("  %s path: %u debug views x wireframe off/on drawn, %u pipelines, %u draw calls in the last\n",
         hardware ? "hardware" : "pattern", TLOD_DEBUG_NUM, st.vk.pipelines, st.draw_calls);
  free(rgba);
  CALL(object_close(&o));
}

TEST(test_debug_views_and_wireframe) {
  CALL(draw_views(false));
  CALL(draw_views(true));
}

/* A fragment hook that does not compile: TLOD_ERROR_BACKEND naming the
 * hook's line. */
TEST(test_hook_error_names_line) {
  char err[512] = "";
  tlod_platform* p = vk_test_platform(W, H, true, err, sizeof err);
  CHECK_MSG(p, "no Vulkan device: %s", err);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = new_patterns(ctx, 3);
  CHECK(pat);
  tlod_device_vk_desc vk = vk_desc_of(p);
  vk.fragment_hook = "vec4 tlod_shade(tlod_fragment f) {\n  return no_such_name;\n}\n";
  tlod_device* dev = (tlod_device*)1;
  tlod_result r = tlod_device_create(ctx, &(tlod_device_desc){.backend = "vulkan", .patterns = pat, .vk = vk}, &dev);
  const char* msg = tlod_context_last_error(ctx);
  printf("  bad hook: %s: %s\n", tlod_result_string(r), msg);
  CHECK_MSG(r == TLOD_ERROR_BACKEND && dev == NULL && has(msg, "fragment_hook:2"), "%s", msg);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  CALL(platform_clean(p));
}

int main(void) {
  RUN(test_desc_fields_refused);
  RUN(test_draw_fields_refused);
  RUN(test_destroy_frees_everything);
  RUN(test_update_reaches_every_slot);
  RUN(test_attribute_update_reaches_every_slot);
  RUN(test_two_draws_in_one_frame);
  RUN(test_debug_views_and_wireframe);
  RUN(test_hook_error_names_line);
  VK_TEST_END();
}
