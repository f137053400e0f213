/*
 * gl_material_test.c -- the materials of the "gl" device (tesslod/backend.h
 * tlod_draw_item, tesslod/gl.h fragment hooks), checked by pixels against
 * values computed here (owned by the GL tests). Public API only.
 *
 * The scenes are seen by an orthographic camera on +z looking down -z, the
 * light along +z (Lambert factor exactly 1 on surfaces facing the camera),
 * so a pixel's expected colour is known in closed form:
 *   - a fragment hook writing the TEXCOORD_0 attribute as colour, on a flat
 *     quad grid (bilinear UVs on squares: affine, exact per pixel) and on a
 *     lat-long sphere (UVs from the ray's hit point, away from the seam and
 *     poles: the linear interpolation and the curved patch differ a little),
 *     and against the cpu tessellator's attributes of the same draw list;
 *     a hook with an error fails the device naming its line;
 *   - a 2 x 2 texture on the quad: each quadrant shows its texel (RGBA8 and
 *     sRGB), the image's top row at the top (glTF orientation);
 *   - items of different colours and model matrices: each one's colour at
 *     its projected centre;
 *   - MASK discards below the cutoff; a BLEND item in front of an opaque one
 *     listed after it blends over it; two BLEND items blend farthest first
 *     whatever their order; cull_back_faces culls a quad turned away;
 *     a both-sided quad turned away is lit with the flipped normal.
 */
#include "gl_test.h"

#define W 128
#define H 128
#define HALF 1.25 /* orthographic half extent */
#define GRID 4    /* quads per side of the flat grid */

/* ---- scene ------------------------------------------------------------- */

static camera ortho_camera(void) {
  return (camera){.eye = {0, 0, 3},
                  .target = {0, 0, 0},
                  .up = {0, 1, 0},
                  .half_h = HALF,
                  .aspect = 1.0,
                  .znear = 0.5,
                  .zfar = 10.0,
                  .ortho = true,
                  .width = W,
                  .height = H};
}

/* World x, y at the centre of pixel (px, py), py = 0 the bottom row. */
static void pixel_world(uint32_t px, uint32_t py, double* x, double* y) {
  *x = ((px + 0.5) / W * 2.0 - 1.0) * HALF;
  *y = ((py + 0.5) / H * 2.0 - 1.0) * HALF;
}

/* The pixel showing world (x, y). */
static const uint8_t* pixel_at(const uint8_t* rgba, double x, double y) {
  uint32_t px = (uint32_t)((x / HALF + 1.0) * 0.5 * W), py = (uint32_t)((y / HALF + 1.0) * 0.5 * H);
  return rgba + 4 * ((size_t)py * W + px);
}

/* A flat GRID x GRID quad grid on [-1, 1]^2 at z = 0, facing +z, with
 * TEXCOORD_0 = ((x + 1) / 2, (1 - y) / 2): (0, 0) at the top-left, glTF's. */
typedef struct grid_mesh {
  float pos[3 * (GRID + 1) * (GRID + 1)], nrm[3 * (GRID + 1) * (GRID + 1)], uv[2 * (GRID + 1) * (GRID + 1)];
  uint32_t idx[4 * GRID * GRID];
  tlod_attribute_desc attr;
  tlod_mesh_desc desc;
} grid_mesh;

static void grid_make(grid_mesh* g) {
  memset(g, 0, sizeof *g);
  for (uint32_t j = 0; j <= GRID; j++)
    for (uint32_t i = 0; i <= GRID; i++) {
      uint32_t v = j * (GRID + 1) + i;
      float x = -1.0f + 2.0f * (float)i / GRID, y = -1.0f + 2.0f * (float)j / GRID;
      g->pos[3 * v] = x, g->pos[3 * v + 1] = y;
      g->nrm[3 * v + 2] = 1.0f;
      g->uv[2 * v] = (x + 1.0f) * 0.5f, g->uv[2 * v + 1] = (1.0f - y) * 0.5f;
    }
  for (uint32_t j = 0, k = 0; j < GRID; j++)
    for (uint32_t i = 0; i < GRID; i++, k += 4) {
      uint32_t a = j * (GRID + 1) + i;
      g->idx[k] = a, g->idx[k + 1] = a + 1, g->idx[k + 2] = a + GRID + 2, g->idx[k + 3] = a + GRID + 1;
    }
  g->attr = (tlod_attribute_desc){.data = g->uv, .components = 2, .name = "TEXCOORD_0"};
  g->desc = (tlod_mesh_desc){.positions = g->pos,
                             .normals = g->nrm,
                             .vertex_count = (GRID + 1) * (GRID + 1),
                             .indices = g->idx,
                             .index_count = 4 * GRID * GRID,
                             .face_type = TLOD_FACE_QUADS,
                             .normal_mode = TLOD_NORMALS_KEEP,
                             .label = "uv_grid",
                             .attributes = &g->attr,
                             .attribute_count = 1};
}

/* Column-major: scale s, then translation t. */
static void place(float m[16], float s, float tx, float ty, float tz) {
  memset(m, 0, sizeof(float) * 16);
  m[0] = m[5] = m[10] = s;
  m[12] = tx, m[13] = ty, m[14] = tz, m[15] = 1.0f;
}

/* A session with the default material, an image buffer and the quad grid. */
static void material_open(gl_session* gs, const char* label, uint8_t** rgba, grid_mesh* g) {
  CHECK_MSG(gl_session_open(gs, W, H, 5, label, (tlod_device_gl_desc){0}), "no GL context or device (see above)");
  *rgba = malloc(4 * W * H);
  CHECK(*rgba);
  grid_make(g);
}

/* An object of a scene: fixture, scheduler, its item. */
typedef struct object {
  fixture fx;
  tlod_scheduler* sched;
} object;

static bool object_make(object* o, gl_session* gs, const tlod_mesh_desc* md, tlod_surface_type type) {
  memset(o, 0, sizeof *o);
  if (!fixture_make_desc(&o->fx, gs->ctx, md, type, gs->pat, gs->dev)) return false;
  o->sched = new_scheduler(&o->fx, (tlod_scheduler_desc){.max_level = 5});
  return o->sched != NULL;
}

static void object_free(object* o) {
  tlod_scheduler_destroy(o->sched);
  fixture_free(&o->fx);
}

/* Plans every item's object and draws them in one tlod_device_draw, into a
 * cleared frame; reads the image. */
static bool draw_scene(gl_session* gs, object* objs, tlod_draw_item* items, uint32_t n, uint8_t* rgba) {
  camera cam = ortho_camera();
  tlod_view_desc v = make_view(&cam);
  for (uint32_t k = 0; k < n; k++) {
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    tlod_view_desc ov = object_view(&v, items[k].has_model ? items[k].model : identity);
    items[k].surface = objs[k].fx.ds;
    items[k].draw_list = plan(&objs[k].fx, objs[k].sched, &ov, 0.0f);
    if (!items[k].draw_list) return false;
  }
  tlod_platform_bind(gs->platform);
  clear_frame(W, H);
  tlod_draw_desc d = {.items = items, .item_count = n, .viewport = {0, 0, W, H}, .light_dir = {0, 0, 1}};
  memcpy(d.view, v.view, sizeof d.view);
  memcpy(d.proj, v.proj, sizeof d.proj);
  tlod_result r = tlod_device_draw(gs->dev, &d);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_device_draw: %s: %s\n", tlod_result_string(r), tlod_context_last_error(gs->ctx));
    return false;
  }
  gl_read_rgba(W, H, rgba);
  return true;
}

/* Largest difference of the pixel's rgb from want (0..255). */
static int rgb_error(const uint8_t* px, const double want[3]) {
  int e = 0;
  for (int c = 0; c < 3; c++) {
    int d = abs((int)px[c] - (int)lround(want[c]));
    e = d > e ? d : e;
  }
  return e;
}

/* ---- (a) fragment hook: UVs as colour ------------------------------------ */

static const char* const k_uv_hook = "vec4 tlod_shade(tlod_fragment f) {\n"
                                     "  return vec4(f.attributes[0].xy, 0.0, 1.0);\n"
                                     "}\n";

/* Worst error (in 1/255) of the hook's UV colour over the quad's pixels. */
static void check_uv_quad(gl_session* gs, uint8_t* rgba) {
  grid_mesh g;
  grid_make(&g);
  object o;
  CHECK(object_make(&o, gs, &g.desc, TLOD_SURFACE_FLAT));
  tlod_draw_item item = {0};
  CHECK(draw_scene(gs, &o, &item, 1, rgba));
  int worst = 0;
  uint32_t checked = 0;
  for (uint32_t py = 0; py < H; py++)
    for (uint32_t px = 0; px < W; px++) {
      double x, y;
      pixel_world(px, py, &x, &y);
      if (fabs(x) > 0.98 || fabs(y) > 0.98) continue;
      const double want[3] = {255.0 * (x + 1.0) * 0.5, 255.0 * (1.0 - y) * 0.5, 0.0};
      int e = rgb_error(rgba + 4 * ((size_t)py * W + px), want);
      worst = e > worst ? e : worst;
      checked++;
    }
  printf("  uv hook, flat quad: %u pixels, worst UV error %d / 255\n", checked, worst);
  CHECK_MSG(checked > 8000 && worst <= 2, "UV colour off by %d / 255 (of %u pixels)", worst, checked);
  object_free(&o);
}

/* The lat-long sphere: u = atan2(y, x) / 2 pi, v = polar angle / pi at the
 * hit point of the pixel's ray with the unit sphere. */
static void check_uv_sphere(gl_session* gs, uint8_t* rgba) {
  uv_sphere us;
  CHECK(uv_sphere_make(&us, 16, 32));
  object o;
  CHECK(object_make(&o, gs, &us.desc, TLOD_SURFACE_PHONG));
  tlod_draw_item item = {0};
  CHECK(draw_scene(gs, &o, &item, 1, rgba));
  CHECK_MSG(item.draw_list->strip_count > 0 || item.draw_list->level_histogram[0] == 0, "no refinement");
  double worst = 0.0;
  uint32_t checked = 0;
  for (uint32_t py = 0; py < H; py++)
    for (uint32_t px = 0; px < W; px++) {
      double x, y;
      pixel_world(px, py, &x, &y);
      double z2 = 1.0 - x * x - y * y;
      if (z2 < 0.3) continue; /* near the silhouette the patches and the sphere differ most */
      double z = sqrt(z2), u = atan2(y, x) / (2.0 * SHAPES_PI), v = acos(z) / SHAPES_PI;
      u = u < 0.0 ? u + 1.0 : u;
      if (u < 0.03 || u > 0.97) continue; /* the seam: either side is right */
      const uint8_t* p = rgba + 4 * ((size_t)py * W + px);
      double e = fmax(fabs(p[0] / 255.0 - u), fabs(p[1] / 255.0 - v));
      worst = e > worst ? e : worst;
      checked++;
    }
  printf("  uv hook, seam sphere: %u pixels, worst UV error %.4f (strips %u)\n", checked, worst,
         item.draw_list->strip_count);
  CHECK_MSG(checked > 3000 && worst < 0.04, "UV off by %.4f (of %u pixels)", worst, checked);
  object_free(&o);
  uv_sphere_free(&us);
}

/* ---- (a') attribute parity with the cpu tessellator ------------------------ */

/* The cpu mesh drawn with its first attribute's xy as colour (independent of
 * the backend: plain vertex attributes, GL's own interpolation). */
static const char* const k_uv_ref_vs = "#version 450 core\n"
                                       "layout(location = 0) in vec3 a_position;\n"
                                       "layout(location = 1) in vec4 a_uv;\n"
                                       "uniform mat4 u_mvp;\n"
                                       "out vec2 v_uv;\n"
                                       "void main() { v_uv = a_uv.xy; gl_Position = u_mvp * vec4(a_position, 1.0); }\n";
static const char* const k_uv_ref_fs = "#version 450 core\n"
                                       "in vec2 v_uv;\n"
                                       "out vec4 o_color;\n"
                                       "void main() { o_color = vec4(v_uv, 0.0, 1.0); }\n";

static bool draw_uv_reference(const tlod_cpu_mesh* m, const tlod_view_desc* v) {
  GLuint prog = gl_program(k_uv_ref_vs, k_uv_ref_fs), vao, buf[3];
  if (!prog) return false;
  glGenVertexArrays(1, &vao);
  glGenBuffers(3, buf);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)m->vertex_count * 12, m->positions, GL_STREAM_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, NULL);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, buf[1]);
  GLsizei stride = (GLsizei)(16 * m->attribute_count);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)m->vertex_count * stride, m->attributes, GL_STREAM_DRAW);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride, NULL);
  glEnableVertexAttribArray(1);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)m->triangle_count * 12, m->indices, GL_STREAM_DRAW);
  float mvp[16];
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      float sum = 0.0f;
      for (int k = 0; k < 4; k++)
        sum += v->proj[k * 4 + r] * v->view[c * 4 + k];
      mvp[c * 4 + r] = sum;
    }
  glUseProgram(prog);
  glUniformMatrix4fv(glGetUniformLocation(prog, "u_mvp"), 1, GL_FALSE, mvp);
  glDrawElements(GL_TRIANGLES, (GLsizei)(3 * m->triangle_count), GL_UNSIGNED_INT, NULL);
  glUseProgram(0);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(3, buf);
  glDeleteProgram(prog);
  return glGetError() == GL_NO_ERROR;
}

/* The seam sphere at mixed levels, seen across its seam: the backend's UV
 * image (hook) against the cpu tessellation's (attributes per output
 * vertex, strips taking side a's): on pixels both cover, the UV colours
 * agree within 2 / 255 on all but 0.1% of them (u away from 0 and 1, where
 * a pixel at the seam may take either side). */
static void check_uv_parity(gl_session* gs, uint8_t* rgba) {
  uv_sphere us;
  uint8_t* ref = malloc(4 * W * H);
  CHECK(uv_sphere_make(&us, 12, 24) && ref);
  object o;
  CHECK(object_make(&o, gs, &us.desc, TLOD_SURFACE_PN));
  camera cam = camera_look(2.2, 0.4, 1.1, 0, 0, 0, 50, W, H); /* the seam (+x) in view, levels mixed */
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&o.fx, o.sched, &v, 0.0f);
  CHECK(dl);
  tlod_platform_bind(gs->platform);
  clear_frame(W, H);
  one_draw d;
  one_draw_make(&d, o.fx.ds, dl, &v);
  CHECK(tlod_device_draw(gs->dev, &d.desc) == TLOD_SUCCESS);
  gl_read_rgba(W, H, rgba);
  tlod_cpu_mesh* m = realise(&o.fx, dl);
  CHECK(m && m->attribute_count == 1);
  clear_frame(W, H);
  CHECK(draw_uv_reference(m, &v));
  gl_read_rgba(W, H, ref);
  uint32_t both = 0, close = 0;
  for (uint32_t i = 0; i < W * H; i++) {
    const uint8_t *a = rgba + 4 * i, *b = ref + 4 * i;
    if (is_background(a) || is_background(b) || a[0] < 8 || a[0] > 247 || b[0] < 8 || b[0] > 247) continue;
    both++;
    close += abs(a[0] - b[0]) <= 2 && abs(a[1] - b[1]) <= 2;
  }
  printf("  uv parity with the cpu tessellator (%u strips): %u of %u pixels within 2 / 255\n", dl->strip_count, close,
         both);
  CHECK_MSG(dl->strip_count > 0, "no strips: the parity does not reach them");
  /* measured: 0 differ; strips reading b's points in b's direction (a wrong
   * edge parameter) make 30 of 8450 differ: strips are a thin share */
  CHECK_MSG(both > 5000 && (both - close) * 1000 <= both, "%u of %u pixels differ", both - close, both);
  tlod_cpu_mesh_destroy(gs->ctx, m);
  object_free(&o);
  free(ref);
  uv_sphere_free(&us);
}

TEST(test_fragment_hook_uv) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, 5, "gl_material_hook", (tlod_device_gl_desc){.fragment_hook = k_uv_hook}),
            "no GL context or device (see above)");
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  CALL(check_uv_quad(&gs, rgba));
  CALL(check_uv_sphere(&gs, rgba));
  CALL(check_uv_parity(&gs, rgba));
  free(rgba);
  gl_session_close(&gs);
}

/* A hook that does not compile: TLOD_ERROR_BACKEND, the log naming the
 * hook's line, no device. */
TEST(test_fragment_hook_error) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, 5, "gl_material_bad", (tlod_device_gl_desc){0}), "no GL context");
  const char* bad = "vec4 tlod_shade(tlod_fragment f) {\n"
                    "  vec4 c = f.base_color;\n"
                    "  return c * no_such_variable;\n"
                    "}\n";
  tlod_device* dev = (tlod_device*)(uintptr_t)1;
  tlod_result r = tlod_device_create(
      gs.ctx, &(tlod_device_desc){.backend = "gl", .patterns = gs.pat, .gl = {.fragment_hook = bad}}, &dev);
  const char* e = tlod_context_last_error(gs.ctx);
  printf("  bad hook: %s\n", e);
  CHECK_MSG(r == TLOD_ERROR_BACKEND && dev == NULL, "%s", tlod_result_string(r));
  CHECK_MSG(strstr(e, "fragment_hook:3") || strstr(e, "fragment_hook(3)"), "the error names no hook line: %s", e);
  CHECK(strstr(e, "no_such_variable"));
  gl_session_close(&gs);
}

/* ---- (b) textures ------------------------------------------------------------ */

static const uint8_t k_checker[16] = {200, 40, 40,  255, 40,  200, 40, 255,  /* top row: left, right */
                                      40,  40, 200, 255, 200, 200, 40, 255}; /* bottom row */

static double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

/* Each quadrant's centre shows its texel (white item, Lambert 1). */
static void check_quadrants(const uint8_t* rgba, bool srgb, const char* what) {
  static const double centres[4][2] = {{-0.5, 0.5}, {0.5, 0.5}, {-0.5, -0.5}, {0.5, -0.5}}; /* TL TR BL BR */
  int worst = 0;
  for (int q = 0; q < 4; q++) {
    double want[3];
    for (int c = 0; c < 3; c++) {
      double t = k_checker[4 * q + c] / 255.0;
      want[c] = 255.0 * (srgb ? srgb_to_linear(t) : t);
    }
    const uint8_t* p = pixel_at(rgba, centres[q][0], centres[q][1]);
    int e = rgb_error(p, want);
    if (e > 2)
      fprintf(stderr, "  %s quadrant %d: (%u, %u, %u), want (%.0f, %.0f, %.0f)\n", what, q, p[0], p[1], p[2], want[0],
              want[1], want[2]);
    worst = e > worst ? e : worst;
  }
  printf("  %s texture: worst quadrant error %d / 255\n", what, worst);
  CHECK_MSG(worst <= 2, "%s texture: quadrant colours off by %d / 255", what, worst);
}

TEST(test_texture) {
  gl_session gs;
  uint8_t* rgba = NULL;
  grid_mesh g;
  CALL(material_open(&gs, "gl_material_tex", &rgba, &g));
  object o;
  CHECK(object_make(&o, &gs, &g.desc, TLOD_SURFACE_FLAT));
  for (int s = 0; s < 2; s++) {
    tlod_device_texture* tex = NULL;
    tlod_texture_desc td = {.width = 2,
                            .height = 2,
                            .rgba8 = k_checker,
                            .srgb = s == 1,
                            .mag_filter = TLOD_FILTER_NEAREST,
                            .wrap_s = TLOD_WRAP_CLAMP_TO_EDGE,
                            .wrap_t = TLOD_WRAP_CLAMP_TO_EDGE,
                            .label = "checker"};
    tlod_result r = tlod_device_create_texture(gs.dev, &td, &tex);
    CHECK_MSG(r == TLOD_SUCCESS, "%s: %s", tlod_result_string(r), tlod_context_last_error(gs.ctx));
    tlod_draw_item item = {.base_color_texture = tex, .color = {1, 1, 1, 1}, .has_color = true};
    CHECK(draw_scene(&gs, &o, &item, 1, rgba));
    CALL(check_quadrants(rgba, s == 1, s ? "sRGB" : "RGBA8"));
    if (s == 0) tlod_device_destroy_texture(gs.dev, tex); /* the sRGB one is left to tlod_device_destroy */
  }
  CHECK(tlod_device_query_stats(gs.dev).textures_live == 1);
  object_free(&o);
  free(rgba);
  gl_session_close(&gs);
}

/* An untextured item draws with programs that carry no texture coordinates
 * or fetch (linked at creation); the first textured item links its own,
 * once. Both give the same pixels where the texture is white (1x1). */
TEST(test_plain_programs) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, 5, "gl_material_plain", (tlod_device_gl_desc){0}), "no GL context");
  uint8_t *plain = malloc(4 * W * H), *full = malloc(4 * W * H);
  CHECK(plain && full);
  shape sph = shape_icosphere(2);
  tlod_mesh_desc md = shape_mesh_desc(&sph);
  float* uv = calloc(2u * md.vertex_count, sizeof(float)); /* a texture to sample, at (0, 0) */
  CHECK(uv);
  tlod_attribute_desc attr = {.data = uv, .components = 2, .name = "TEXCOORD_0"};
  md.attributes = &attr, md.attribute_count = 1;
  object o;
  CHECK(object_make(&o, &gs, &md, TLOD_SURFACE_PHONG));
  static const uint8_t white[4] = {255, 255, 255, 255};
  tlod_device_texture* tex = NULL;
  CHECK(tlod_device_create_texture(gs.dev, &(tlod_texture_desc){.width = 1, .height = 1, .rgba8 = white}, &tex) ==
        TLOD_SUCCESS);
  const uint32_t links = tlod_device_query_stats(gs.dev).gl.program_links;
  tlod_draw_item item = {.color = {0.9f, 0.6f, 0.3f, 1}, .has_color = true};
  CHECK(draw_scene(&gs, &o, &item, 1, plain));
  CHECK_MSG(tlod_device_query_stats(gs.dev).gl.program_links == links, "an untextured item linked programs");
  item.base_color_texture = tex;
  for (int k = 0; k < 2; k++) {
    CHECK(draw_scene(&gs, &o, &item, 1, full));
    uint32_t more = tlod_device_query_stats(gs.dev).gl.program_links - links;
    CHECK_MSG(more == 2, "textured draw %d: %u links in all (pattern + strip of phong, once: 2)", k, more);
  }
  size_t differ = 0, covered = 0;
  for (size_t i = 0; i < 4u * W * H; i += 4) {
    differ += memcmp(plain + i, full + i, 4) != 0;
    covered += !is_background(plain + i);
  }
  printf("  plain against white-textured: %zu of %zu pixels differ (%zu covered)\n", differ, (size_t)W * H, covered);
  CHECK_MSG(differ == 0, "%zu pixels differ between the plain and the textured programs", differ);
  CHECK_MSG(covered > (size_t)W * H / 20, "the sphere covers %zu pixels only", covered);
  tlod_device_destroy_texture(gs.dev, tex);
  object_free(&o);
  shape_free(&sph);
  free(uv);
  free(plain);
  free(full);
  gl_session_close(&gs);
}

/* ---- (c) several items ------------------------------------------------------- */

TEST(test_items_colours_and_models) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, W, H, 5, "gl_material_items", (tlod_device_gl_desc){0}), "no GL context");
  uint8_t* rgba = malloc(4 * W * H);
  CHECK(rgba);
  shape sph = shape_icosphere(2);
  tlod_mesh_desc md = shape_mesh_desc(&sph);
  enum { N = 3 };
  static const float colours[N][4] = {{0.9f, 0.2f, 0.1f, 1}, {0.1f, 0.8f, 0.3f, 1}, {0.9f, 0.9f, 0.2f, 1}};
  static const float at[N][2] = {{-0.7f, 0.1f}, {0.1f, 0.6f}, {0.6f, -0.5f}};
  object objs[N];
  tlod_draw_item items[N];
  for (int k = 0; k < N; k++) {
    CHECK(object_make(&objs[k], &gs, &md, TLOD_SURFACE_PHONG));
    items[k] = (tlod_draw_item){.has_model = true, .has_color = true};
    memcpy(items[k].color, colours[k], sizeof colours[k]);
    place(items[k].model, 0.3f, at[k][0], at[k][1], 0.0f);
  }
  CHECK(draw_scene(&gs, objs, items, N, rgba));
  int worst = 0;
  for (int k = 0; k < N; k++) {
    const double want[3] = {255.0 * colours[k][0], 255.0 * colours[k][1], 255.0 * colours[k][2]};
    const uint8_t* p = pixel_at(rgba, at[k][0], at[k][1]);
    int e = rgb_error(p, want);
    printf("  item %d at (%.1f, %.1f): (%u, %u, %u), want (%.0f, %.0f, %.0f)\n", k, at[k][0], at[k][1], p[0], p[1],
           p[2], want[0], want[1], want[2]);
    worst = e > worst ? e : worst;
  }
  CHECK_MSG(worst <= 3, "item colours off by %d / 255", worst);
  CHECK(is_background(pixel_at(rgba, -0.7, -0.8))); /* between the items: nothing */
  for (int k = 0; k < N; k++)
    object_free(&objs[k]);
  shape_free(&sph);
  free(rgba);
  gl_session_close(&gs);
}

/* ---- (d) mask, blend, culling, two sides --------------------------------------- */

/* Alpha 0 on the left texel column, 1 on the right. */
static const uint8_t k_half_alpha[16] = {255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255};

static void check_mask(gl_session* gs, object* o, uint8_t* rgba) {
  tlod_device_texture* tex = NULL;
  tlod_texture_desc td = {.width = 2, .height = 2, .rgba8 = k_half_alpha, .mag_filter = TLOD_FILTER_NEAREST};
  CHECK(tlod_device_create_texture(gs->dev, &td, &tex) == TLOD_SUCCESS);
  tlod_draw_item item = {.base_color_texture = tex, .blend = TLOD_BLEND_MASK, .color = {1, 0, 0, 1}, .has_color = true};
  uint32_t links = tlod_device_query_stats(gs->dev).gl.program_links;
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  /* the first MASK item of a type links that type's MASK programs, once */
  uint32_t mask_links = tlod_device_query_stats(gs->dev).gl.program_links - links;
  CHECK_MSG(mask_links == 2, "the first MASK draw linked %u programs (pattern + strip: 2)", mask_links);
  const uint8_t *left = pixel_at(rgba, -0.5, 0.2), *right = pixel_at(rgba, 0.5, 0.2);
  printf("  MASK: left (alpha 0) (%u, %u, %u), right (alpha 1) (%u, %u, %u)\n", left[0], left[1], left[2], right[0],
         right[1], right[2]);
  CHECK_MSG(is_background(left), "MASK drew alpha 0");
  CHECK_MSG(right[0] >= 250 && right[1] <= 2, "MASK did not draw alpha 1");
  /* the item's alpha against the cutoff: 0.3 < 0.5 discarded, 0.3 >= 0.2 drawn */
  item = (tlod_draw_item){.blend = TLOD_BLEND_MASK, .color = {1, 0, 0, 0.3f}, .has_color = true};
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  CHECK_MSG(is_background(pixel_at(rgba, 0, 0)), "MASK drew alpha 0.3 under the default cutoff 0.5");
  item.has_alpha_cutoff = true, item.alpha_cutoff = 0.2f;
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  CHECK_MSG(pixel_at(rgba, 0, 0)[0] >= 250, "MASK did not draw alpha 0.3 over the cutoff 0.2");
  CHECK(tlod_device_query_stats(gs->dev).gl.program_links == links + 2);
  tlod_device_destroy_texture(gs->dev, tex);
}

/* out = a over b (straight alpha a_alpha). */
static void over(const double a[3], double alpha, const double b[3], double out[3]) {
  for (int c = 0; c < 3; c++)
    out[c] = a[c] * alpha + b[c] * (1.0 - alpha);
}

static void check_blend_order(gl_session* gs, object* objs, uint8_t* rgba) {
  /* a blended red quad in front (z 0.5), listed before an opaque green one behind it (z -0.5) */
  tlod_draw_item items[2] = {
      {.blend = TLOD_BLEND_BLEND, .color = {1, 0, 0, 0.5f}, .has_color = true, .has_model = true},
      {.color = {0, 1, 0, 1}, .has_color = true, .has_model = true}};
  place(items[0].model, 1.0f, 0, 0, 0.5f);
  place(items[1].model, 1.0f, 0, 0, -0.5f);
  CHECK(draw_scene(gs, objs, items, 2, rgba));
  double red[3] = {255, 0, 0}, green[3] = {0, 255, 0}, blue[3] = {0, 0, 255}, want[3], mid[3];
  over(red, 0.5, green, want);
  const uint8_t* p = pixel_at(rgba, 0.1, 0.1);
  printf("  BLEND before opaque in the list: (%u, %u, %u), want (%.0f, %.0f, %.0f)\n", p[0], p[1], p[2], want[0],
         want[1], want[2]);
  CHECK_MSG(rgb_error(p, want) <= 2, "the blended item was not drawn over the opaque one");
  /* two blended quads, the near one (red) listed first: farthest (green) first */
  items[1].blend = TLOD_BLEND_BLEND;
  items[1].color[3] = 0.5f;
  CHECK(draw_scene(gs, objs, items, 2, rgba));
  over(green, 0.5, blue, mid);
  over(red, 0.5, mid, want);
  p = pixel_at(rgba, 0.1, 0.1);
  printf("  two BLEND items, near first in the list: (%u, %u, %u), want (%.0f, %.0f, %.0f)\n", p[0], p[1], p[2],
         want[0], want[1], want[2]);
  CHECK_MSG(rgb_error(p, want) <= 2, "blended items not drawn farthest first");
}

/* The quad turned about y (facing -z): culled with cull_back_faces; both
 * sided, its back face is lit with the flipped normal (towards +z). */
static void check_sides(gl_session* gs, object* o, uint8_t* rgba) {
  tlod_draw_item item = {.color = {0.2f, 0.6f, 1.0f, 1}, .has_color = true, .has_model = true, .cull_back_faces = true};
  place(item.model, 1.0f, 0, 0, 0);
  item.model[0] = -1.0f, item.model[10] = -1.0f;
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  CHECK_MSG(is_background(pixel_at(rgba, 0.2, 0.3)), "cull_back_faces drew the back face");
  item.cull_back_faces = false;
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  const double want[3] = {0.2 * 255, 0.6 * 255, 255};
  const uint8_t* p = pixel_at(rgba, 0.2, 0.3);
  printf("  back face, both sides: (%u, %u, %u), want (%.0f, %.0f, %.0f) (unflipped: 0.15 x that)\n", p[0], p[1], p[2],
         want[0], want[1], want[2]);
  CHECK_MSG(rgb_error(p, want) <= 2, "the back face is not lit with the flipped normal");
  /* and the front face is drawn with culling on */
  item.cull_back_faces = true;
  item.model[0] = 1.0f, item.model[10] = 1.0f;
  CHECK(draw_scene(gs, o, &item, 1, rgba));
  CHECK_MSG(rgb_error(pixel_at(rgba, 0.2, 0.3), want) <= 2, "cull_back_faces culled the front face");
}

TEST(test_mask_blend_cull) {
  gl_session gs;
  uint8_t* rgba = NULL;
  grid_mesh g;
  CALL(material_open(&gs, "gl_material_alpha", &rgba, &g));
  object objs[2];
  CHECK(object_make(&objs[0], &gs, &g.desc, TLOD_SURFACE_FLAT));
  CHECK(object_make(&objs[1], &gs, &g.desc, TLOD_SURFACE_FLAT));
  CALL(check_mask(&gs, &objs[0], rgba));
  CALL(check_blend_order(&gs, objs, rgba));
  CALL(check_sides(&gs, &objs[0], rgba));
  object_free(&objs[0]);
  object_free(&objs[1]);
  free(rgba);
  gl_session_close(&gs);
}

int main(void) {
  RUN(test_fragment_hook_uv);
  RUN(test_fragment_hook_error);
  RUN(test_texture);
  RUN(test_plain_programs);
  RUN(test_items_colours_and_models);
  RUN(test_mask_blend_cull);
  GL_TEST_END();
}
