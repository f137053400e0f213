/* tesslod::gl -- OpenGL 4.5 core device: refinement patterns drawn
 * instanced, each vertex evaluating its patch in the vertex shader; strips
 * from the connection patterns; geomorphs; timer queries. Programs and
 * pattern buffers are made once per device; a device surface is one storage
 * buffer of patch records.
 *
 * This work is based on:
 *   T. Boubekeur, C. Schlick. Generic mesh refinement on GPU. Graphics
 *   Hardware 2005 (refinement patterns evaluated in the vertex shader);
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "device_stage.h"
#include "gl_internal.h"

enum { QUERY_RING = 4, TYPE_COUNT = TLOD_SURFACE_NUM };
/* The programs a surface type may need, by what the item's fragments read:
 * PLAIN neither texture coordinates nor attributes (the default look,
 * linked at creation), FULL the base colour texture and, for a fragment
 * hook, every attribute, MASK FULL with the alpha test (both linked at the
 * first item that needs them). Each varying and the texture fetch cost per
 * fragment even when a uniform skips the fetch (llvmpipe, measured: docs/
 * shaders.md), so an untextured item never carries them. */
enum { VARIANT_PLAIN, VARIANT_FULL, VARIANT_MASK, VARIANT_COUNT };

/* The uniforms the device sets, by index; locations looked up once, at link
 * (backends/shaders/common.glsl, shade.frag and the vertex stages). */
enum {
  U_VIEW_PROJ,
  U_MODEL,
  U_NORMAL_MATRIX,
  U_LIGHT_DIR,
  U_BASE_COLOR,
  U_DEBUG,
  U_EYE,
  U_FORWARD,
  U_ORTHO,
  U_FIRST_INSTANCE,
  U_SHAPE_BASE,
  U_CORNERS,
  U_GRID,
  U_MAX_LEVEL,
  U_ALPHA_CUTOFF,
  U_TEXCOORD,
  U_ATTRIBUTE_COUNT,
  U_COUNT
};
static const char* const uniform_names[U_COUNT] = {
    "u_view_proj", "u_model",     "u_normal_matrix", "u_light_dir",      "u_base_color",     "u_debug",
    "u_eye",       "u_forward",   "u_ortho",         "u_first_instance", "u_shape_base",     "u_corners",
    "u_grid",      "u_max_level", "u_alpha_cutoff",  "u_texcoord",       "u_attribute_count"};

typedef struct gl_program {
  GLuint id;
  GLint loc[U_COUNT]; /* -1: not in this program (GL ignores the call) */
} gl_program;

/* The programs of one surface type. */
typedef struct gl_programs {
  bool linked;
  gl_program pattern, strip;
  gl_program tess[2]; /* hardware path: triangles, quads */
  gl_program mesh;    /* CPU-mesh mode (PLAIN only): mesh.vert */
} gl_programs;

typedef struct gl_device {
  tlod_context* ctx;
  char label[64];
  const tlod_patterns* patterns;
  tlod_device_stats* stats;
  uint32_t lmax;
  bool hardware;
  bool cpu_mesh;       /* tlod_gpu_eval resolved to OFF: PLAIN items draw their CPU mesh (gl_mesh.c) */
  char* fragment_hook; /* a copy of the desc's (FULL and MASK programs link later); NULL == material.glsl */
  /* By resolved surface type and variant: programs with `discard` (MASK
   * items) are their own: a shader that may discard loses the early depth
   * test (llvmpipe: ~10% of a heavy frame), so the others never carry it. */
  gl_programs programs[TYPE_COUNT][VARIANT_COUNT];
  GLuint vao_pattern, vao_strip;
  GLuint buf_pattern, buf_indices, buf_instances, buf_strips, buf_refs, buf_strip_indices;
  uint32_t index_first[2][TLOD_MAX_LEVEL + 1], index_count[2][TLOD_MAX_LEVEL + 1], shape_base[2];
  GLuint queries[QUERY_RING];
  GLuint prim_queries[QUERY_RING];
  uint64_t query_draw[QUERY_RING]; /* the draw (stats numbering) each query measured */
  uint64_t frame;
  _tlod_stage st;             /* staging of every item of a draw (device_stage.h) */
  tlod_patch_record* records; /* surface upload */
  uint32_t record_cap;
  float (*attributes)[4]; /* surface upload */
  uint32_t attribute_cap;
} gl_device;

typedef struct gl_surface {
  GLuint buf_patches, buf_attributes;
  uint32_t attribute_count;
  float center[3]; /* of the box around the patches' bounding spheres (BLEND order) */
  tlod_surface_type type;
  uint32_t patch_count;
  const tlod_surface* surface;
  gl_mesh mesh; /* CPU-mesh mode */
} gl_surface;

static tlod_result check_context(tlod_context* ctx) {
  const char* version = (const char*)glGetString(GL_VERSION);
  if (!version)
    return tlod_context_fail(ctx, TLOD_ERROR_BACKEND,
                             "gl device: no current OpenGL context on this thread (make one current first)");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    return tlod_context_fail(ctx, TLOD_ERROR_BACKEND, "gl device: OpenGL %d.%d is too old (needs 4.5 core): %s", major,
                             minor, version);
  return TLOD_SUCCESS;
}

static void gl_destroy(void* state) {
  gl_device* d = state;
  GLuint bufs[6] = {d->buf_pattern, d->buf_indices, d->buf_instances, d->buf_strips, d->buf_refs, d->buf_strip_indices};
  glDeleteBuffers(6, bufs);
  glDeleteVertexArrays(1, &d->vao_pattern);
  glDeleteVertexArrays(1, &d->vao_strip);
  glDeleteQueries(QUERY_RING, d->queries);
  glDeleteQueries(QUERY_RING, d->prim_queries);
  for (int t = 0; t < TYPE_COUNT; t++) {
    for (int m = 0; m < VARIANT_COUNT; m++) {
      glDeleteProgram(d->programs[t][m].pattern.id);
      glDeleteProgram(d->programs[t][m].strip.id);
      glDeleteProgram(d->programs[t][m].tess[0].id);
      glDeleteProgram(d->programs[t][m].tess[1].id);
      glDeleteProgram(d->programs[t][m].mesh.id);
    }
  }
  tlod_context_free(d->ctx, d->fragment_hook);
  _tlod_stage_free(d->ctx, &d->st);
  tlod_context_free(d->ctx, d->records);
  tlod_context_free(d->ctx, d->attributes);
  tlod_context_free(d->ctx, d);
}

/* ---- programs and patterns (once per device) ----------------------------- */

static void locate(gl_device* d, gl_program* p) {
  for (int u = 0; u < U_COUNT; u++)
    p->loc[u] = glGetUniformLocation(p->id, uniform_names[u]);
  /* Constant for the device's patterns. */
  glProgramUniform1ui(p->id, p->loc[U_GRID], 1u << d->lmax);
  glProgramUniform1ui(p->id, p->loc[U_MAX_LEVEL], d->lmax);
  d->stats->gl.program_links++;
}

static tlod_result build_programs(gl_device* d, tlod_surface_type type, int variant) {
  const char* surface = _tlod_shader_surface(type);
  /* All attributes reach the fragment stage only for a hook: the built-in
   * material reads none, and each varying costs per fragment. */
  bool full = variant != VARIANT_PLAIN;
  _tlod_shader_variant v = {.attribute_varyings = full && d->fragment_hook ? TLOD_SHADER_MAX_ATTRIBUTES : 0,
                            .texcoord = full,
                            .mask = variant == VARIANT_MASK};
  char version[_TLOD_SHADER_DEFINES_BYTES];
  _tlod_shader_defines(&v, version);
  const char *pattern[_TLOD_SHADER_STAGE_SOURCES], *strip[_TLOD_SHADER_STAGE_SOURCES];
  int np = _tlod_shader_vertex_side(pattern, version, NULL, surface, true, _tlod_shader_pattern_vert);
  int ns = _tlod_shader_vertex_side(strip, version, NULL, surface, true, _tlod_shader_strip_vert);
  /* The material's lines are numbered from TLOD_GL_HOOK_LINE: the driver's log names them. */
  const char* frag[_TLOD_SHADER_FRAGMENT_SOURCES];
  int nf = _tlod_shader_fragment(frag, version, TLOD_GL_HOOK_LINE_DIRECTIVE, d->fragment_hook);
  char error[1600] = "";
  gl_programs* ps = &d->programs[type][variant];
  ps->pattern.id = _tlod_gl_program(pattern, np, frag, nf, error, sizeof(error));
  if (ps->pattern.id) ps->strip.id = _tlod_gl_program(strip, ns, frag, nf, error, sizeof(error));
  bool ok = ps->pattern.id && ps->strip.id;
  if (ok && d->cpu_mesh && variant == VARIANT_PLAIN) {
    const char* mesh[_TLOD_SHADER_STAGE_SOURCES];
    int nm = _tlod_shader_vertex_side(mesh, version, NULL, surface, true, _tlod_shader_mesh_vert);
    ps->mesh.id = _tlod_gl_program(mesh, nm, frag, nf, error, sizeof(error));
    ok = ps->mesh.id != 0;
  }
  for (int sh = 0; sh < 2 && d->hardware && ok; sh++) {
    const char* corners = _tlod_shader_corners(sh ? 4 : 3);
    const char *vs[_TLOD_SHADER_STAGE_SOURCES], *tcs[_TLOD_SHADER_STAGE_SOURCES], *tes[_TLOD_SHADER_STAGE_SOURCES];
    const int counts[4] = {_tlod_shader_vertex_side(vs, version, corners, surface, false, _tlod_shader_tess_vert),
                           _tlod_shader_vertex_side(tcs, version, corners, surface, false, _tlod_shader_tess_tesc),
                           _tlod_shader_vertex_side(tes, version, corners, surface, true, _tlod_shader_tess_tese), nf};
    const char* const* stages[4] = {vs, tcs, tes, frag};
    ps->tess[sh].id = _tlod_gl_program_tess(stages, counts, error, sizeof(error));
    ok = ps->tess[sh].id != 0;
  }
  if (!ok)
    return tlod_context_fail(d->ctx, TLOD_ERROR_BACKEND, "gl device '%s': %s shader build failed: %s", d->label,
                             tlod_surface_type_name(type), error);
  locate(d, &ps->pattern);
  locate(d, &ps->strip);
  if (ps->mesh.id) locate(d, &ps->mesh);
  for (int sh = 0; sh < 2 && d->hardware; sh++)
    locate(d, &ps->tess[sh]);
  ps->linked = true;
  return TLOD_SUCCESS;
}

static tlod_result upload_patterns(gl_device* d) {
  _tlod_pattern_data pd;
  if (!_tlod_pattern_data_make(d->ctx, d->patterns, &pd)) {
    _tlod_pattern_data_free(d->ctx, &pd);
    return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory for patterns");
  }
  memcpy(d->index_first, pd.index_first, sizeof(d->index_first));
  memcpy(d->index_count, pd.index_count, sizeof(d->index_count));
  memcpy(d->shape_base, pd.shape_base, sizeof(d->shape_base));
  size_t vbytes = sizeof(tlod_gl_pattern_vertex) * pd.vertex_count, ibytes = sizeof(uint32_t) * pd.index_total;
  glNamedBufferData(d->buf_pattern, (GLsizeiptr)vbytes, pd.vertices, GL_STATIC_DRAW);
  glNamedBufferData(d->buf_indices, (GLsizeiptr)ibytes, pd.indices, GL_STATIC_DRAW);
  d->stats->gl.pattern_uploads++;
  d->stats->gl.pattern_bytes += vbytes + ibytes;
  _tlod_pattern_data_free(d->ctx, &pd);
  return TLOD_SUCCESS;
}

static tlod_result gl_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats, void** state) {
  tlod_result r = check_context(ctx);
  if (r != TLOD_SUCCESS) return r;
  double t0 = tlod_now_ms();
  gl_device* d = tlod_context_calloc(ctx, 1, sizeof(*d));
  if (!d) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory");
  d->ctx = ctx;
  d->stats = stats;
  d->patterns = desc->patterns;
  d->lmax = tlod_patterns_max_level(desc->patterns);
  d->hardware = desc->gl.hardware_tessellation;
  d->st.hardware = d->hardware;
  const char* renderer = (const char*)glGetString(GL_RENDERER);
  d->cpu_mesh = _tlod_resolve_gpu_eval(stats, desc->gl.gpu_eval, _tlod_software_renderer(renderer), d->hardware,
                                       "desc.gl.gpu_eval", renderer);
  if (desc->gl.fragment_hook) {
    size_t n = strlen(desc->gl.fragment_hook) + 1;
    d->fragment_hook = tlod_context_alloc(ctx, n);
    if (!d->fragment_hook) {
      tlod_context_free(ctx, d);
      return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory for the fragment hook");
    }
    memcpy(d->fragment_hook, desc->gl.fragment_hook, n);
  }
  snprintf(d->label, sizeof(d->label), "%s", desc->label);
  /* Named objects only (DSA): creating them binds nothing of the engine's. */
  GLuint bufs[6];
  glCreateBuffers(6, bufs);
  d->buf_pattern = bufs[0], d->buf_indices = bufs[1], d->buf_instances = bufs[2];
  d->buf_strips = bufs[3], d->buf_refs = bufs[4], d->buf_strip_indices = bufs[5];
  glCreateVertexArrays(1, &d->vao_pattern);
  glCreateVertexArrays(1, &d->vao_strip);
  glVertexArrayElementBuffer(d->vao_pattern, d->buf_indices);
  glEnableVertexArrayAttrib(d->vao_strip, TLOD_ATTRIB_STRIP_REF);
  glVertexArrayAttribIFormat(d->vao_strip, TLOD_ATTRIB_STRIP_REF, 2, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(d->vao_strip, TLOD_ATTRIB_STRIP_REF, 0);
  glVertexArrayVertexBuffer(d->vao_strip, 0, d->buf_refs, 0, sizeof(uint32_t[2]));
  glVertexArrayElementBuffer(d->vao_strip, d->buf_strip_indices);
  glCreateQueries(GL_TIME_ELAPSED, QUERY_RING, d->queries);
  glCreateQueries(GL_PRIMITIVES_GENERATED, QUERY_RING, d->prim_queries);
  uint32_t mask = desc->gl.surface_types ? desc->gl.surface_types : (1u << TLOD_SURFACE_NUM) - 1u;
  if (mask & (1u << TLOD_SURFACE_DEFAULT)) mask |= 1u << TLOD_SURFACE_PHONG;
  for (int t = 1; t < TYPE_COUNT && r == TLOD_SUCCESS; t++) {
    if (mask & (1u << t)) r = build_programs(d, (tlod_surface_type)t, VARIANT_PLAIN);
  }
  if (r == TLOD_SUCCESS) r = upload_patterns(d);
  if (r != TLOD_SUCCESS) {
    gl_destroy(d);
    return r;
  }
  stats->gl.create_ms = tlod_now_ms() - t0;
  *state = d;
  return TLOD_SUCCESS;
}

/* ---- surfaces -------------------------------------------------------------- */

/* The mesh attributes per patch and corner (tlod_mesh_patch_attributes), the
 * layout of TLOD_BINDING_ATTRIBUTES; one vec4 of zeros without any. */
static tlod_result upload_attributes(gl_device* d, gl_surface* gs, const tlod_surface* s) {
  const tlod_mesh* mesh = tlod_surface_mesh(s);
  uint32_t n = gs->patch_count, count = tlod_mesh_attribute_count(mesh);
  size_t vec4s = (size_t)n * 4u * count;
  if (vec4s > UINT32_MAX - 1u ||
      !_tlod_device_grow(d->ctx, (void**)&d->attributes, &d->attribute_cap, (uint32_t)vec4s + 1u, sizeof(float[4])))
    return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory for %u patches' attributes",
                             n);
  memset(d->attributes, 0, sizeof(float[4]));
  tlod_result r = count ? tlod_mesh_patch_attributes(mesh, 0, n, d->attributes) : TLOD_SUCCESS;
  if (r != TLOD_SUCCESS) return r;
  size_t bytes = sizeof(float[4]) * (vec4s ? vec4s : 1u);
  glNamedBufferData(gs->buf_attributes, (GLsizeiptr)bytes, d->attributes, GL_STATIC_DRAW);
  gs->attribute_count = count;
  d->stats->gl.attribute_bytes += bytes;
  return TLOD_SUCCESS;
}

static tlod_result upload_surface(gl_device* d, gl_surface* gs, const tlod_surface* s) {
  double t0 = tlod_now_ms();
  uint32_t n = gs->patch_count;
  if (!_tlod_device_grow(d->ctx, (void**)&d->records, &d->record_cap, n + 1, sizeof(tlod_patch_record)))
    return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory for %u patch records", n);
  tlod_result r = tlod_surface_patch_records(s, 0, n, d->records);
  if (r != TLOD_SUCCESS) return r;
  size_t bytes = sizeof(tlod_patch_record) * (n ? n : 1);
  if (!n) memset(d->records, 0, sizeof(tlod_patch_record));
  glNamedBufferData(gs->buf_patches, (GLsizeiptr)bytes, d->records, GL_STATIC_DRAW);
  d->stats->gl.patch_bytes += bytes;
  _tlod_surface_center(s, gs->center);
  r = upload_attributes(d, gs, s);
  if (r != TLOD_SUCCESS) return r;
  d->stats->gl.surface_upload_ms += tlod_now_ms() - t0;
  return TLOD_SUCCESS;
}

static tlod_result gl_create_surface(void* state, const tlod_surface* s, void** surface_state) {
  gl_device* d = state;
  tlod_surface_view view = tlod_surface_query_view(s);
  if ((uint32_t)view.type >= TYPE_COUNT || !d->programs[view.type][0].linked)
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED,
                             "gl device '%s': surface '%s' is %s, and the device has no programs for it "
                             "(desc.gl.surface_types)",
                             d->label, tlod_surface_query_desc(s).label ? tlod_surface_query_desc(s).label : "surface",
                             tlod_surface_type_name(view.type));
  gl_surface* gs = tlod_context_calloc(d->ctx, 1, sizeof(*gs));
  if (!gs) return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory");
  gs->type = view.type;
  gs->patch_count = view.patch_count;
  gs->surface = s;
  glCreateBuffers(1, &gs->buf_patches);
  glCreateBuffers(1, &gs->buf_attributes);
  tlod_result r = upload_surface(d, gs, s);
  if (r != TLOD_SUCCESS) {
    glDeleteBuffers(1, &gs->buf_patches);
    glDeleteBuffers(1, &gs->buf_attributes);
    tlod_context_free(d->ctx, gs);
    return r;
  }
  *surface_state = gs;
  return TLOD_SUCCESS;
}

static tlod_result gl_update_surface(void* state, void* surface_state, const tlod_surface* s) {
  return upload_surface(state, surface_state, s);
}

static void gl_destroy_surface(void* state, void* surface_state) {
  gl_device* d = state;
  gl_surface* gs = surface_state;
  glDeleteBuffers(1, &gs->buf_patches);
  glDeleteBuffers(1, &gs->buf_attributes);
  _tlod_gl_mesh_free(d->ctx, &gs->mesh);
  tlod_context_free(d->ctx, gs);
}

/* ---- staging ----------------------------------------------------------------- */

/* Every item's instances, strips, strip references and indices
 * (device_stage.h), then one upload per array; none when the items' draw
 * lists are those of the last draw (the buffers hold them already). */
static tlod_result stage(gl_device* d, const tlod_draw_desc* desc, const _tlod_draw_ref* items,
                         tlod_draw_item_stats* item_stats) {
  bool restaged = true;
  tlod_result r = _tlod_stage_items(d->ctx, &d->st, d->patterns, "gl device", desc, items, item_stats, &restaged);
  d->stats->gl.buffer_streams = 0;
  if (r != TLOD_SUCCESS || !restaged) return r;
  /* Orphans each buffer and fills it: the driver never waits for a draw in flight. */
  const GLuint bufs[4] = {d->buf_instances, d->buf_strips, d->buf_refs, d->buf_strip_indices};
  const void* data[4] = {d->st.instances, d->st.strips, d->st.refs, d->st.indices};
  const size_t bytes[4] = {sizeof(tlod_gl_instance) * d->st.instance_count, sizeof(tlod_gl_strip) * d->st.strip_count,
                           sizeof(uint32_t[2]) * d->st.ref_count, sizeof(uint32_t) * d->st.index_count};
  for (int b = 0; b < 4; b++) {
    glNamedBufferData(bufs[b], (GLsizeiptr)(bytes[b] ? bytes[b] : 16), NULL, GL_STREAM_DRAW);
    if (bytes[b]) glNamedBufferSubData(bufs[b], 0, (GLsizeiptr)bytes[b], data[b]);
  }
  d->stats->gl.buffer_streams = 4;
  return TLOD_SUCCESS;
}

/* ---- drawing ----------------------------------------------------------------- */

/* The programs of a surface type in use: pattern and strip, and the two
 * tessellation programs with hardware tessellation. */
static int programs_of(const gl_device* d, const gl_programs* ps, const gl_program* out[4]) {
  int n = 0;
  out[n++] = &ps->pattern, out[n++] = &ps->strip;
  if (d->hardware) out[n++] = &ps->tess[0], out[n++] = &ps->tess[1];
  if (ps->mesh.id) out[n++] = &ps->mesh; /* never with hardware tessellation */
  return n;
}

/* The view's uniforms, on every program the device linked. */
static void set_view_uniforms(gl_device* d, const tlod_draw_desc* fr) {
  float light[3], eye[3], fwd[3];
  _tlod_view_vectors(fr, light, eye, fwd);
  for (int t = 0; t < VARIANT_COUNT * TYPE_COUNT; t++) {
    gl_programs* ps = &d->programs[t / VARIANT_COUNT][t % VARIANT_COUNT];
    if (!ps->linked) continue;
    const gl_program* progs[4];
    for (int k = 0, n = programs_of(d, ps, progs); k < n; k++) {
      const gl_program* p = progs[k];
      glProgramUniform3fv(p->id, p->loc[U_LIGHT_DIR], 1, light);
      glProgramUniform1ui(p->id, p->loc[U_DEBUG], (uint32_t)fr->debug);
      glProgramUniform3fv(p->id, p->loc[U_EYE], 1, eye);
      glProgramUniform3fv(p->id, p->loc[U_FORWARD], 1, fwd);
      glProgramUniform1ui(p->id, p->loc[U_ORTHO], fr->proj[15] == 1.0f ? 1u : 0u);
    }
  }
}

static void set_item_uniforms(const gl_device* d, const gl_programs* ps, const _tlod_item_shading* sh,
                              const tlod_draw_item* it, const gl_surface* gs) {
  const gl_program* progs[4];
  uint32_t texcoord = it->base_color_texture ? it->base_color_texcoord : TLOD_SHADER_MAX_ATTRIBUTES;
  float cutoff = it->has_alpha_cutoff ? it->alpha_cutoff : 0.5f;
  for (int k = 0, n = programs_of(d, ps, progs); k < n; k++) {
    const gl_program* p = progs[k];
    glProgramUniformMatrix4fv(p->id, p->loc[U_VIEW_PROJ], 1, GL_FALSE, sh->mvp);
    glProgramUniformMatrix4fv(p->id, p->loc[U_MODEL], 1, GL_FALSE, sh->model);
    glProgramUniformMatrix3fv(p->id, p->loc[U_NORMAL_MATRIX], 1, GL_FALSE, sh->normal_matrix);
    glProgramUniform4fv(p->id, p->loc[U_BASE_COLOR], 1, sh->color);
    glProgramUniform1f(p->id, p->loc[U_ALPHA_CUTOFF], cutoff);
    glProgramUniform1ui(p->id, p->loc[U_TEXCOORD], texcoord);
    glProgramUniform1ui(p->id, p->loc[U_ATTRIBUTE_COUNT], gs->attribute_count);
  }
}

/* The item's fixed-function state: culling, blending and depth writes, its
 * texture on TLOD_TEXTURE_UNIT_BASE_COLOR (the active unit while drawing). */
static void set_item_state(const _tlod_draw_ref* it) {
  const tlod_draw_item* item = it->item;
  if (item->cull_back_faces) {
    glEnable(GL_CULL_FACE);
  } else {
    glDisable(GL_CULL_FACE);
  }
  bool blend = item->blend == TLOD_BLEND_BLEND;
  if (blend) {
    glEnable(GL_BLEND);
  } else {
    glDisable(GL_BLEND);
  }
  glDepthMask(blend ? GL_FALSE : GL_TRUE);
  const gl_texture* t = it->texture_state;
  glBindTexture(GL_TEXTURE_2D, t ? t->texture : 0);
  glBindSampler(TLOD_TEXTURE_UNIT_BASE_COLOR, t ? t->sampler : 0);
}

static void set_debug(const gl_device* d, const gl_programs* ps, uint32_t debug) {
  const gl_program* progs[4];
  for (int k = 0, n = programs_of(d, ps, progs); k < n; k++)
    glProgramUniform1ui(progs[k]->id, progs[k]->loc[U_DEBUG], debug);
}

/* One instanced draw per refinement pattern, then the item's strips in one draw. */
static uint32_t issue_draws(const gl_device* d, const gl_programs* ps, const tlod_draw_list* dl,
                            const _tlod_stage_range* range, uint64_t* vertices) {
  uint32_t calls = 0;
  const gl_program* p = &ps->pattern;
  glUseProgram(p->id);
  glBindVertexArray(d->vao_pattern);
  for (uint32_t k = 0; k < dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape;
    glProgramUniform1ui(p->id, p->loc[U_FIRST_INSTANCE], range->instance_first + bk->first);
    glProgramUniform1ui(p->id, p->loc[U_SHAPE_BASE], d->shape_base[sh]);
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)d->index_count[sh][bk->level], GL_UNSIGNED_INT,
                            (const void*)(sizeof(uint32_t) * (size_t)d->index_first[sh][bk->level]),
                            (GLsizei)bk->count);
    *vertices += (uint64_t)tlod_pattern_vertex_count(bk->shape, bk->level) * bk->count;
    calls++;
  }
  if (range->index_count) {
    /* Indexed: each strip point is shaded once, not once per triangle. */
    glUseProgram(ps->strip.id);
    glBindVertexArray(d->vao_strip);
    glDrawElements(GL_TRIANGLES, (GLsizei)range->index_count, GL_UNSIGNED_INT,
                   (const void*)(sizeof(uint32_t) * (size_t)range->index_first));
    *vertices += range->ref_count;
    calls++;
  }
  return calls;
}

/* Hardware path: per bucket, draws of whole patches kept under 65,536
 * tessellated vertices each (_tlod_tess_batch). */
static uint32_t issue_tess_draws(const gl_device* d, const gl_programs* ps, const tlod_draw_list* dl,
                                 const _tlod_stage_range* range, uint64_t* vertices) {
  uint32_t calls = 0;
  for (uint32_t k = 0; k < dl->bucket_count; k++) {
    const tlod_draw_bucket* bk = &dl->buckets[k];
    uint32_t sh = (uint32_t)bk->shape, corners = sh ? 4u : 3u;
    const gl_program* p = &ps->tess[sh];
    glUseProgram(p->id);
    glBindVertexArray(d->vao_pattern);
    glPatchParameteri(GL_PATCH_VERTICES, (GLint)corners);
    glProgramUniform1ui(p->id, p->loc[U_CORNERS], corners);
    uint32_t end = range->instance_first + bk->first + bk->count;
    for (uint32_t start = range->instance_first + bk->first, next; start < end; start = next) {
      next = _tlod_tess_batch(d->st.instances, start, end, corners, vertices);
      glProgramUniform1ui(p->id, p->loc[U_FIRST_INSTANCE], start);
      glDrawArrays(GL_PATCHES, 0, (GLsizei)((next - start) * corners));
      calls++;
    }
  }
  return calls;
}

static void read_query(gl_device* d) {
  /* The query of QUERY_RING - 1 draws ago: reading it never stalls. */
  if (d->frame < QUERY_RING) return;
  GLuint q = d->queries[(d->frame + 1) % QUERY_RING];
  GLint ready = 0;
  glGetQueryObjectiv(q, GL_QUERY_RESULT_AVAILABLE, &ready);
  if (!ready) return;
  GLuint64 ns = 0, prims = 0;
  glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
  glGetQueryObjectui64v(d->prim_queries[(d->frame + 1) % QUERY_RING], GL_QUERY_RESULT, &prims);
  d->stats->gpu_ms = (double)ns * 1e-6;
  d->stats->gpu_draw = d->query_draw[(d->frame + 1) % QUERY_RING];
  d->stats->gl.primitives_generated = prims;
}

static const float* gl_surface_center(const void* surface_state) { return ((const gl_surface*)surface_state)->center; }

/* The variant an item draws with: PLAIN unless its fragments read a
 * texture, or (a fragment hook) its mesh's attributes. */
static int variant_of(const gl_device* d, const _tlod_draw_ref* it) {
  const gl_surface* gs = it->surface_state;
  return _tlod_stage_variant(d->fragment_hook != NULL, gs->attribute_count, it->item);
}

/* CPU-mesh mode: the item's mesh (evaluated again only when its list,
 * surface or mesh changed), then one indexed draw (two with wireframe). */
static tlod_result draw_mesh(gl_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* it, const gl_programs* ps,
                             tlod_draw_item_stats* st) {
  gl_surface* gs = it->surface_state;
  bool evaluated = false;
  double t0 = tlod_now_ms();
  tlod_result r = _tlod_gl_mesh_update(d->ctx, d->patterns, it, &gs->mesh, &evaluated, &d->stats->mesh_bytes);
  if (r != TLOD_SUCCESS) return r;
  if (evaluated) d->stats->mesh_evaluations++, d->stats->mesh_eval_ms += tlod_now_ms() - t0;
  glUseProgram(ps->mesh.id);
  _tlod_gl_mesh_draw(&gs->mesh);
  st->draw_calls = 1;
  if (fr->wireframe) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    set_debug(d, ps, 4u);
    _tlod_gl_mesh_draw(&gs->mesh);
    set_debug(d, ps, (uint32_t)fr->debug);
    st->draw_calls = 2;
  }
  const tlod_cpu_mesh* c = gs->mesh.eval.cpu;
  st->triangles = c ? (uint64_t)c->triangle_count + c->folds_skipped : 0u;
  st->vertices = c ? c->vertex_count : 0u;
  return TLOD_SUCCESS;
}

/* Item k: its patterns and strips, then (wireframe) its edges over them. */
static tlod_result draw_item(gl_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* it, uint32_t k,
                             tlod_draw_item_stats* st) {
  double t0 = tlod_now_ms();
  const gl_surface* gs = it->surface_state;
  const gl_programs* ps = &d->programs[gs->type][variant_of(d, it)];
  const tlod_draw_list* dl = it->item->draw_list;
  const _tlod_stage_range* range = &d->st.ranges[k];
  _tlod_item_shading sh;
  _tlod_item_shading_of(fr, it->item, &sh);
  set_item_uniforms(d, ps, &sh, it->item, gs);
  set_item_state(it);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_PATCHES, gs->buf_patches);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_ATTRIBUTES, gs->buf_attributes);
  if (fr->wireframe) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  if (ps->mesh.id) {
    tlod_result r = draw_mesh(d, fr, it, ps, st);
    st->cpu_ms += tlod_now_ms() - t0;
    return r;
  }
  uint64_t vertices = 0;
  uint32_t calls =
      d->hardware ? issue_tess_draws(d, ps, dl, range, &vertices) : issue_draws(d, ps, dl, range, &vertices);
  if (fr->wireframe) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    set_debug(d, ps, 4u);
    uint64_t unused = 0;
    calls += d->hardware ? issue_tess_draws(d, ps, dl, range, &unused) : issue_draws(d, ps, dl, range, &unused);
    set_debug(d, ps, (uint32_t)fr->debug);
  }
  st->triangles = d->hardware ? dl->pattern_triangles : dl->pattern_triangles + range->index_count / 3;
  st->vertices = vertices;
  st->draw_calls = calls;
  st->cpu_ms += tlod_now_ms() - t0;
  return TLOD_SUCCESS;
}

/* The FULL and MASK programs of the surface types of this draw's items
 * that need them, linked the first time (they bind nothing: DSA and
 * glProgramUniform only). */
static tlod_result link_lazy_programs(gl_device* d, const tlod_draw_desc* fr, const _tlod_draw_ref* items) {
  for (uint32_t k = 0; k < fr->item_count; k++) {
    tlod_surface_type t = ((const gl_surface*)items[k].surface_state)->type;
    int v = variant_of(d, &items[k]);
    if (d->programs[t][v].linked) continue;
    double t0 = tlod_now_ms();
    tlod_result r = build_programs(d, t, v);
    d->stats->gl.mask_link_ms += tlod_now_ms() - t0;
    if (r != TLOD_SUCCESS) return r;
  }
  return TLOD_SUCCESS;
}

static tlod_result gl_draw(void* state, const tlod_draw_desc* fr, const _tlod_draw_ref* items,
                           tlod_draw_item_stats* item_stats) {
  gl_device* d = state;
  double t0 = tlod_now_ms();
  tlod_result r = link_lazy_programs(d, fr, items);
  if (r != TLOD_SUCCESS) return r;
  gl_saved_state saved;
  _tlod_gl_save_state(&saved);
  r = stage(d, fr, items, item_stats);
  if (r == TLOD_SUCCESS) r = _tlod_stage_order(d->ctx, &d->st, "gl device", fr, items, gl_surface_center);
  if (r != TLOD_SUCCESS) {
    _tlod_gl_restore_state(&saved);
    return r;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_PATTERN, d->buf_pattern);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_INSTANCES, d->buf_instances);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TLOD_BINDING_STRIPS, d->buf_strips);
  glViewport((GLint)fr->viewport[0], (GLint)fr->viewport[1], (GLsizei)fr->viewport[2], (GLsizei)fr->viewport[3]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
  glBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glActiveTexture(GL_TEXTURE0 + TLOD_TEXTURE_UNIT_BASE_COLOR);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  /* An engine may be timing the frame around us: one query per target can
   * be active, so ours stay out of its way then. */
  GLint busy_time = 0, busy_prims = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &busy_time);
  glGetQueryiv(GL_PRIMITIVES_GENERATED, GL_CURRENT_QUERY, &busy_prims);
  bool timed = !busy_time && !busy_prims;
  if (timed) {
    d->query_draw[d->frame % QUERY_RING] = d->stats->draws + 1; /* the dispatch counts this draw on success */
    glBeginQuery(GL_TIME_ELAPSED, d->queries[d->frame % QUERY_RING]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, d->prim_queries[d->frame % QUERY_RING]);
  }
  set_view_uniforms(d, fr);
  d->stats->mesh_evaluations = 0, d->stats->mesh_eval_ms = 0.0, d->stats->mesh_bytes = 0;
  for (uint32_t j = 0; j < fr->item_count && r == TLOD_SUCCESS; j++) {
    uint32_t k = d->st.order[j];
    r = draw_item(d, fr, &items[k], k, &item_stats[k]);
  }
  if (timed) {
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TIME_ELAPSED);
    read_query(d);
    d->frame++;
  }
  _tlod_gl_restore_state(&saved);
  d->stats->cpu_ms = tlod_now_ms() - t0;
  if (r != TLOD_SUCCESS) return r;
  if (fr->finish) {
    glFinish();
    d->stats->wall_ms = tlod_now_ms() - t0;
  }
  return TLOD_SUCCESS;
}

static tlod_result gl_create_texture(void* state, const tlod_texture_desc* desc, void** texture_state) {
  gl_device* d = state;
  return _tlod_gl_texture_create(d->ctx, desc, (gl_texture**)texture_state);
}

static void gl_destroy_texture(void* state, void* texture_state) {
  gl_device* d = state;
  _tlod_gl_texture_destroy(d->ctx, texture_state);
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

const _tlod_device_vtbl _tlod_gl_device_vtbl = {.create = gl_create,
                                                .destroy = gl_destroy,
                                                .create_surface = gl_create_surface,
                                                .update_surface = gl_update_surface,
                                                .destroy_surface = gl_destroy_surface,
                                                .draw = gl_draw,
                                                .read_image = gl_read_image,
                                                .times_draws = true,
                                                .create_texture = gl_create_texture,
                                                .destroy_texture = gl_destroy_texture};
