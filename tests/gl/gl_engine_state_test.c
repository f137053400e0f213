/*
 * gl_engine_state_test.c -- tlod_device_draw leaves an engine's GL state
 * as it found it and draws into the engine's framebuffer (owned by the GL
 * tests). Public API only.
 *
 * The test plays the engine: its own FBO (not the platform's), program,
 * VAO with its own element buffer, array / element / shader-storage /
 * uniform / draw-indirect buffers, SSBOs on binding points 0-4 (two as
 * ranges), a UBO on binding point 0, blend on with a specific function and
 * equation (MAX on alpha), front face CW, a texture and a sampler of its own
 * on unit 0 (the device's) with unit 3 active,
 * depth test GREATER with the mask off, polygon mode LINE, culling of FRONT
 * faces, polygon offset fill (1.5, 2.5), an odd viewport, a scissor box, a
 * stencil setup. It draws a triangle of its own, then calls
 * tlod_device_draw (shaded, then LEVELS + wireframe, then a BLEND item
 * with cull_back_faces) and checks:
 *   - every state in tesslod/gl.h's GL STATE list is exactly as it was
 *     (glGetIntegerv & co.), and the states the backend must not touch
 *     (framebuffer bindings, scissor, stencil, colour mask) too;
 *   - no GL error is pending;
 *   - tesslod drew into the test's FBO (pixels inside its own coverage,
 *     taken from a separate render into the platform's FBO, changed);
 *   - the triangle's pixels are untouched wherever tesslod did not draw
 *     (outside its coverage grown by one pixel).
 * And, separately, that a draw inside the engine's own GL_TIME_ELAPSED and
 * GL_PRIMITIVES_GENERATED queries raises no GL error and leaves them active.
 */
#include "gl_test.h"

#define W 192
#define H 192

/* Every state the test sets and checks, as integers. */
typedef struct gl_state {
  GLint program, vao, array_buffer, element_buffer, ssbo_generic, ubo_generic, indirect_buffer;
  GLint ssbo[5];
  GLint64 ssbo_start[5], ssbo_size[5];
  GLint ubo0;
  GLint polygon_mode[2];
  GLboolean cull;
  GLint cull_mode;
  GLboolean depth_test;
  GLint depth_func;
  GLboolean depth_mask;
  GLboolean blend;
  GLint blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha, blend_eq_rgb, blend_eq_alpha;
  GLboolean offset_fill;
  GLfloat offset_factor, offset_units;
  GLint viewport[4];
  GLint draw_fbo, read_fbo;
  GLboolean scissor;
  GLint scissor_box[4];
  GLboolean stencil;
  GLint stencil_func, stencil_ref, stencil_writemask;
  GLboolean color_mask[4];
  GLint front_face, active_texture;
  GLint texture_unit0, sampler_unit0; /* GL_TEXTURE_BINDING_2D, GL_SAMPLER_BINDING of unit 0 */
} gl_state;

static gl_state capture(void) {
  gl_state s;
  memset(&s, 0, sizeof s);
  glGetIntegerv(GL_CURRENT_PROGRAM, &s.program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s.array_buffer);
  glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &s.element_buffer);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.ssbo_generic);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.ubo_generic);
  glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &s.indirect_buffer);
  for (GLuint i = 0; i < 5; ++i) {
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &s.ssbo[i]);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &s.ssbo_start[i]);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &s.ssbo_size[i]);
  }
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &s.ubo0);
  glGetIntegerv(GL_POLYGON_MODE, s.polygon_mode);
  s.cull = glIsEnabled(GL_CULL_FACE);
  glGetIntegerv(GL_CULL_FACE_MODE, &s.cull_mode);
  s.depth_test = glIsEnabled(GL_DEPTH_TEST);
  glGetIntegerv(GL_DEPTH_FUNC, &s.depth_func);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &s.depth_mask);
  s.blend = glIsEnabled(GL_BLEND);
  glGetIntegerv(GL_BLEND_SRC_RGB, &s.blend_src_rgb);
  glGetIntegerv(GL_BLEND_DST_RGB, &s.blend_dst_rgb);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &s.blend_src_alpha);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &s.blend_dst_alpha);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &s.blend_eq_rgb);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s.blend_eq_alpha);
  s.offset_fill = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &s.offset_factor);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &s.offset_units);
  glGetIntegerv(GL_VIEWPORT, s.viewport);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_fbo);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.read_fbo);
  s.scissor = glIsEnabled(GL_SCISSOR_TEST);
  glGetIntegerv(GL_SCISSOR_BOX, s.scissor_box);
  s.stencil = glIsEnabled(GL_STENCIL_TEST);
  glGetIntegerv(GL_STENCIL_FUNC, &s.stencil_func);
  glGetIntegerv(GL_STENCIL_REF, &s.stencil_ref);
  glGetIntegerv(GL_STENCIL_WRITEMASK, &s.stencil_writemask);
  glGetBooleanv(GL_COLOR_WRITEMASK, s.color_mask);
  glGetIntegerv(GL_FRONT_FACE, &s.front_face);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &s.active_texture);
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &s.texture_unit0);
  glGetIntegerv(GL_SAMPLER_BINDING, &s.sampler_unit0);
  glActiveTexture((GLenum)s.active_texture);
  return s;
}

/* Compares field by field; prints every difference; returns their count. */
static int compare_state(const gl_state* want, const gl_state* got, const char* when) {
  int diffs = 0;
#define SAME_INT(field, name)                                                                                          \
  do {                                                                                                                 \
    if ((long long)want->field != (long long)got->field) {                                                             \
      fprintf(stderr, "  %s: %s changed: was %lld (0x%llX), now %lld (0x%llX)\n", when, name, (long long)want->field,  \
              (unsigned long long)want->field, (long long)got->field, (unsigned long long)got->field);                 \
      diffs++;                                                                                                         \
    }                                                                                                                  \
  } while (0)
#define SAME_FLOAT(field, name)                                                                                        \
  do {                                                                                                                 \
    if (want->field != got->field) {                                                                                   \
      fprintf(stderr, "  %s: %s changed: was %g, now %g\n", when, name, (double)want->field, (double)got->field);      \
      diffs++;                                                                                                         \
    }                                                                                                                  \
  } while (0)
  SAME_INT(program, "GL_CURRENT_PROGRAM");
  SAME_INT(vao, "GL_VERTEX_ARRAY_BINDING");
  SAME_INT(array_buffer, "GL_ARRAY_BUFFER_BINDING");
  SAME_INT(element_buffer, "GL_ELEMENT_ARRAY_BUFFER_BINDING");
  SAME_INT(ssbo_generic, "GL_SHADER_STORAGE_BUFFER_BINDING");
  SAME_INT(ubo_generic, "GL_UNIFORM_BUFFER_BINDING");
  SAME_INT(indirect_buffer, "GL_DRAW_INDIRECT_BUFFER_BINDING");
  static const char* const ssbo_names[5] = {"SSBO binding point 0", "SSBO binding point 1", "SSBO binding point 2",
                                            "SSBO binding point 3", "SSBO binding point 4"};
  for (int i = 0; i < 5; ++i) {
    SAME_INT(ssbo[i], ssbo_names[i]);
    SAME_INT(ssbo_start[i], "GL_SHADER_STORAGE_BUFFER_START");
    SAME_INT(ssbo_size[i], "GL_SHADER_STORAGE_BUFFER_SIZE");
  }
  SAME_INT(ubo0, "uniform buffer binding point 0");
  SAME_INT(polygon_mode[0], "GL_POLYGON_MODE");
  SAME_INT(cull, "GL_CULL_FACE enable");
  SAME_INT(cull_mode, "GL_CULL_FACE_MODE");
  SAME_INT(depth_test, "GL_DEPTH_TEST enable");
  SAME_INT(depth_func, "GL_DEPTH_FUNC");
  SAME_INT(depth_mask, "GL_DEPTH_WRITEMASK");
  SAME_INT(blend, "GL_BLEND enable");
  SAME_INT(blend_src_rgb, "GL_BLEND_SRC_RGB");
  SAME_INT(blend_dst_rgb, "GL_BLEND_DST_RGB");
  SAME_INT(blend_src_alpha, "GL_BLEND_SRC_ALPHA");
  SAME_INT(blend_dst_alpha, "GL_BLEND_DST_ALPHA");
  SAME_INT(blend_eq_rgb, "GL_BLEND_EQUATION_RGB");
  SAME_INT(blend_eq_alpha, "GL_BLEND_EQUATION_ALPHA");
  SAME_INT(offset_fill, "GL_POLYGON_OFFSET_FILL enable");
  SAME_FLOAT(offset_factor, "GL_POLYGON_OFFSET_FACTOR");
  SAME_FLOAT(offset_units, "GL_POLYGON_OFFSET_UNITS");
  static const char* const vp_names[4] = {"viewport x", "viewport y", "viewport width", "viewport height"};
  for (int i = 0; i < 4; ++i)
    SAME_INT(viewport[i], vp_names[i]);
  SAME_INT(draw_fbo, "GL_DRAW_FRAMEBUFFER_BINDING");
  SAME_INT(read_fbo, "GL_READ_FRAMEBUFFER_BINDING");
  SAME_INT(scissor, "GL_SCISSOR_TEST enable");
  for (int i = 0; i < 4; ++i)
    SAME_INT(scissor_box[i], "GL_SCISSOR_BOX");
  SAME_INT(stencil, "GL_STENCIL_TEST enable");
  SAME_INT(stencil_func, "GL_STENCIL_FUNC");
  SAME_INT(stencil_ref, "GL_STENCIL_REF");
  SAME_INT(stencil_writemask, "GL_STENCIL_WRITEMASK");
  for (int i = 0; i < 4; ++i)
    SAME_INT(color_mask[i], "GL_COLOR_WRITEMASK");
  SAME_INT(front_face, "GL_FRONT_FACE");
  SAME_INT(active_texture, "GL_ACTIVE_TEXTURE");
  SAME_INT(texture_unit0, "GL_TEXTURE_BINDING_2D of unit 0");
  SAME_INT(sampler_unit0, "GL_SAMPLER_BINDING of unit 0");
#undef SAME_INT
#undef SAME_FLOAT
  return diffs;
}

/* The engine's own triangle: flat orange, left part of the image, far back
 * (depth 0.995): where the sphere overlaps it, tesslod draws over it. */
static const char* const tri_vs = "#version 450 core\n"
                                  "layout(location = 0) in vec2 a_position;\n"
                                  "void main() { gl_Position = vec4(a_position, 0.99, 1.0); }\n";
static const char* const tri_fs = "#version 450 core\n"
                                  "layout(std140, binding = 0) uniform engine_block { vec4 color; };\n"
                                  "out vec4 o_color;\n"
                                  "void main() { o_color = color; }\n";

TEST(test_engine_state) {
  gl_session gs;
  shape sph;
  fixture fx;
  tlod_scheduler* sch;
  CALL(sphere_scene_open(&gs, &sph, &fx, &sch, W, H, "engine_state", TLOD_SURFACE_PN));
  tlod_result r;
  /* the sphere sits right of centre; the engine's triangle covers the left */
  camera cam = camera_look(0.9, -3.2, 0.6, -0.7, 0, 0, 50, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
  CHECK(dl);
  one_draw frame;
  one_draw_make(&frame, fx.ds, dl, &v);

  /* tesslod's coverage alone, in the gs.platform's FBO */
  uint8_t* alone = malloc(4 * W * H);
  uint8_t* before = malloc(4 * W * H);
  uint8_t* after = malloc(4 * W * H);
  CHECK(alone && before && after);
  tlod_platform_bind(gs.platform);
  clear_frame(W, H);
  CHECK(tlod_device_draw(gs.dev, &frame.desc) == TLOD_SUCCESS);
  gl_read_rgba(W, H, alone);

  /* ---- the engine ---- */
  gl_target target;
  CHECK_MSG(gl_target_make(&target, W, H), "engine FBO incomplete");
  GLuint program = gl_program(tri_vs, tri_fs);
  CHECK(program);
  GLuint vao, buffers[11], engine_texture, engine_sampler;
  glGenVertexArrays(1, &vao);
  glGenBuffers(11, buffers);
  GLuint vbo = buffers[0], ebo = buffers[1], ubo = buffers[2], indirect = buffers[3], loose_array = buffers[4];
  GLuint ssbo[5] = {buffers[5], buffers[6], buffers[7], buffers[8], buffers[10]}, ssbo_generic = buffers[9];
  const float tri[6] = {-1.0f, -0.9f, 0.1f, -0.9f, -1.0f, 0.9f};
  const uint32_t idx[3] = {0, 1, 2};
  const float orange[4] = {1.0f, 0.5f, 0.0f, 1.0f};
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof tri, tri, GL_STATIC_DRAW);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 8, NULL);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, ubo);
  glBufferData(GL_UNIFORM_BUFFER, sizeof orange, orange, GL_STATIC_DRAW);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo);
  for (int i = 0; i < 5; ++i) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo[i]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, 1024, NULL, GL_STATIC_DRAW);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo_generic);
  glBufferData(GL_SHADER_STORAGE_BUFFER, 64, NULL, GL_STATIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, ssbo[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, ssbo[1]);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, ssbo[2], 256, 512);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, ssbo[3]);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, ssbo[4], 512, 256);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo_generic);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, indirect);
  glBufferData(GL_DRAW_INDIRECT_BUFFER, 64, NULL, GL_STATIC_DRAW);

  /* the engine's frame: clear, its triangle (plain state) */
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  clear_frame(W, H);
  glUseProgram(program);
  glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, NULL);
  CHECK_MSG(glGetError() == GL_NO_ERROR, "the engine's own draw failed");
  gl_read_rgba(W, H, before);

  /* ... then its odd state, left as an engine might leave it */
  glBindBuffer(GL_ARRAY_BUFFER, loose_array); /* not the VAO's attribute buffer */
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
  glBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
  glFrontFace(GL_CW);
  /* a texture and a sampler of the engine's on unit 0 (the device's unit), another unit active */
  glGenTextures(1, &engine_texture);
  glGenSamplers(1, &engine_sampler);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, engine_texture);
  glBindSampler(0, engine_sampler);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.5f);
  glViewport(3, 5, 101, 77);
  glEnable(GL_SCISSOR_TEST); /* the whole image: must not clip tesslod */
  glScissor(0, 0, W, H);
  glEnable(GL_STENCIL_TEST); /* passes everywhere, writes nothing */
  glStencilFunc(GL_ALWAYS, 3, 0xFF);
  glStencilMask(0x00);
  glActiveTexture(GL_TEXTURE3);
  CHECK_MSG(glGetError() == GL_NO_ERROR, "setting the engine state failed");
  gl_state want = capture();
  CHECK(want.program == (GLint)program && want.vao == (GLint)vao && want.element_buffer == (GLint)ebo &&
        want.ssbo[2] == (GLint)ssbo[2] && want.ssbo_start[2] == 256 && want.ssbo_generic == (GLint)ssbo_generic &&
        want.texture_unit0 == (GLint)engine_texture && want.sampler_unit0 == (GLint)engine_sampler &&
        want.ssbo_start[4] == 512 && want.front_face == GL_CW && want.blend_eq_alpha == GL_MAX);

  /* tesslod draws into the engine's framebuffer, twice: shaded, then
   * LEVELS with the wireframe overlay */
  r = tlod_device_draw(gs.dev, &frame.desc);
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_draw: %s: %s", tlod_result_string(r), tlod_context_last_error(gs.ctx));
  GLenum gl_err = glGetError();
  gl_state got = capture();
  int diffs = compare_state(&want, &got, "after draw");
  CHECK_MSG(gl_err == GL_NO_ERROR, "tlod_device_draw left a GL error: %s (0x%04X)", gl_error_name(gl_err), gl_err);
  gl_read_rgba(W, H, after);
  frame.desc.debug = TLOD_DEBUG_LEVELS;
  frame.desc.wireframe = true;
  r = tlod_device_draw(gs.dev, &frame.desc);
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_draw (wireframe): %s: %s", tlod_result_string(r),
            tlod_context_last_error(gs.ctx));
  gl_err = glGetError();
  got = capture();
  diffs += compare_state(&want, &got, "after wireframe draw");
  CHECK_MSG(gl_err == GL_NO_ERROR, "tlod_device_draw (wireframe) left a GL error: %s (0x%04X)", gl_error_name(gl_err),
            gl_err);
  /* and a blended, back-face-culled item (the state of materials) */
  frame.desc.debug = TLOD_DEBUG_NONE;
  frame.desc.wireframe = false;
  frame.item.blend = TLOD_BLEND_BLEND;
  frame.item.cull_back_faces = true;
  r = tlod_device_draw(gs.dev, &frame.desc);
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_draw (blend): %s: %s", tlod_result_string(r),
            tlod_context_last_error(gs.ctx));
  gl_err = glGetError();
  got = capture();
  diffs += compare_state(&want, &got, "after blended draw");
  CHECK_MSG(gl_err == GL_NO_ERROR, "tlod_device_draw (blend) left a GL error: %s (0x%04X)", gl_error_name(gl_err),
            gl_err);
  printf("  %d state differences after 3 draws (%u triangles each)\n", diffs,
         (unsigned)(dl->pattern_triangles + dl->strip_triangles));
  CHECK_MSG(diffs == 0, "%d GL states changed by tlod_device_draw (see above)", diffs);

  /* pixels: the shaded draw's image ('after') against the coverage alone */
  uint32_t covered = 0, changed_inside = 0, triangle_px = 0, triangle_kept = 0, touched_outside = 0;
  int first_x = -1, first_y = -1;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      size_t i = (size_t)y * W + x;
      bool mine = !is_background(alone + 4 * i);
      bool near_mine = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = (int)x + dx, ny = (int)y + dy;
          if (nx >= 0 && ny >= 0 && nx < W && ny < H && !is_background(alone + 4 * ((size_t)ny * W + (size_t)nx)))
            near_mine = true;
        }
      bool changed = memcmp(before + 4 * i, after + 4 * i, 4) != 0;
      covered += mine;
      changed_inside += mine && changed;
      bool orange_px =
          before[4 * i] == 255 && before[4 * i + 1] >= 127 && before[4 * i + 1] <= 128 && before[4 * i + 2] == 0;
      if (!near_mine) {
        triangle_px += orange_px;
        triangle_kept += orange_px && !changed;
        if (changed && touched_outside++ == 0) first_x = (int)x, first_y = (int)y;
      }
    }
  printf("  tesslod covers %u pixels, changed %u of them in the engine FBO; engine triangle %u pixels outside that, "
         "%u kept; %u pixels changed elsewhere\n",
         covered, changed_inside, triangle_px, triangle_kept, touched_outside);
  CHECK_MSG(covered > 1000, "tesslod drew only %u pixels alone", covered);
  CHECK_MSG(changed_inside * 10 >= covered * 9, "tesslod changed only %u of its %u pixels in the engine FBO",
            changed_inside, covered);
  CHECK_MSG(triangle_px > 1000, "the engine triangle has only %u pixels", triangle_px);
  CHECK_MSG(triangle_kept == triangle_px, "%u of %u engine triangle pixels changed where tesslod did not draw",
            triangle_px - triangle_kept, triangle_px);
  CHECK_MSG(touched_outside == 0, "%u pixels changed outside tesslod's coverage, first at (%d, %d)", touched_outside,
            first_x, first_y);

  glBindVertexArray(0);
  glUseProgram(0);
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(11, buffers);
  glDeleteTextures(1, &engine_texture);
  glDeleteSamplers(1, &engine_sampler);
  glDeleteProgram(program);
  gl_target_free(&target);
  free(alone);
  free(before);
  free(after);
  sphere_scene_close(&gs, &sph, &fx, sch);
}

/* An engine that times its passes has its own GL_TIME_ELAPSED (and
 * GL_PRIMITIVES_GENERATED) query active around the middleware's draw
 * (docs/style.md item 12: per-pass timestamps). GL allows one active query per target:
 * tlod_device_draw must not begin another on the same target (that is
 * GL_INVALID_OPERATION), and the engine's queries must still end and
 * report. */
TEST(test_engine_queries_active) {
  gl_session gs;
  shape sph;
  fixture fx;
  tlod_scheduler* sch;
  CALL(sphere_scene_open(&gs, &sph, &fx, &sch, W, H, "engine_queries", TLOD_SURFACE_PHONG));
  tlod_result r;
  camera cam = camera_look(0.9, -3.2, 0.6, 0, 0, 0, 50, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
  CHECK(dl);
  one_draw frame;
  one_draw_make(&frame, fx.ds, dl, &v);
  tlod_platform_bind(gs.platform);
  clear_frame(W, H);
  while (glGetError() != GL_NO_ERROR) {
  }
  GLuint q[2];
  glGenQueries(2, q);
  int errors = 0;
  GLenum first_error = GL_NO_ERROR;
  for (int f = 0; f < 6; ++f) { /* the backend reads its queries a few frames late */
    glBeginQuery(GL_TIME_ELAPSED, q[0]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, q[1]);
    r = tlod_device_draw(gs.dev, &frame.desc);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR && errors++ == 0) first_error = e;
    GLint active_time = 0, active_prims = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &active_time);
    glGetQueryiv(GL_PRIMITIVES_GENERATED, GL_CURRENT_QUERY, &active_prims);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TIME_ELAPSED);
    e = glGetError();
    if (e != GL_NO_ERROR && errors++ == 0) first_error = e;
    if (r != TLOD_SUCCESS || active_time != (GLint)q[0] || active_prims != (GLint)q[1]) {
      fprintf(stderr,
              "  frame %d: draw %s, engine queries active after the draw: time %d (want %u), primitives %d "
              "(want %u)\n",
              f, tlod_result_string(r), active_time, q[0], active_prims, q[1]);
      errors++;
    }
  }
  GLuint64 ns = 0, prims = 0;
  glGetQueryObjectui64v(q[0], GL_QUERY_RESULT, &ns);
  glGetQueryObjectui64v(q[1], GL_QUERY_RESULT, &prims);
  printf("  6 frames inside the engine's queries: %d GL errors / lost queries (first %s); engine saw %.3f ms, %llu "
         "primitives (draw list %llu triangles)\n",
         errors, gl_error_name(first_error), (double)ns * 1e-6, (unsigned long long)prims,
         (unsigned long long)(dl->pattern_triangles + dl->strip_triangles));
  glDeleteQueries(2, q);
  uint64_t pattern_triangles = dl->pattern_triangles; /* dl dies with the scheduler */
  sphere_scene_close(&gs, &sph, &fx, sch);
  CHECK_MSG(errors == 0,
            "tlod_device_draw inside an engine's GL_TIME_ELAPSED / GL_PRIMITIVES_GENERATED queries: %d "
            "errors, first %s (0x%04X)",
            errors, gl_error_name(first_error), first_error);
  CHECK_MSG(prims >= pattern_triangles, "the engine's GL_PRIMITIVES_GENERATED saw %llu primitives",
            (unsigned long long)prims);
}

int main(void) {
  RUN(test_engine_state);
  RUN(test_engine_queries_active);
  GL_TEST_END();
}
