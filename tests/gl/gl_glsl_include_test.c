/*
 * gl_glsl_include_test.c -- the GLSL shipped for engines (docs/shaders.md:
 * layout.h, uniforms.glsl, common.glsl, attributes.glsl, then phong.glsl, pn.glsl,
 * flat.glsl or quadratic.glsl, installed under share/tesslod/glsl) compiles into an engine's
 * own vertex shader and evaluates patches as the library does (owned by
 * the GL tests). Public API only, plus the shader files of the source tree.
 *
 * The "engine" shader evaluates every patch of a UV seam sphere at two
 * interior parameters and one edge point from the patch records
 * (tlod_surface_patch_records, binding TLOD_GL_BINDING_PATCHES) and the
 * attributes (tlod_mesh_patch_attributes, TLOD_GL_BINDING_ATTRIBUTES),
 * captured by transform feedback; positions and normals are compared with
 * tlod_surface_eval(), the UV attribute with the barycentric blend of the
 * corners' UVs computed here, for Phong, PN, flat and quadratic surfaces
 * (the sphere has no nodes: its quadratic surface takes the Phong nodes).
 */
#include "gl_test.h"
#include "tesslod/gl.h"

#ifndef TLOD_GLSL_SOURCE_DIR
#error "TLOD_GLSL_SOURCE_DIR (tests/gl/CMakeLists.txt) names the shader directory"
#endif

#define NLAT 6
#define NLON 10
#define POINTS 3 /* per patch: two interior points, one edge point */

static const float k_params[POINTS][2] = {
    {0.3f, 0.25f}, {0.1f, 0.7f}, {0.375f, 0.0f}}; /* the last: on edge 2 (v = 0) */

static char* read_text(const char* name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", TLOD_GLSL_SOURCE_DIR, name);
  return test_read_file(path, NULL);
}

/* The engine's vertex stage: point k of patch p from gl_VertexID. Edge
 * points go through patch_edge_point with the grid parameter, like the
 * library's own patterns. */
static const char* const k_engine_main =
    "uniform vec2 u_params[3];\n"
    "out vec3 o_pos;\n"
    "out vec3 o_nrm;\n"
    "out vec4 o_uv;\n"
    "void main() {\n"
    "  uint p = uint(gl_VertexID) / 3u, k = uint(gl_VertexID) % 3u;\n"
    "  Patch P = patches[p];\n"
    "  vec2 uv = u_params[k];\n"
    "  vec4 attr[TLOD_SHADER_MAX_ATTRIBUTES];\n"
    "  if (k == 2u) {\n"
    "    // v = 0: edge 2 of a triangle, corner 2 to corner 0, u the end corner's weight\n"
    "    uint num = uint(uv.x * float(u_grid));\n"
    "    patch_edge_point(P, 2u, num, o_pos, o_nrm);\n"
    "    point_attributes(p, P, 6u, num, uv, attr);\n"
    "  } else {\n"
    "    interior_point(P, uv, o_pos, o_nrm);\n"
    "    point_attributes(p, P, 8u, 0u, uv, attr);\n"
    "  }\n"
    "  o_nrm = normalize(o_nrm);\n"
    "  o_uv = attr[0];\n"
    "}\n";

/* Compiles "#version 450 core" + TLOD_GLSL + the files + k_engine_main into a
 * transform feedback program; 0 with the log printed. */
static GLuint engine_program(const char* surface_file) {
  const char* files[5] = {"layout.h", "uniforms.glsl", "common.glsl", "attributes.glsl", surface_file};
  char* text[5] = {0};
  const char* src[7] = {"#version 450 core\n#define TLOD_GLSL 1\n"};
  for (int i = 0; i < 5; i++) {
    text[i] = read_text(files[i]);
    if (!text[i]) fprintf(stderr, "cannot read %s/%s\n", TLOD_GLSL_SOURCE_DIR, files[i]);
    src[1 + i] = text[i] ? text[i] : "";
  }
  src[6] = k_engine_main;
  GLuint sh = glCreateShader(GL_VERTEX_SHADER);
  glShaderSource(sh, 7, src, NULL);
  glCompileShader(sh);
  for (int i = 0; i < 5; i++)
    free(text[i]);
  if (!gl_status_ok(sh, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, "engine vertex shader")) return 0;
  GLuint prog = glCreateProgram();
  glAttachShader(prog, sh);
  const char* outs[3] = {"o_pos", "o_nrm", "o_uv"};
  glTransformFeedbackVaryings(prog, 3, outs, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(prog);
  glDeleteShader(sh);
  if (!gl_status_ok(prog, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, "engine program")) {
    glDeleteProgram(prog);
    return 0;
  }
  return prog;
}

/* Runs the engine program over every patch; out: 10 floats per point. */
static bool evaluate(GLuint prog, const fixture* fx, uint32_t patches, float* out) {
  tlod_patch_record* rec = malloc(sizeof *rec * patches);
  uint32_t count = tlod_mesh_attribute_count(fx->mesh);
  float(*attrs)[4] = malloc(sizeof(float[4]) * 4 * count * patches);
  if (!rec || !attrs || tlod_surface_patch_records(fx->surf, 0, patches, rec) != TLOD_SUCCESS ||
      tlod_mesh_patch_attributes(fx->mesh, 0, patches, attrs) != TLOD_SUCCESS)
    return free(rec), free(attrs), false;
  GLuint buf[3], vao;
  glGenBuffers(3, buf);
  glGenVertexArrays(1, &vao);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_GL_BINDING_PATCHES, buf[0]);
  glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(sizeof *rec * patches), rec, GL_STATIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_GL_BINDING_ATTRIBUTES, buf[1]);
  glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(sizeof(float[4]) * 4 * count * patches), attrs, GL_STATIC_DRAW);
  size_t bytes = sizeof(float) * 10 * POINTS * patches;
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buf[2]);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (GLsizeiptr)bytes, NULL, GL_STATIC_READ);
  glUseProgram(prog);
  glUniform1ui(glGetUniformLocation(prog, "u_grid"), 1u << 5);
  glUniform1ui(glGetUniformLocation(prog, "u_max_level"), 5u);
  glUniform1ui(glGetUniformLocation(prog, "u_attribute_count"), count);
  glUniform2fv(glGetUniformLocation(prog, "u_params"), POINTS, &k_params[0][0]);
  glBindVertexArray(vao);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, (GLsizei)(POINTS * patches));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, (GLsizeiptr)bytes, out);
  GLenum err = glGetError();
  glUseProgram(0);
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(3, buf);
  free(rec);
  free(attrs);
  if (err != GL_NO_ERROR) fprintf(stderr, "GL error %s\n", gl_error_name(err));
  return err == GL_NO_ERROR;
}

/* Worst differences of the engine's points from the library's, and of
 * its UVs from the corner blend. */
static void compare(const fixture* fx, uint32_t patches, const float* got, double* pos_err, double* nrm_err,
                    double* uv_err) {
  tlod_mesh_view mv = tlod_mesh_query_view(fx->mesh);
  *pos_err = *nrm_err = *uv_err = 0.0;
  for (uint32_t p = 0; p < patches; p++)
    for (uint32_t k = 0; k < POINTS; k++) {
      const float* g = got + 10 * (POINTS * p + k);
      float u = k_params[k][0], v = k_params[k][1];
      tlod_surface_point sp;
      if (tlod_surface_eval(fx->surf, p, u, v, &sp) != TLOD_SUCCESS) *pos_err = 1e9;
      const double w[3] = {u, v, 1.0 - u - v};
      for (int c = 0; c < 3; c++) {
        *pos_err = fmax(*pos_err, fabs(g[c] - sp.position[c]));
        *nrm_err = fmax(*nrm_err, fabs(g[3 + c] - sp.normal[c]));
      }
      for (int c = 0; c < 2; c++) {
        double want = 0.0;
        for (int i = 0; i < 3; i++)
          want += w[i] * mv.attributes[mv.faces[p][i] * mv.attribute_count][c];
        *uv_err = fmax(*uv_err, fabs(g[6 + c] - want));
      }
    }
}

TEST(test_engine_shader_evaluates_patches) {
  gl_session gs;
  CHECK_MSG(gl_session_open(&gs, 16, 16, 5, "gl_glsl_include", (tlod_device_gl_desc){0}), "no GL context");
  uv_sphere us;
  CHECK(uv_sphere_make(&us, NLAT, NLON));
  static const char* const files[4] = {"phong.glsl", "pn.glsl", "flat.glsl", "quadratic.glsl"};
  static const tlod_surface_type types[4] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN, TLOD_SURFACE_FLAT,
                                             TLOD_SURFACE_QUADRATIC};
  for (int t = 0; t < 4; t++) {
    fixture fx;
    CHECK(fixture_make_desc(&fx, gs.ctx, &us.desc, types[t], gs.pat, NULL));
    uint32_t patches = tlod_surface_patch_count(fx.surf);
    GLuint prog = engine_program(files[t]);
    CHECK_MSG(prog, "%s: the engine shader did not build (see above)", files[t]);
    float* got = calloc((size_t)10 * POINTS * patches, sizeof(float));
    CHECK(got);
    CHECK(evaluate(prog, &fx, patches, got));
    double pe, ne, ue;
    compare(&fx, patches, got, &pe, &ne, &ue);
    printf("  %-10s %u patches x %d points: position error %.2e, normal %.2e, uv %.2e\n", files[t], patches, POINTS, pe,
           ne, ue);
    CHECK_MSG(pe < 2e-5 && ne < 2e-4 && ue < 1e-6, "%s: the engine's evaluation differs from tlod_surface_eval",
              files[t]);
    free(got);
    glDeleteProgram(prog);
    fixture_free(&fx);
  }
  uv_sphere_free(&us);
  gl_session_close(&gs);
}

int main(void) {
  RUN(test_engine_shader_evaluates_patches);
  GL_TEST_END();
}
