/* Private to tesslod::gl. */
#ifndef TESSLOD_GL_INTERNAL_H
#define TESSLOD_GL_INTERNAL_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "internal.h"
#include "tesslod/backend.h"

/* std430 mirrors of backends/shaders/common.glsl. */
typedef struct gl_patch {
  float p[4][4]; /* xyz + alpha */
  float n[4][4];
  uint32_t weld[4];
  uint32_t info[4];
  float b[10][4];
  float mn[3][4];
} gl_patch;

typedef struct gl_pattern_vertex {
  float uv[2];
  uint32_t parent0, parent1;
  uint32_t code, param;
  uint32_t pad[2];
} gl_pattern_vertex;

typedef struct gl_instance {
  uint32_t patch, level;
  uint32_t edge_levels; /* hardware path: outer level exponent per edge, 8 bits each */
  uint32_t pad;
  float morph[4];
  float morph_e3[4];
} gl_instance;

typedef struct gl_strip {
  uint32_t patch_a, patch_b, edges, levels;
  float morph[4];
} gl_strip;

_Static_assert(sizeof(gl_patch) == 23 * 16, "gl_patch must match the std430 Patch");
_Static_assert(sizeof(gl_pattern_vertex) == 32, "gl_pattern_vertex must match PatternVertex");
_Static_assert(sizeof(gl_instance) == 48, "gl_instance must match Instance");
_Static_assert(sizeof(gl_strip) == 32, "gl_strip must match Strip");

/* The GL state the backend touches, saved before a draw and restored after. */
typedef struct gl_saved_state {
  GLint program, vao, array_buffer, element_buffer, ssbo, ubo, indirect;
  GLint ssbo_binding[4];
  GLint64 ssbo_start[4], ssbo_size[4]; /* glBindBufferRange ranges; size 0 == whole buffer */
  GLint polygon_mode[2], cull_mode, depth_func, viewport[4];
  GLboolean cull, depth_test, depth_mask, blend, offset_fill;
  GLfloat offset_factor, offset_units;
  GLint patch_vertices;
} gl_saved_state;

void _tlod_gl_save_state(gl_saved_state* s);
void _tlod_gl_restore_state(const gl_saved_state* s);

/* Compiles and links a program from the shader sources; on failure writes
 * the driver's log to error and returns 0. */
GLuint _tlod_gl_program(const char* const* vert, int vert_count, const char* const* frag, int frag_count, char* error,
                        size_t error_size);
/* The same with tessellation control and evaluation stages. */
GLuint _tlod_gl_program_tess(const char* const* stages[4], const int counts[4], char* error, size_t error_size);

/* Embedded shader sources (generated from backends/shaders at configure time). */
extern const char* const _tlod_shader_common;
extern const char* const _tlod_shader_phong;
extern const char* const _tlod_shader_pn;
extern const char* const _tlod_shader_flat;
extern const char* const _tlod_shader_pattern_vert;
extern const char* const _tlod_shader_strip_vert;
extern const char* const _tlod_shader_shade_frag;
extern const char* const _tlod_shader_tess_vert;
extern const char* const _tlod_shader_tess_tesc;
extern const char* const _tlod_shader_tess_tese;

extern const tlod_backend_vtbl _tlod_gl_vtbl;

#endif
