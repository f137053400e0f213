/* tesslod::gl -- textures: immutable storage, mipmaps generated, one
 * sampler object per texture with the desc's wrap and filters. */
#include "gl_internal.h"

static GLenum wrap_of(tlod_wrap w) {
  switch (w) {
  case TLOD_WRAP_CLAMP_TO_EDGE:
    return GL_CLAMP_TO_EDGE;
  case TLOD_WRAP_MIRRORED_REPEAT:
    return GL_MIRRORED_REPEAT;
  default:
    return GL_REPEAT;
  }
}

static GLenum min_filter_of(tlod_filter f, bool mipmaps) {
  if (f == TLOD_FILTER_NEAREST) return mipmaps ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST;
  return mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
}

static GLsizei mip_levels(uint32_t w, uint32_t h) {
  GLsizei n = 1;
  for (uint32_t m = w > h ? w : h; m > 1; m >>= 1)
    n++;
  return n;
}

/* Uploads the texels from client memory whatever the engine's unpack state
 * (a bound pixel unpack buffer, a row length or skips would redirect or
 * reshape them); the state is restored after. Rows go in as given: GL's
 * row 0 (t = 0) is the image's top row, so glTF coordinates (v = 0 at the
 * top) sample unchanged. */
static void upload(GLuint tex, const tlod_texture_desc* desc) {
  GLint align, row_length, skip_rows, skip_pixels, image_height, unpack_buffer;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &align);
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &row_length);
  glGetIntegerv(GL_UNPACK_SKIP_ROWS, &skip_rows);
  glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &skip_pixels);
  glGetIntegerv(GL_UNPACK_IMAGE_HEIGHT, &image_height);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
  glTextureSubImage2D(tex, 0, 0, 0, (GLsizei)desc->width, (GLsizei)desc->height, GL_RGBA, GL_UNSIGNED_BYTE,
                      desc->rgba8);
  glPixelStorei(GL_UNPACK_ALIGNMENT, align);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, row_length);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, skip_rows);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, skip_pixels);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, image_height);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)unpack_buffer);
}

/* No glGetError check: it would take an error the engine left pending; the
 * desc is validated, so only GL_OUT_OF_MEMORY could follow. */
tlod_result _tlod_gl_texture_create(tlod_context* ctx, const tlod_texture_desc* desc, gl_texture** out) {
  gl_texture* t = tlod_context_calloc(ctx, 1, sizeof(*t));
  if (!t) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "gl device: out of memory for a texture");
  bool mipmaps = !desc->mipmaps_off;
  GLsizei levels = mipmaps ? mip_levels(desc->width, desc->height) : 1;
  glCreateTextures(GL_TEXTURE_2D, 1, &t->texture);
  glTextureStorage2D(t->texture, levels, desc->srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, (GLsizei)desc->width,
                     (GLsizei)desc->height);
  upload(t->texture, desc);
  if (mipmaps) glGenerateTextureMipmap(t->texture);
  glCreateSamplers(1, &t->sampler);
  glSamplerParameteri(t->sampler, GL_TEXTURE_WRAP_S, (GLint)wrap_of(desc->wrap_s));
  glSamplerParameteri(t->sampler, GL_TEXTURE_WRAP_T, (GLint)wrap_of(desc->wrap_t));
  glSamplerParameteri(t->sampler, GL_TEXTURE_MIN_FILTER, (GLint)min_filter_of(desc->min_filter, mipmaps));
  glSamplerParameteri(t->sampler, GL_TEXTURE_MAG_FILTER,
                      desc->mag_filter == TLOD_FILTER_NEAREST ? GL_NEAREST : GL_LINEAR);
  *out = t;
  return TLOD_SUCCESS;
}

void _tlod_gl_texture_destroy(tlod_context* ctx, gl_texture* t) {
  glDeleteTextures(1, &t->texture);
  glDeleteSamplers(1, &t->sampler);
  tlod_context_free(ctx, t);
}
