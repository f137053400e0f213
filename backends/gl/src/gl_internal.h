/* Private to tesslod::gl. */
#ifndef TESSLOD_GL_INTERNAL_H
#define TESSLOD_GL_INTERNAL_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "device_internal.h"
#include "device_mesh.h"    /* the CPU-mesh mode's evaluation */
#include "layout.h"         /* backends/shaders: binding points and buffer structs, shared with GLSL */
#include "shader_sources.h" /* backends/shaders as C strings */
#include "tesslod/gl.h"

#if TLOD_GL_BINDING_PATCHES != TLOD_BINDING_PATCHES || TLOD_GL_BINDING_PATTERNS != TLOD_BINDING_PATTERN ||             \
    TLOD_GL_BINDING_INSTANCES != TLOD_BINDING_INSTANCES || TLOD_GL_BINDING_STRIPS != TLOD_BINDING_STRIPS ||            \
    TLOD_GL_BINDING_ATTRIBUTES != TLOD_BINDING_ATTRIBUTES ||                                                           \
    TLOD_GL_TEXTURE_UNIT_BASE_COLOR != TLOD_TEXTURE_UNIT_BASE_COLOR
#error "tesslod/gl.h and backends/shaders/layout.h disagree on the binding points"
#endif

/* The GL state the device touches, saved before a draw and restored after
 * (the list in tesslod/gl.h). */
typedef struct gl_saved_state {
  GLint program, vao, array_buffer, element_buffer, ssbo, ubo, indirect;
  GLint ssbo_binding[TLOD_BINDING_COUNT];
  GLint64 ssbo_start[TLOD_BINDING_COUNT],
      ssbo_size[TLOD_BINDING_COUNT]; /* glBindBufferRange ranges; size 0 == whole buffer */
  GLint polygon_mode[2], cull_mode, depth_func, viewport[4];
  GLboolean cull, depth_test, depth_mask, blend, offset_fill;
  GLfloat offset_factor, offset_units;
  GLint patch_vertices;
  GLint front_face, blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha, blend_eq_rgb, blend_eq_alpha;
  GLint active_texture, texture_2d, sampler; /* the last two: of TLOD_TEXTURE_UNIT_BASE_COLOR */
} gl_saved_state;

void _tlod_gl_save_state(gl_saved_state* s);
void _tlod_gl_restore_state(const gl_saved_state* s);

/* A texture and its sampler (gl_texture.c). */
typedef struct gl_texture {
  GLuint texture, sampler;
} gl_texture;

tlod_result _tlod_gl_texture_create(tlod_context* ctx, const tlod_texture_desc* desc, gl_texture** out);
void _tlod_gl_texture_destroy(tlod_context* ctx, gl_texture* t);

/* CPU-mesh mode (tlod_gpu_eval OFF): one device surface's evaluated mesh
 * and its GL copy (gl_mesh.c). Vertex buffer: positions, then normals. */
typedef struct gl_mesh {
  _tlod_item_mesh eval; /* the mesh and what it (and the buffers) were made from */
  GLuint vao, vertices, indices;
  uint32_t index_count;
} gl_mesh;

/* Evaluates item it's draw list into m and uploads it, unless it is the
 * one m holds (*evaluated false); the uploaded bytes are added to *bytes. */
tlod_result _tlod_gl_mesh_update(tlod_context* ctx, const tlod_patterns* p, const _tlod_draw_ref* it, gl_mesh* m,
                                 bool* evaluated, uint64_t* bytes);
/* One indexed draw of the mesh, with the program and state in place. */
void _tlod_gl_mesh_draw(const gl_mesh* m);
void _tlod_gl_mesh_free(tlod_context* ctx, gl_mesh* m);

/* The first line number of the fragment stage's material source (its
 * #line directive): the log's lines from here on are the hook's. */
#define TLOD_GL_HOOK_LINE 100001
#define TLOD_GL_HOOK_LINE_DIRECTIVE "\n#line 100001\n"

/* Compiles and links a program from the shader sources; on failure writes
 * the driver's log to error and returns 0. */
GLuint _tlod_gl_program(const char* const* vert, int vert_count, const char* const* frag, int frag_count, char* error,
                        size_t error_size);
/* The same with tessellation control and evaluation stages. */
GLuint _tlod_gl_program_tess(const char* const* stages[4], const int counts[4], char* error, size_t error_size);

#endif
