/* Private to the GPU backends (tesslod::gl, tesslod::vulkan): the files of
 * backends/shaders as C strings, generated at configure time by
 * cmake/tesslod_embed.cmake, and how a program's stages concatenate them
 * (shader_program.c). Both compiled once into the object library
 * tlod_shader_sources, which both backends take: one copy, one order. */
#ifndef TESSLOD_SHADER_SOURCES_H
#define TESSLOD_SHADER_SOURCES_H

#include <stdbool.h>
#include <stddef.h>

#include "tesslod/core.h"

extern const char* const _tlod_shader_layout;
extern const char* const _tlod_shader_uniforms;
extern const char* const _tlod_shader_common;
extern const char* const _tlod_shader_phong;
extern const char* const _tlod_shader_pn;
extern const char* const _tlod_shader_flat;
extern const char* const _tlod_shader_quadratic;
extern const char* const _tlod_shader_pattern_vert;
extern const char* const _tlod_shader_strip_vert;
extern const char* const _tlod_shader_mesh_vert;
extern const char* const _tlod_shader_shade_frag;
extern const char* const _tlod_shader_attributes;
extern const char* const _tlod_shader_varyings;
extern const char* const _tlod_shader_material;
extern const char* const _tlod_shader_tess_vert;
extern const char* const _tlod_shader_tess_tesc;
extern const char* const _tlod_shader_tess_tese;

/* Every embedded file with its name in backends/shaders ("pattern.vert"). */
typedef struct _tlod_shader_file {
  const char* name;
  const char* text;
} _tlod_shader_file;
extern const _tlod_shader_file _tlod_shader_files[];
extern const int _tlod_shader_file_count;

/* ---- program assembly (shader_program.c) ---------------------------------- */

/* What a program variant compiles in: the defines after "#version 450 core". */
typedef struct _tlod_shader_variant {
  bool vulkan;            /* TLOD_VULKAN 1 (else GL) */
  int attribute_varyings; /* TLOD_ATTRIBUTE_VARYINGS: 0, or TLOD_SHADER_MAX_ATTRIBUTES (a hook's FULL/MASK) */
  bool texcoord;          /* TLOD_TEXCOORD: the FULL and MASK variants */
  bool mask;              /* TLOD_MASK: the MASK variant */
} _tlod_shader_variant;

#define _TLOD_SHADER_DEFINES_BYTES 200
/* "#version 450 core\n#define TLOD_GLSL 1\n..." for the variant, into out
 * (_TLOD_SHADER_DEFINES_BYTES). */
void _tlod_shader_defines(const _tlod_shader_variant* v, char out[_TLOD_SHADER_DEFINES_BYTES]);

/* "#define TLOD_CORNERS 3\n" or "... 4\n" (the hardware path's stages). */
const char* _tlod_shader_corners(int corners);

/* The evaluation file of a surface type (TLOD_SURFACE_DEFAULT: Phong). */
const char* _tlod_shader_surface(tlod_surface_type type);

#define _TLOD_SHADER_STAGE_SOURCES 9
/* A vertex-side stage in order: defines, corners (NULL: none), layout.h,
 * uniforms.glsl, common.glsl, attributes.glsl, varyings.glsl when last (the
 * stage feeds the fragment stage), the surface's file, main_src (one of
 * pattern.vert, strip.vert, tess.vert/.tesc/.tese). Returns the count. */
int _tlod_shader_vertex_side(const char* out[_TLOD_SHADER_STAGE_SOURCES], const char* defines, const char* corners,
                             const char* surface, bool last, const char* main_src);

#define _TLOD_SHADER_FRAGMENT_SOURCES 6
/* The fragment stage: defines, layout.h, uniforms.glsl, shade.frag,
 * before_hook (NULL: none; GL puts its #line directive here), then the
 * fragment hook (NULL: material.glsl). Returns the count. */
int _tlod_shader_fragment(const char* out[_TLOD_SHADER_FRAGMENT_SOURCES], const char* defines, const char* before_hook,
                          const char* hook);

/* The stages of a program variant, as the devices build them. */
typedef enum _tlod_shader_stage {
  _TLOD_SHADER_VERTEX = 0,
  _TLOD_SHADER_TESS_CONTROL,
  _TLOD_SHADER_TESS_EVALUATION,
  _TLOD_SHADER_FRAGMENT
} _tlod_shader_stage;

/* Receives one stage: its kind, strings and their names (_tlod_shader_names);
 * false stops the walk. */
typedef bool (*_tlod_shader_stage_fn)(void* user, _tlod_shader_stage stage, const char* const* src,
                                      const char* const* names, int count);

/* Every stage of the programs of surface type type in variant v with
 * fragment hook hook (NULL: the built-in material): the pattern and strip
 * vertex stages, the fragment stage, and with hardware the tessellation
 * path's vertex, control and evaluation stages for 3 then 4 corners; the
 * strings of the Vulkan device (no #line before the hook). src[0], the
 * defines, lives only during the call. Returns false when fn stopped. */
bool _tlod_shader_each_stage(tlod_surface_type type, const _tlod_shader_variant* v, const char* hook, bool hardware,
                             _tlod_shader_stage_fn fn, void* user);

/* Names for error messages of the strings of a stage: the file name of an
 * embedded file, "fragment_hook" for hook (may be NULL), "defines" for any
 * other string (the defines, corners, directives). */
void _tlod_shader_names(const char* const* sources, int count, const char* hook, const char** names);

#endif
