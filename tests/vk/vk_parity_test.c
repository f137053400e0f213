/*
 * vk_parity_test.c -- the "vulkan" device draws the image the "gl" device
 * draws, and what the CPU reference tessellator computes (owned by the
 * Vulkan tests). Public API only; docs/vulkan_parity.md explains the
 * tolerances below.
 *
 * One process holds a headless GL platform (EGL, llvmpipe) with a "gl"
 * device and a headless Vulkan platform (lavapipe) with a "vulkan" device,
 * on one tesslod context and one pattern set; both images are W x H, cleared
 * to pure blue, read back top row first. For each case the SAME draw desc
 * (same draw list, view, projection, items) is drawn by both devices:
 *   shapes:  icosphere(2), torus(16, 10), cube_soft (split normals) under
 *            Phong and PN, the icosphere flat, quadratic_cube.h's curved
 *            cube under TLOD_SURFACE_QUADRATIC; two cameras each (an
 *            oblique one, then a closer grazing one 60 ms later, so the
 *            second list carries fractional geomorph blends);
 *   scene:   four items with model matrices, colours, a light direction, a
 *            textured sphere (sRGB checker), a MASK item (the checker's
 *            transparent texels cut away), a BLEND item, back-face culling;
 *            drawn shaded, with the LEVELS debug view and with wireframe
 *            (line pixels compared by count, see mask_lines).
 *   hardware path: icosphere and torus, Phong and PN, and the quadratic
 *            cube, the two cameras, on devices with hardware_tessellation
 *            (GL against Vulkan only);
 * Besides, each shape frame's draw list is realised by tlod_cpu_tessellate
 * and drawn by gl_test.h's independent mesh renderer (image R).
 *
 * TOLERANCES (why):
 *   Vulkan vs GL: the same GLSL sources, the same float evaluation; the
 *     devices differ only in the clip-space depth remap (z' = (z + w) / 2;
 *     x, y, w bitwise GL's) and in the rasterisers (lavapipe and llvmpipe
 *     share Mesa's gallium rasteriser, but the viewport transform differs:
 *     a negative-height Vulkan viewport against GL's). So:
 *       coverage: a pixel covered in one image only must lie on GL's
 *         1-pixel silhouette band, and at most 0.1% of the covered pixels;
 *       colour: on pixels covered by both, max channel difference <= 2/255
 *         on >= 99.5% of them (depth ties between a front and a back face
 *         at a silhouette can swap which one wins);
 *   CPU-mesh mode (a third device, "vulkan" with gpu_eval OFF: the list
 *     evaluated by tlod_cpu_tessellate_into, one indexed draw) against the
 *     GPU-eval Vulkan image, with the tolerances against R below; it
 *     reports the mode, evaluates once, and a second draw of the same list
 *     evaluates nothing and gives its image again bitwise.
 *   Vulkan vs the CPU mesh (R): as tests/gl/gl_parity_test.c for GL: the
 *     GPU evaluates the surface in float with its own operation order, so
 *     coverage may differ on R's silhouette band only (at most 0.5%), and
 *     colour within 8/255 on >= 99% of the commonly covered pixels.
 */
#include "quadratic_cube.h"
#include "vk_gl_test.h"

#define W 192
#define H 192
#define MAX_LEVEL 5

#define VG_BAND_PERMILLE 1 /* Vulkan vs GL: coverage differences, per mille of the covered pixels */
#define VG_COLOUR 2        /* ... max channel difference on both-covered pixels */
#define VG_FRACTION 0.995  /* ... on at least this fraction */
#define VR_BAND_PERMILLE 5 /* Vulkan vs the CPU mesh */
#define VR_COLOUR 8
#define VR_FRACTION 0.99

typedef struct parity_env {
  vk_gl_env b;
  tlod_device *gl_dev, *vk_dev;
  tlod_device* vk_cpu_dev; /* gpu_eval OFF (not on the hardware path) */
  unsigned char* prev;     /* the instances and strips vk_cpu_dev drew last on this surface */
  size_t prev_bytes;       /* SIZE_MAX: none */
  uint8_t *img_gl, *img_vk, *img_ref, *img_cpu, *img_again;
} parity_env;

/* Totals for the summary line. */
static struct {
  uint32_t comparisons;
  uint64_t covered, gl_diff, ref_diff;
  uint32_t gl_worst, ref_worst;
} s_totals;

typedef struct tolerance {
  uint32_t band_permille, colour;
  double fraction;
} tolerance;

/* Compares img_vk with a reference image; prints one line. */
static void check_pair(const uint8_t* vk, const uint8_t* ref, tolerance t, const char* what, const char* against,
                       uint64_t* diff_total, uint32_t* worst) {
  compare_result c = compare_images(vk, ref, W, H, t.colour);
  double fraction = c.covered_both ? (double)c.colour_ok / c.covered_both : 1.0;
  printf("  %-34s vs %-3s covered %5u/%5u, differ %3u, off band %u | colour max %3u mean %.2f, %.2f%% <= %u\n", what,
         against, c.covered_a, c.covered_b, c.coverage_diff, c.off_band, c.max_colour_diff, c.mean_colour_diff,
         100.0 * fraction, t.colour);
  *diff_total += c.coverage_diff;
  if (c.max_colour_diff > *worst) *worst = c.max_colour_diff;
  CHECK_MSG(c.covered_b > 500, "%s: %s covers only %u pixels (camera misses the object)", what, against, c.covered_b);
  CHECK_MSG(c.off_band == 0, "%s vs %s: %u pixels differ in coverage off the band, first at (%d, %d) (row 0 = top)",
            what, against, c.off_band, c.off_band_x, c.off_band_y);
  CHECK_MSG(c.coverage_diff * 1000 <= t.band_permille * c.covered_either,
            "%s vs %s: coverage differs on %u of %u pixels (> %u per mille)", what, against, c.coverage_diff,
            c.covered_either, t.band_permille);
  CHECK_MSG(fraction >= t.fraction, "%s vs %s: only %.2f%% of %u common pixels within %u/255 (max %u)", what, against,
            100.0 * fraction, c.covered_both, t.colour, c.max_colour_diff);
}

/* The same desc drawn by both devices: img_gl, img_vk. desc.items name the
 * GL device's surfaces; vk_items the Vulkan device's (same order). */
static void draw_both(parity_env* env, tlod_draw_desc* desc, const tlod_draw_item* vk_items, const char* what) {
  tlod_platform_bind(env->b.gl);
  clear_frame(W, H);
  tlod_result r = tlod_device_draw(env->gl_dev, desc);
  CHECK_MSG(r == TLOD_SUCCESS, "%s: gl draw: %s: %s", what, tlod_result_string(r), tlod_context_last_error(env->b.ctx));
  CHECK_MSG(tlod_platform_read_rgba(env->b.gl, env->img_gl), "%s: gl read", what);
  tlod_draw_desc vd = *desc;
  vd.items = vk_items;
  CHECK_MSG(vk_draw_frame(env->b.vk, env->vk_dev, env->b.ctx, &vd, env->img_vk), "%s: vulkan frame", what);
  s_totals.comparisons++;
  s_totals.covered += covered_pixels(env->img_gl, W, H);
}

static const tolerance k_vs_gl = {VG_BAND_PERMILLE, VG_COLOUR, VG_FRACTION};
static const tolerance k_vs_ref = {VR_BAND_PERMILLE, VR_COLOUR, VR_FRACTION};

/* The draw list's CPU mesh through the independent renderer: img_ref. */
static void draw_reference(parity_env* env, const fixture* fx, const tlod_draw_list* dl, const tlod_view_desc* v) {
  tlod_platform_bind(env->b.gl);
  tlod_cpu_mesh* m = ref_draw_list(&env->b.ref, fx, dl, v, W, H, false);
  CHECK_MSG(m, "CPU realisation failed");
  tlod_cpu_mesh_destroy(fx->ctx, m);
  CHECK(tlod_platform_read_rgba(env->b.gl, env->img_ref));
}

/* The CPU-mesh device's image of item vi (its surface on vk_cpu_dev)
 * against the GPU-eval Vulkan image; the mode reported; the second draw
 * evaluating nothing. */
static void check_cpu_mesh(parity_env* env, const tlod_draw_desc* desc, tlod_draw_item vi, const char* what) {
  const tlod_draw_list* dl = vi.draw_list;
  size_t ib = sizeof(tlod_draw_instance) * dl->instance_count, sb = sizeof(tlod_draw_strip) * dl->strip_count;
  /* Equal to the last list (another camera, every patch at one level): the mesh is kept. */
  bool same = env->prev && env->prev_bytes == ib + sb && (ib == 0 || !memcmp(env->prev, dl->instances, ib)) &&
              (sb == 0 || !memcmp(env->prev + ib, dl->strips, sb));
  free(env->prev);
  CHECK(env->prev = malloc(ib + sb + 1u));
  if (ib) memcpy(env->prev, dl->instances, ib);
  if (sb) memcpy(env->prev + ib, dl->strips, sb);
  env->prev_bytes = ib + sb;
  tlod_draw_desc vd = *desc;
  vd.items = &vi;
  char label[128];
  snprintf(label, sizeof label, "%s cpu mesh", what);
  CHECK_MSG(vk_draw_frame(env->b.vk, env->vk_cpu_dev, env->b.ctx, &vd, env->img_cpu), "%s: vulkan frame", label);
  tlod_device_stats t = tlod_device_query_stats(env->vk_cpu_dev);
  CHECK_MSG(t.cpu_mesh && strstr(t.gpu_eval_reason, "off"), "%s: mode not reported: cpu_mesh %d, '%s'", label,
            t.cpu_mesh, t.gpu_eval_reason);
  CHECK_MSG(t.mesh_evaluations == (same ? 0u : 1u) && t.mesh_bytes > 0, "%s: %u evaluations (expected %u), %llu bytes",
            label, t.mesh_evaluations, same ? 0u : 1u, (unsigned long long)t.mesh_bytes);
  CALL(check_pair(env->img_cpu, env->img_vk, k_vs_ref, label, "vk", &s_totals.ref_diff, &s_totals.ref_worst));
  CHECK_MSG(vk_draw_frame(env->b.vk, env->vk_cpu_dev, env->b.ctx, &vd, env->img_again), "%s: vulkan frame", label);
  t = tlod_device_query_stats(env->vk_cpu_dev);
  CHECK_MSG(t.mesh_evaluations == 0, "%s: the same list again: %u evaluations (expected 0)", label, t.mesh_evaluations);
  CHECK_MSG(!memcmp(env->img_again, env->img_cpu, 4 * W * H), "%s: the reused mesh draws another image", label);
}

/* with_cpu: also against the CPU mesh (not on the hardware path: its
 * triangles are the tessellator's, not the draw list's). */
static void one_surface(parity_env* env, const tlod_mesh_desc* md, tlod_surface_type type, bool with_cpu) {
  fixture fx;
  CHECK(fixture_make_desc(&fx, env->b.ctx, md, type, env->b.pat, env->gl_dev));
  tlod_device_surface* vds = NULL;
  tlod_result r = tlod_device_create_surface(env->vk_dev, fx.surf, &vds);
  CHECK_MSG(r == TLOD_SUCCESS, "vulkan surface: %s: %s", tlod_result_string(r), tlod_context_last_error(env->b.ctx));
  tlod_device_surface* cds = NULL;
  if (env->vk_cpu_dev) CHECK(tlod_device_create_surface(env->vk_cpu_dev, fx.surf, &cds) == TLOD_SUCCESS);
  env->prev_bytes = SIZE_MAX;
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
  CHECK(sch);
  camera cams[2] = {camera_look(2.6, -3.4, 1.9, 0, 0, 0, 45, W, H),
                    camera_look(1.25, 1.9, 0.35, 0.15, 0.1, 0.05, 60, W, H)};
  for (int ci = 0; ci < 2; ++ci) {
    tlod_view_desc v = make_view(&cams[ci]);
    const tlod_draw_list* dl = plan(&fx, sch, &v, ci == 0 ? 0.0f : 60.0f);
    CHECK(dl);
    char what[96];
    snprintf(what, sizeof what, "%s %s cam %d", md->label, type_name(type), ci);
    one_draw d;
    one_draw_make(&d, fx.ds, dl, &v);
    tlod_draw_item vi = d.item;
    vi.surface = vds;
    CALL(draw_both(env, &d.desc, &vi, what));
    CALL(check_pair(env->img_vk, env->img_gl, k_vs_gl, what, "gl", &s_totals.gl_diff, &s_totals.gl_worst));
    vi.surface = cds;
    if (cds) CALL(check_cpu_mesh(env, &d.desc, vi, what));
    if (!with_cpu) continue;
    CALL(draw_reference(env, &fx, dl, &v));
    CALL(check_pair(env->img_vk, env->img_ref, k_vs_ref, what, "cpu", &s_totals.ref_diff, &s_totals.ref_worst));
  }
  tlod_scheduler_destroy(sch);
  tlod_device_destroy_surface(env->vk_dev, vds);
  tlod_device_destroy_surface(env->vk_cpu_dev, cds);
  fixture_free(&fx);
}

/* hardware: both devices on the hardware tessellation path. */
static bool env_open(parity_env* env, bool hardware) {
  memset(env, 0, sizeof *env);
  if (!vk_gl_open(&env->b, W, H, MAX_LEVEL)) return false;
  env->img_gl = malloc(4 * W * H), env->img_vk = malloc(4 * W * H), env->img_ref = malloc(4 * W * H);
  env->img_cpu = malloc(4 * W * H), env->img_again = malloc(4 * W * H);
  if (!env->img_gl || !env->img_vk || !env->img_ref || !env->img_cpu || !env->img_again) return false;
  tlod_device_gl_desc gl = {.hardware_tessellation = hardware};
  if (!(env->gl_dev = new_gl_device(env->b.ctx, env->b.pat, "parity gl", gl))) return false;
  tlod_device_vk_desc vk = vk_desc_of(env->b.vk);
  vk.hardware_tessellation = hardware;
  env->vk_dev = new_vk_device(env->b.ctx, env->b.pat, "parity vulkan", vk);
  if (!hardware) {
    vk.gpu_eval = TLOD_GPU_EVAL_OFF;
    if (!(env->vk_cpu_dev = new_vk_device(env->b.ctx, env->b.pat, "parity vulkan cpu mesh", vk))) return false;
  }
  tlod_platform_bind(env->b.gl);
  return env->vk_dev != NULL;
}

static void one_shape(parity_env* env, const shape* s, tlod_surface_type type, bool with_cpu) {
  tlod_mesh_desc md = shape_mesh_desc(s);
  one_surface(env, &md, type, with_cpu);
}

/* quadratic_cube.h's curved second-order cube under TLOD_SURFACE_QUADRATIC. */
static void quadratic_cube_case(parity_env* env, bool with_cpu) {
  qcube q;
  qcube_make(&q);
  one_surface(env, &q.desc, TLOD_SURFACE_QUADRATIC, with_cpu);
}

static void env_close(parity_env* env) {
  if (env->b.vk) tlod_platform_finish(env->b.vk);
  if (env->b.gl) tlod_platform_bind(env->b.gl);
  tlod_device_destroy(env->gl_dev);
  tlod_device_destroy(env->vk_dev);
  tlod_device_destroy(env->vk_cpu_dev);
  free(env->img_gl), free(env->img_vk), free(env->img_ref), free(env->img_cpu), free(env->img_again), free(env->prev);
  vk_gl_close(&env->b);
  memset(env, 0, sizeof *env);
}

TEST(test_shapes_match_gl_and_cpu) {
  parity_env env;
  bool opened = env_open(&env, false);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL + Vulkan devices (see above)");
  shape shapes[3] = {shape_icosphere(2), shape_torus(16, 10), shape_cube_soft()};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti)
      CALL(one_shape(&env, &shapes[si], types[ti], true));
  CALL(one_shape(&env, &shapes[0], TLOD_SURFACE_FLAT, true));
  CALL(quadratic_cube_case(&env, true));
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  CALL(vk_check_no_messages());
  printf("  %u frames: coverage differs on %llu (vs gl) / %llu (vs cpu) of %llu covered pixels; worst colour diff "
         "%u / %u\n",
         s_totals.comparisons, (unsigned long long)s_totals.gl_diff, (unsigned long long)s_totals.ref_diff,
         (unsigned long long)s_totals.covered, s_totals.gl_worst, s_totals.ref_worst);
}

/* ---- a material scene, GL vs Vulkan ------------------------------------------ */

typedef struct material_scene {
  shape sph, torus;
  uv_sphere uvs;
  fixture fx[3]; /* on the GL device */
  tlod_device_surface* vds[3];
  tlod_device_texture *gl_tex, *vk_tex;
  tlod_scheduler* sch[4];
  tlod_draw_item gl_items[4], vk_items[4];
} material_scene;

static tlod_device_texture* checker(tlod_device* dev) {
  uint8_t texels[4 * 4 * 4];
  for (int i = 0; i < 16; ++i) {
    bool odd = ((i % 4) + (i / 4)) % 2;
    uint8_t px[4] = {odd ? 230 : 40, odd ? 120 : 200, odd ? 20 : 90, odd ? 0 : 255};
    memcpy(texels + 4 * i, px, 4);
  }
  tlod_device_texture* t = NULL;
  tlod_texture_desc td = {.width = 4, .height = 4, .rgba8 = texels, .srgb = true, .mag_filter = TLOD_FILTER_NEAREST};
  return tlod_device_create_texture(dev, &td, &t) == TLOD_SUCCESS ? t : NULL;
}

static void place(float m[16], double x, double y, double z, double s) {
  memset(m, 0, 16 * sizeof *m);
  m[0] = m[5] = m[10] = (float)s;
  m[12] = (float)x, m[13] = (float)y, m[14] = (float)z, m[15] = 1.0f;
}

static void material_open(material_scene* ms, parity_env* env) {
  memset(ms, 0, sizeof *ms);
  ms->sph = shape_icosphere(2), ms->torus = shape_torus(16, 10);
  CHECK(uv_sphere_make(&ms->uvs, 10, 20));
  tlod_mesh_desc descs[3] = {shape_mesh_desc(&ms->sph), shape_mesh_desc(&ms->torus), ms->uvs.desc};
  const tlod_surface_type types[3] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN, TLOD_SURFACE_PHONG};
  for (int k = 0; k < 3; ++k) {
    CHECK(fixture_make_desc(&ms->fx[k], env->b.ctx, &descs[k], types[k], env->b.pat, env->gl_dev));
    CHECK(tlod_device_create_surface(env->vk_dev, ms->fx[k].surf, &ms->vds[k]) == TLOD_SUCCESS);
  }
  CHECK(ms->gl_tex = checker(env->gl_dev));
  CHECK(ms->vk_tex = checker(env->vk_dev));
  const int surf_of[4] = {0, 1, 2, 2};
  for (int i = 0; i < 4; ++i) {
    CHECK(ms->sch[i] = new_scheduler(&ms->fx[surf_of[i]], (tlod_scheduler_desc){.max_level = MAX_LEVEL}));
    tlod_draw_item* it = &ms->gl_items[i];
    it->surface = ms->fx[surf_of[i]].ds;
    it->has_model = true;
  }
  place(ms->gl_items[0].model, -1.1, 0.0, 0.0, 0.8);
  ms->gl_items[0].has_color = true;
  memcpy(ms->gl_items[0].color, (float[4]){0.9f, 0.3f, 0.2f, 1.0f}, sizeof(float[4]));
  place(ms->gl_items[1].model, 0.2, -0.6, 0.3, 0.9); /* in front: BLEND over the others */
  ms->gl_items[1].blend = TLOD_BLEND_BLEND;
  ms->gl_items[1].has_color = true;
  memcpy(ms->gl_items[1].color, (float[4]){0.2f, 0.6f, 1.0f, 0.5f}, sizeof(float[4]));
  place(ms->gl_items[2].model, 1.1, 0.4, 0.0, 0.8);
  ms->gl_items[2].base_color_texture = ms->gl_tex;
  ms->gl_items[2].cull_back_faces = true;
  place(ms->gl_items[3].model, 0.0, 0.8, 1.0, 0.7);
  ms->gl_items[3].base_color_texture = ms->gl_tex;
  ms->gl_items[3].blend = TLOD_BLEND_MASK;
}

static void material_close(material_scene* ms, parity_env* env) {
  for (int i = 0; i < 4; ++i)
    tlod_scheduler_destroy(ms->sch[i]);
  for (int k = 0; k < 3; ++k) {
    tlod_device_destroy_surface(env->vk_dev, ms->vds[k]);
    if (ms->fx[k].mesh) fixture_free(&ms->fx[k]);
  }
  tlod_device_destroy_texture(env->gl_dev, ms->gl_tex);
  tlod_device_destroy_texture(env->vk_dev, ms->vk_tex);
  shape_free(&ms->sph), shape_free(&ms->torus);
  uv_sphere_free(&ms->uvs);
}

/* Plans every item for v and mirrors the items onto the Vulkan device. */
static void material_plan(material_scene* ms, parity_env* env, const tlod_view_desc* v) {
  const int surf_of[4] = {0, 1, 2, 2};
  for (int i = 0; i < 4; ++i) {
    tlod_view_desc ov = object_view(v, ms->gl_items[i].model);
    tlod_frame_desc f = {.views = &ov, .view_count = 1, .dt_ms = 0.0f};
    CHECK(ms->gl_items[i].draw_list = scheduler_plan(env->b.ctx, ms->sch[i], &f));
    ms->vk_items[i] = ms->gl_items[i];
    ms->vk_items[i].surface = ms->vds[surf_of[i]];
    if (ms->gl_items[i].base_color_texture) ms->vk_items[i].base_color_texture = ms->vk_tex;
  }
}

/* The wireframe overlay is drawn as lines in the edge colour (0.05, 0.05,
 * 0.05) = 13/255, and GL's and Vulkan's line rasterisation rules differ
 * (diamond exit vs parallelogram): a line pixel of one image may be the
 * surface beside the line in the other. Both images must draw about as many
 * line pixels (within 15%); then the pixels within one pixel of a line in
 * either image are set equal in both, and the rest is compared as usual. */
static bool is_line(const uint8_t* p) { return p[0] == 13 && p[1] == 13 && p[2] == 13; }

static bool near_line(const uint8_t* img, uint32_t x, uint32_t y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int nx = (int)x + dx, ny = (int)y + dy;
      if (nx >= 0 && ny >= 0 && nx < W && ny < H && is_line(img + 4 * ((size_t)ny * W + (size_t)nx))) return true;
    }
  return false;
}

static void mask_lines(parity_env* env) {
  uint32_t lines_gl = 0, lines_vk = 0;
  for (uint32_t i = 0; i < W * H; ++i)
    lines_gl += is_line(env->img_gl + 4 * i), lines_vk += is_line(env->img_vk + 4 * i);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      if (near_line(env->img_gl, x, y) || near_line(env->img_vk, x, y))
        env->img_gl[4 * (y * W + x) + 3] = 1; /* mark: alpha is not compared */
  for (uint32_t i = 0; i < W * H; ++i)
    if (env->img_gl[4 * i + 3] == 1) memcpy(env->img_vk + 4 * i, env->img_gl + 4 * i, 4);
  printf("  wireframe: %u line pixels (gl), %u (vulkan)\n", lines_gl, lines_vk);
  CHECK_MSG(lines_gl > 200 && lines_vk * 100 >= lines_gl * 85 && lines_vk * 100 <= lines_gl * 115,
            "wireframe: %u line pixels in the GL image, %u in the Vulkan one", lines_gl, lines_vk);
}

TEST(test_materials_match_gl) {
  parity_env env;
  bool opened = env_open(&env, false);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL + Vulkan devices (see above)");
  material_scene ms;
  CALL(material_open(&ms, &env));
  camera cam = camera_look(3.2, -4.4, 2.4, 0, 0, 0.2, 45, W, H);
  cam.znear = 1.0, cam.zfar = 12.0;
  tlod_view_desc v = make_view(&cam);
  CALL(material_plan(&ms, &env, &v));
  tlod_draw_desc d;
  memset(&d, 0, sizeof d);
  d.items = ms.gl_items, d.item_count = 4;
  memcpy(d.view, v.view, sizeof d.view), memcpy(d.proj, v.proj, sizeof d.proj);
  d.viewport[2] = W, d.viewport[3] = H;
  d.light_dir[0] = -0.4f, d.light_dir[1] = -0.5f, d.light_dir[2] = 0.8f;
  const char* names[3] = {"materials shaded", "materials LEVELS view", "materials wireframe"};
  for (int k = 0; k < 3; ++k) {
    d.debug = k == 1 ? TLOD_DEBUG_LEVELS : TLOD_DEBUG_NONE;
    d.wireframe = k == 2;
    CALL(draw_both(&env, &d, ms.vk_items, names[k]));
    if (d.wireframe) CALL(mask_lines(&env));
    /* not CALL: every view is compared and printed, a failed one still fails the test */
    check_pair(env.img_vk, env.img_gl, k_vs_gl, names[k], "gl", &s_totals.gl_diff, &s_totals.gl_worst);
  }
  tlod_platform_finish(env.b.vk);
  material_close(&ms, &env);
  env_close(&env);
  CALL(vk_check_no_messages());
}

/* The hardware tessellation path: the same image as GL's hardware path
 * (winding, facing and the flipped back-face normal included). */
TEST(test_hardware_path_matches_gl) {
  parity_env env;
  bool opened = env_open(&env, true);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL + Vulkan hardware-tessellation devices (see above)");
  shape shapes[2] = {shape_icosphere(2), shape_torus(16, 10)};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 2; ++si)
    for (int ti = 0; ti < 2; ++ti)
      CALL(one_shape(&env, &shapes[si], types[ti], false));
  CALL(quadratic_cube_case(&env, false));
  for (int k = 0; k < 2; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  CALL(vk_check_no_messages());
}

int main(void) {
  RUN(test_shapes_match_gl_and_cpu);
  RUN(test_hardware_path_matches_gl);
  RUN(test_materials_match_gl);
  VK_TEST_END();
}
