/* tesslod::gl -- OpenGL 4.5 core backend: refinement patterns drawn
 * instanced, each vertex evaluating its patch in the vertex shader; strips
 * from the connection patterns; geomorphs; timer queries.
 *
 * This work is based on:
 *   T. Boubekeur, C. Schlick. Generic mesh refinement on GPU. Graphics
 *   Hardware 2005 (refinement patterns evaluated in the vertex shader);
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl_internal.h"
#include "surface_eval.h"

enum { QUERY_RING = 4 };

typedef struct gl_backend {
  tlod_context* ctx;
  char label[64];
  const tlod_surface* surface;
  const tlod_patterns* patterns;
  uint32_t lmax;
  GLuint prog_pattern, prog_strip;
  bool hardware;
  GLuint prog_tess[2]; /* hardware path: triangles, quads */
  GLuint vao_pattern, vao_strip;
  GLuint buf_patches, buf_pattern, buf_indices, buf_instances, buf_strips, buf_refs;
  uint32_t index_first[2][TLOD_MAX_LEVEL + 1], index_count[2][TLOD_MAX_LEVEL + 1], shape_base[2];
  GLuint queries[QUERY_RING];
  GLuint prim_queries[QUERY_RING];
  uint64_t frame;
  tlod_backend_timings timings;
  gl_instance* instances; /* staging, grown as needed */
  uint32_t instance_cap;
  gl_strip* strips;
  uint32_t strip_cap;
  uint32_t (*refs)[2];
  uint32_t ref_cap;
  uint32_t* instance_of; /* patch -> instance, this frame */
  uint32_t instance_of_cap;
} gl_backend;

static tlod_result check_context(tlod_context* ctx) {
  const char* version = (const char*)glGetString(GL_VERSION);
  if (!version)
    return _tlod_fail(ctx, TLOD_ERROR_BACKEND,
                      "gl backend: no current OpenGL context on this thread (make one current first)");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    return _tlod_fail(ctx, TLOD_ERROR_BACKEND, "gl backend: OpenGL %d.%d is too old (needs 4.5 core): %s", major, minor,
                      version);
  return TLOD_SUCCESS;
}

static tlod_result gl_create(tlod_context* ctx, const tlod_backend_desc* desc, void** state) {
  tlod_result r = check_context(ctx);
  if (r != TLOD_SUCCESS) return r;
  gl_backend* b = _tlod_calloc(ctx, 1, sizeof(*b));
  if (!b) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl backend: out of memory");
  b->ctx = ctx;
  b->hardware = desc && desc->hardware_tessellation;
  snprintf(b->label, sizeof(b->label), "%s", desc && desc->label ? desc->label : "gl");
  /* Named objects only (DSA): creating them binds nothing of the engine's. */
  GLuint bufs[6];
  glCreateBuffers(6, bufs);
  b->buf_patches = bufs[0], b->buf_pattern = bufs[1], b->buf_indices = bufs[2];
  b->buf_instances = bufs[3], b->buf_strips = bufs[4], b->buf_refs = bufs[5];
  glCreateVertexArrays(1, &b->vao_pattern);
  glCreateVertexArrays(1, &b->vao_strip);
  glVertexArrayElementBuffer(b->vao_pattern, b->buf_indices);
  glEnableVertexArrayAttrib(b->vao_strip, 0);
  glVertexArrayAttribIFormat(b->vao_strip, 0, 2, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(b->vao_strip, 0, 0);
  glCreateQueries(GL_TIME_ELAPSED, QUERY_RING, b->queries);
  glCreateQueries(GL_PRIMITIVES_GENERATED, QUERY_RING, b->prim_queries);
  b->timings.gpu_ms = -1.0;
  *state = b;
  return TLOD_SUCCESS;
}

static void gl_destroy(void* state) {
  gl_backend* b = state;
  GLuint bufs[6] = {b->buf_patches, b->buf_pattern, b->buf_indices, b->buf_instances, b->buf_strips, b->buf_refs};
  glDeleteBuffers(6, bufs);
  glDeleteVertexArrays(1, &b->vao_pattern);
  glDeleteVertexArrays(1, &b->vao_strip);
  glDeleteQueries(QUERY_RING, b->queries);
  glDeleteQueries(QUERY_RING, b->prim_queries);
  glDeleteProgram(b->prog_pattern);
  glDeleteProgram(b->prog_strip);
  glDeleteProgram(b->prog_tess[0]);
  glDeleteProgram(b->prog_tess[1]);
  _tlod_free(b->ctx, b->instances);
  _tlod_free(b->ctx, b->strips);
  _tlod_free(b->ctx, b->refs);
  _tlod_free(b->ctx, b->instance_of);
  _tlod_free(b->ctx, b);
}

/* ---- upload ---------------------------------------------------------------- */

static void fill_patch(const tlod_surface* s, uint32_t f, gl_patch* out) {
  const tlod_mesh* m = s->mesh;
  memset(out, 0, sizeof(*out));
  out->info[0] = m->face_corners[f];
  for (uint32_t c = 0; c < m->face_corners[f]; c++) {
    uint32_t v = m->faces[f][c];
    memcpy(out->p[c], m->positions[v], sizeof(float) * 3);
    out->p[c][3] = s->alpha[v];
    memcpy(out->n[c], m->normals[v], sizeof(float) * 3);
    out->weld[c] = m->weld_id[v];
  }
  if (s->pn) {
    for (int i = 0; i < 10; i++)
      memcpy(out->b[i], s->pn[f].b[i], sizeof(float) * 3);
    for (int i = 0; i < 3; i++)
      memcpy(out->mn[i], s->pn[f].n[i], sizeof(float) * 3);
  }
}

static tlod_result upload_patches(gl_backend* b, const tlod_surface* s) {
  uint32_t n = s->patch_count;
  gl_patch* data = _tlod_alloc(b->ctx, sizeof(gl_patch) * (n ? n : 1));
  if (!data) return _tlod_fail(b->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl backend: out of memory for %u patches", n);
  for (uint32_t f = 0; f < n; f++)
    fill_patch(s, f, &data[f]);
  glNamedBufferData(b->buf_patches, (GLsizeiptr)(sizeof(gl_patch) * (n ? n : 1)), data, GL_STATIC_DRAW);
  _tlod_free(b->ctx, data);
  return TLOD_SUCCESS;
}

static tlod_result upload_patterns(gl_backend* b, const tlod_patterns* p) {
  uint32_t counts[2], total = 0, indices = 0;
  const tlod_pattern_vertex* pv[2];
  for (int sh = 0; sh < 2; sh++) {
    pv[sh] = tlod_patterns_vertices(p, (tlod_pattern_shape)sh, &counts[sh]);
    b->shape_base[sh] = total;
    total += counts[sh];
    for (uint32_t l = 0; l <= b->lmax; l++) {
      tlod_patterns_indices(p, (tlod_pattern_shape)sh, l, &b->index_count[sh][l]);
      b->index_first[sh][l] = indices;
      indices += b->index_count[sh][l];
    }
  }
  gl_pattern_vertex* verts = _tlod_calloc(b->ctx, total, sizeof(gl_pattern_vertex));
  uint32_t* idx = _tlod_alloc(b->ctx, sizeof(uint32_t) * indices);
  if (!verts || !idx) {
    _tlod_free(b->ctx, verts);
    _tlod_free(b->ctx, idx);
    return _tlod_fail(b->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl backend: out of memory for patterns");
  }
  for (int sh = 0; sh < 2; sh++) {
    for (uint32_t x = 0; x < counts[sh]; x++) {
      const tlod_pattern_vertex* v = &pv[sh][x];
      gl_pattern_vertex* o = &verts[b->shape_base[sh] + x];
      o->uv[0] = v->u, o->uv[1] = v->v;
      o->parent0 = v->parent[0], o->parent1 = v->parent[1];
      uint32_t param = 0, kind = tlod_pattern_vertex_kind((tlod_pattern_shape)sh, b->lmax, v->i, v->j, &param);
      o->code = kind | (uint32_t)v->level << 8;
      o->param = param;
    }
    for (uint32_t l = 0; l <= b->lmax; l++) {
      uint32_t count;
      const uint32_t* src = tlod_patterns_indices(p, (tlod_pattern_shape)sh, l, &count);
      memcpy(idx + b->index_first[sh][l], src, sizeof(uint32_t) * count);
    }
  }
  glNamedBufferData(b->buf_pattern, (GLsizeiptr)(sizeof(gl_pattern_vertex) * total), verts, GL_STATIC_DRAW);
  glNamedBufferData(b->buf_indices, (GLsizeiptr)(sizeof(uint32_t) * indices), idx, GL_STATIC_DRAW);
  _tlod_free(b->ctx, verts);
  _tlod_free(b->ctx, idx);
  return TLOD_SUCCESS;
}

static tlod_result build_programs(gl_backend* b, tlod_surface_type type) {
  const char* surface = type == TLOD_SURFACE_PN      ? _tlod_shader_pn
                        : type == TLOD_SURFACE_PHONG ? _tlod_shader_phong
                                                     : _tlod_shader_flat;
  const char* version = "#version 450 core\n";
  const char* pattern[] = {version, _tlod_shader_common, surface, _tlod_shader_pattern_vert};
  const char* strip[] = {version, _tlod_shader_common, surface, _tlod_shader_strip_vert};
  const char* frag[] = {version, _tlod_shader_shade_frag};
  char error[1200];
  glDeleteProgram(b->prog_pattern);
  glDeleteProgram(b->prog_strip);
  b->prog_strip = 0;
  b->prog_pattern = _tlod_gl_program(pattern, 4, frag, 2, error, sizeof(error));
  if (b->prog_pattern) b->prog_strip = _tlod_gl_program(strip, 4, frag, 2, error, sizeof(error));
  for (int sh = 0; sh < 2 && b->hardware && b->prog_strip; sh++) {
    const char* corners = sh ? "#define TLOD_CORNERS 4\n" : "#define TLOD_CORNERS 3\n";
    const char* vs[] = {version, corners, _tlod_shader_common, surface, _tlod_shader_tess_vert};
    const char* tcs[] = {version, corners, _tlod_shader_common, surface, _tlod_shader_tess_tesc};
    const char* tes[] = {version, corners, _tlod_shader_common, surface, _tlod_shader_tess_tese};
    const char* const* stages[4] = {vs, tcs, tes, frag};
    const int counts[4] = {5, 5, 5, 2};
    glDeleteProgram(b->prog_tess[sh]);
    b->prog_tess[sh] = _tlod_gl_program_tess(stages, counts, error, sizeof(error));
    if (!b->prog_tess[sh]) b->prog_strip = 0;
  }
  if (!b->prog_pattern || !b->prog_strip)
    return _tlod_fail(b->ctx, TLOD_ERROR_BACKEND, "gl backend: shader build failed: %s", error);
  return TLOD_SUCCESS;
}

static tlod_result gl_upload(void* state, const tlod_surface* s, const tlod_patterns* p) {
  gl_backend* b = state;
  b->surface = s;
  b->patterns = p;
  b->lmax = tlod_patterns_max_level(p);
  tlod_result r = build_programs(b, s->desc.type);
  if (r == TLOD_SUCCESS) r = upload_patches(b, s);
  if (r == TLOD_SUCCESS) r = upload_patterns(b, p);
  return r;
}

/* ---- per frame ------------------------------------------------------------- */

static bool grow(gl_backend* b, void** buf, uint32_t* cap, uint32_t need, size_t elem) {
  if (need <= *cap) return true;
  uint32_t n = *cap ? *cap : 256;
  while (n < need)
    n *= 2;
  void* p = _tlod_alloc(b->ctx, elem * n);
  if (!p) return false;
  _tlod_free(b->ctx, *buf);
  *buf = p;
  *cap = n;
  return true;
}

/* Hardware path: an edge is tessellated at the finer of its two sides'
 * levels, so both sides generate the same points. */
static uint32_t edge_levels(const tlod_surface* s, const tlod_draw_list* dl, const tlod_draw_instance* in) {
  const tlod_mesh* m = s->mesh;
  uint32_t packed = 0;
  for (uint32_t e = 0; e < m->face_corners[in->patch]; e++) {
    uint32_t l = in->level, g = m->links[in->patch][e].face;
    if (g != UINT32_MAX && dl->levels[g] > (int8_t)l) l = (uint32_t)dl->levels[g];
    packed |= l << (8 * e);
  }
  return packed;
}

static tlod_result stage_frame(gl_backend* b, const tlod_draw_list* dl, uint32_t* ref_count) {
  uint32_t refs = 0;
  for (uint32_t k = 0; k < dl->strip_count; k++) {
    uint32_t count;
    tlod_patterns_connection(b->patterns, dl->strips[k].level_a, dl->strips[k].level_b, &count);
    refs += 3 * count;
  }
  if (!grow(b, (void**)&b->instances, &b->instance_cap, dl->instance_count + 1, sizeof(gl_instance)) ||
      !grow(b, (void**)&b->strips, &b->strip_cap, dl->strip_count + 1, sizeof(gl_strip)) ||
      !grow(b, (void**)&b->refs, &b->ref_cap, refs + 1, sizeof(uint32_t[2])) ||
      !grow(b, (void**)&b->instance_of, &b->instance_of_cap, dl->patch_count + 1, sizeof(uint32_t)))
    return _tlod_fail(b->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl backend: out of memory staging a frame");
  for (uint32_t k = 0; k < dl->instance_count; k++) {
    const tlod_draw_instance* in = &dl->instances[k];
    b->instances[k] = (gl_instance){.patch = in->patch,
                                    .level = in->level,
                                    .edge_levels = edge_levels(b->surface, dl, in),
                                    .morph = {in->morph, in->edge_morph[0], in->edge_morph[1], in->edge_morph[2]},
                                    .morph_e3 = {in->edge_morph[3], 0, 0, 0}};
    if (in->patch < dl->patch_count) b->instance_of[in->patch] = k;
  }
  uint32_t r = 0;
  for (uint32_t k = 0; k < dl->strip_count; k++) {
    const tlod_draw_strip* st = &dl->strips[k];
    /* Each side blends its edge points as its own patch does. */
    float ma = dl->instances[b->instance_of[st->patch_a]].edge_morph[st->edge_a];
    float mb = dl->instances[b->instance_of[st->patch_b]].edge_morph[st->edge_b];
    b->strips[k] = (gl_strip){st->patch_a,
                              st->patch_b,
                              st->edge_a | (uint32_t)st->edge_b << 8,
                              st->level_a | (uint32_t)st->level_b << 8,
                              {ma, mb, 0.0f, 0.0f}};
    uint32_t count;
    const uint32_t* tris = tlod_patterns_connection(b->patterns, st->level_a, st->level_b, &count);
    for (uint32_t t = 0; t < 3 * count; t++)
      b->refs[r][0] = k, b->refs[r++][1] = tris[t];
  }
  *ref_count = r;
  return TLOD_SUCCESS;
}

/* Orphans the buffer and fills it: the driver never waits for a frame in flight. */
static void stream(GLuint buf, const void* data, size_t bytes) {
  glNamedBufferData(buf, (GLsizeiptr)(bytes ? bytes : 16), NULL, GL_STREAM_DRAW);
  if (bytes) glNamedBufferSubData(buf, 0, (GLsizeiptr)bytes, data);
}

static void set_uniforms(GLuint prog, const tlod_backend_frame* fr, uint32_t lmax, uint32_t debug) {
  float vp[16];
  for (int c = 0; c < 4; c++) {
    for (int r = 0; r < 4; r++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++)
        s += fr->proj[k * 4 + r] * fr->view[c * 4 + k];
      vp[c * 4 + r] = s;
    }
  }
  float light[3] = {fr->light_dir[0], fr->light_dir[1], fr->light_dir[2]};
  if (light[0] == 0.0f && light[1] == 0.0f && light[2] == 0.0f) light[0] = 0.3f, light[1] = 0.8f, light[2] = 0.5f;
  float len = sqrtf(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
  float base[4] = {fr->base_color[0], fr->base_color[1], fr->base_color[2], fr->base_color[3]};
  if (base[0] == 0.0f && base[1] == 0.0f && base[2] == 0.0f && base[3] == 0.0f) base[0] = base[1] = base[2] = 0.8f;
  if (base[3] == 0.0f) base[3] = 1.0f;
  const float* v = fr->view;
  float eye[3], fwd[3];
  for (int i = 0; i < 3; i++) {
    eye[i] = -(v[i * 4 + 0] * v[12] + v[i * 4 + 1] * v[13] + v[i * 4 + 2] * v[14]);
    fwd[i] = -v[i * 4 + 2];
  }
  glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_proj"), 1, GL_FALSE, vp);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_grid"), 1u << lmax);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_max_level"), lmax);
  glProgramUniform3f(prog, glGetUniformLocation(prog, "u_light_dir"), light[0] / len, light[1] / len, light[2] / len);
  glProgramUniform4fv(prog, glGetUniformLocation(prog, "u_base_color"), 1, base);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_debug"), debug);
  glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_eye"), 1, eye);
  glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_forward"), 1, fwd);
  glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_ortho"), fr->proj[15] == 1.0f ? 1u : 0u);
}

/* One instanced draw per refinement pattern, then the strips in one draw. */
static uint32_t issue_draws(gl_backend* b, const tlod_draw_list* dl, uint32_t refs, uint64_t* vertices) {
  uint32_t calls = 0;
  glUseProgram(b->prog_pattern);
  glBindVertexArray(b->vao_pattern);
  GLint first = glGetUniformLocation(b->prog_pattern, "u_first_instance");
  GLint base = glGetUniformLocation(b->prog_pattern, "u_shape_base");
  for (uint32_t k = 0; k < dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape;
    glProgramUniform1ui(b->prog_pattern, first, bk->first);
    glProgramUniform1ui(b->prog_pattern, base, b->shape_base[sh]);
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)b->index_count[sh][bk->level], GL_UNSIGNED_INT,
                            (const void*)(sizeof(uint32_t) * (size_t)b->index_first[sh][bk->level]),
                            (GLsizei)bk->count);
    *vertices += (uint64_t)tlod_pattern_vertex_count(bk->shape, bk->level) * bk->count;
    calls++;
  }
  if (refs) {
    glUseProgram(b->prog_strip);
    glBindVertexArray(b->vao_strip);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)refs);
    *vertices += refs;
    calls++;
  }
  return calls;
}

/* Tessellated vertices of a patch whose largest level is l (PLATFORM.md). */
static uint32_t tess_vertices(uint32_t corners, uint32_t l) {
  uint32_t n = 1u << l;
  if (corners == 4) return (n + 1) * (n + 1);
  return n == 1 ? 3u : 3u * n * n / 4u + 3u * n / 2u + 1u;
}

/* Hardware path: per bucket, draws of whole patches kept under 65,536
 * tessellated vertices each (Mesa drops what lies past that, silently). */
static uint32_t issue_tess_draws(gl_backend* b, const tlod_draw_list* dl, uint64_t* vertices) {
  uint32_t calls = 0;
  for (uint32_t k = 0; k < dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape, corners = sh ? 4u : 3u;
    GLuint prog = b->prog_tess[sh];
    glUseProgram(prog);
    glBindVertexArray(b->vao_pattern);
    glPatchParameteri(GL_PATCH_VERTICES, (GLint)corners);
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_corners"), corners);
    GLint first = glGetUniformLocation(prog, "u_first_instance");
    uint32_t start = bk->first, end = bk->first + bk->count, batch_vertices = 0;
    for (uint32_t i = start; i <= end; i++) {
      uint32_t v = 0;
      if (i < end) {
        uint32_t l = b->instances[i].level;
        for (uint32_t e = 0; e < corners; e++) {
          uint32_t le = (b->instances[i].edge_levels >> (8 * e)) & 255u;
          l = le > l ? le : l;
        }
        v = tess_vertices(corners, l);
      }
      if (i == end || batch_vertices + v > 65535u) {
        if (i > start) {
          glProgramUniform1ui(prog, first, start);
          glDrawArrays(GL_PATCHES, 0, (GLsizei)((i - start) * corners));
          calls++;
        }
        start = i;
        batch_vertices = 0;
      }
      batch_vertices += v;
      *vertices += v;
    }
  }
  return calls;
}

static void read_query(gl_backend* b) {
  /* The query of QUERY_RING - 1 frames ago: reading it never stalls. */
  if (b->frame < QUERY_RING) return;
  GLuint q = b->queries[(b->frame + 1) % QUERY_RING];
  GLint ready = 0;
  glGetQueryObjectiv(q, GL_QUERY_RESULT_AVAILABLE, &ready);
  if (!ready) return;
  GLuint64 ns = 0, prims = 0;
  glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
  glGetQueryObjectui64v(b->prim_queries[(b->frame + 1) % QUERY_RING], GL_QUERY_RESULT, &prims);
  b->timings.gpu_ms = (double)ns * 1e-6;
  b->timings.primitives_generated = prims;
}

static tlod_result gl_draw(void* state, const tlod_backend_frame* fr) {
  gl_backend* b = state;
  const tlod_draw_list* dl = fr->draw_list;
  if (!b->surface) return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT, "gl backend: draw before upload");
  if (!dl || dl->patch_count != b->surface->patch_count)
    return _tlod_fail(b->ctx, TLOD_ERROR_INVALID_ARGUMENT,
                      "gl backend: the draw list does not match the uploaded surface");
  double t0 = _tlod_now_ms();
  uint32_t refs = 0;
  tlod_result r = stage_frame(b, dl, &refs);
  if (r != TLOD_SUCCESS) return r;
  gl_saved_state saved;
  _tlod_gl_save_state(&saved);
  stream(b->buf_instances, b->instances, sizeof(gl_instance) * dl->instance_count);
  stream(b->buf_strips, b->strips, sizeof(gl_strip) * dl->strip_count);
  stream(b->buf_refs, b->refs, sizeof(uint32_t[2]) * refs);
  glVertexArrayVertexBuffer(b->vao_strip, 0, b->buf_refs, 0, sizeof(uint32_t[2]));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, b->buf_patches);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b->buf_pattern);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, b->buf_instances);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, b->buf_strips);
  glViewport((GLint)fr->viewport[0], (GLint)fr->viewport[1], (GLsizei)fr->viewport[2], (GLsizei)fr->viewport[3]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  /* An engine may be timing the frame around us: one query per target can
   * be active, so ours stay out of its way then. */
  GLint busy_time = 0, busy_prims = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &busy_time);
  glGetQueryiv(GL_PRIMITIVES_GENERATED, GL_CURRENT_QUERY, &busy_prims);
  bool timed = !busy_time && !busy_prims;
  if (timed) {
    glBeginQuery(GL_TIME_ELAPSED, b->queries[b->frame % QUERY_RING]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, b->prim_queries[b->frame % QUERY_RING]);
  }
  uint32_t debug = (uint32_t)fr->debug;
  set_uniforms(b->prog_pattern, fr, b->lmax, debug);
  set_uniforms(b->prog_strip, fr, b->lmax, debug);
  for (int sh = 0; sh < 2 && b->hardware; sh++)
    set_uniforms(b->prog_tess[sh], fr, b->lmax, debug);
  uint64_t vertices = 0;
  if (fr->wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  uint32_t calls = b->hardware ? issue_tess_draws(b, dl, &vertices) : issue_draws(b, dl, refs, &vertices);
  if (fr->wireframe) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    set_uniforms(b->prog_pattern, fr, b->lmax, 4u);
    set_uniforms(b->prog_strip, fr, b->lmax, 4u);
    for (int sh = 0; sh < 2 && b->hardware; sh++)
      set_uniforms(b->prog_tess[sh], fr, b->lmax, 4u);
    uint64_t unused = 0;
    calls += b->hardware ? issue_tess_draws(b, dl, &unused) : issue_draws(b, dl, refs, &unused);
  }
  if (timed) {
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TIME_ELAPSED);
    read_query(b);
    b->frame++;
  }
  _tlod_gl_restore_state(&saved);
  b->timings.cpu_ms = _tlod_now_ms() - t0;
  if (fr->finish) {
    glFinish();
    b->timings.wall_ms = _tlod_now_ms() - t0;
  }
  b->timings.triangles = b->hardware ? dl->pattern_triangles : dl->pattern_triangles + refs / 3;
  b->timings.vertices = vertices;
  b->timings.draw_calls = calls;
  return TLOD_SUCCESS;
}

static tlod_result gl_read_image(void* state, uint32_t width, uint32_t height, uint8_t* rgba) {
  (void)state;
  /* Into client memory whatever the engine's pack state: a bound pixel pack
   * buffer or a row length would redirect or reshape the read. */
  GLint align = 4, row_length = 0, pack_buffer = 0;
  glGetIntegerv(GL_PACK_ALIGNMENT, &align);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glReadPixels(0, 0, (GLsizei)width, (GLsizei)height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  glPixelStorei(GL_PACK_ALIGNMENT, align);
  glPixelStorei(GL_PACK_ROW_LENGTH, row_length);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
  return TLOD_SUCCESS;
}

static tlod_backend_timings gl_timings(const void* state) { return ((const gl_backend*)state)->timings; }

const tlod_backend_vtbl _tlod_gl_vtbl = {gl_create, gl_destroy, gl_upload, gl_draw, gl_read_image, gl_timings};
