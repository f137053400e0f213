/* tesslod::gl -- saving and restoring the engine's GL state around a draw
 * (the documented list in tesslod/gl.h). */
#include "gl_internal.h"

void _tlod_gl_save_state(gl_saved_state* s) {
  glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s->ssbo);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s->ubo);
  glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &s->indirect);
  for (GLuint i = 0; i < TLOD_BINDING_COUNT; i++) {
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &s->ssbo_binding[i]);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &s->ssbo_start[i]);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &s->ssbo_size[i]);
  }
  glGetIntegerv(GL_POLYGON_MODE, s->polygon_mode);
  glGetIntegerv(GL_CULL_FACE_MODE, &s->cull_mode);
  glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
  glGetIntegerv(GL_VIEWPORT, s->viewport);
  s->cull = glIsEnabled(GL_CULL_FACE);
  s->depth_test = glIsEnabled(GL_DEPTH_TEST);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
  s->blend = glIsEnabled(GL_BLEND);
  s->offset_fill = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &s->offset_factor);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &s->offset_units);
  glGetIntegerv(GL_PATCH_VERTICES, &s->patch_vertices);
  glGetIntegerv(GL_FRONT_FACE, &s->front_face);
  glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src_rgb);
  glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst_rgb);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src_alpha);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst_alpha);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend_eq_rgb);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend_eq_alpha);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
  /* Per unit: read on the device's unit, the engine's active unit restored after. */
  glActiveTexture(GL_TEXTURE0 + TLOD_TEXTURE_UNIT_BASE_COLOR);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->texture_2d);
  glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler);
  glActiveTexture((GLenum)s->active_texture);
}

static void set_enabled(GLenum cap, GLboolean on) {
  if (on) {
    glEnable(cap);
  } else {
    glDisable(cap);
  }
}

void _tlod_gl_restore_state(const gl_saved_state* s) {
  glUseProgram((GLuint)s->program);
  /* The element buffer belongs to the VAO: binding the VAO restores it. */
  glBindVertexArray((GLuint)s->vao);
  glBindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
  /* An engine may have bound a range (glBindBufferRange): BindBufferBase
   * would widen it to the whole buffer. */
  for (GLuint i = 0; i < TLOD_BINDING_COUNT; i++) {
    if (s->ssbo_binding[i] && s->ssbo_size[i] > 0)
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, (GLuint)s->ssbo_binding[i], (GLintptr)s->ssbo_start[i],
                        (GLsizeiptr)s->ssbo_size[i]);
    else
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, (GLuint)s->ssbo_binding[i]);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, (GLuint)s->ssbo);
  glBindBuffer(GL_UNIFORM_BUFFER, (GLuint)s->ubo);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, (GLuint)s->indirect);
  glPolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
  glCullFace((GLenum)s->cull_mode);
  glDepthFunc((GLenum)s->depth_func);
  glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
  set_enabled(GL_CULL_FACE, s->cull);
  set_enabled(GL_DEPTH_TEST, s->depth_test);
  glDepthMask(s->depth_mask);
  set_enabled(GL_BLEND, s->blend);
  set_enabled(GL_POLYGON_OFFSET_FILL, s->offset_fill);
  glPolygonOffset(s->offset_factor, s->offset_units);
  glPatchParameteri(GL_PATCH_VERTICES, s->patch_vertices);
  glFrontFace((GLenum)s->front_face);
  glBlendFuncSeparate((GLenum)s->blend_src_rgb, (GLenum)s->blend_dst_rgb, (GLenum)s->blend_src_alpha,
                      (GLenum)s->blend_dst_alpha);
  glBlendEquationSeparate((GLenum)s->blend_eq_rgb, (GLenum)s->blend_eq_alpha);
  /* Only the 2D target of the unit: glBindTextureUnit would unbind the others. */
  glActiveTexture(GL_TEXTURE0 + TLOD_TEXTURE_UNIT_BASE_COLOR);
  glBindTexture(GL_TEXTURE_2D, (GLuint)s->texture_2d);
  glBindSampler(TLOD_TEXTURE_UNIT_BASE_COLOR, (GLuint)s->sampler);
  glActiveTexture((GLenum)s->active_texture);
}
