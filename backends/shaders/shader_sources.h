/* Private to the GPU backends (tesslod::gl, tesslod::vulkan): the files of
 * backends/shaders as C strings, generated at configure time by
 * cmake/tesslod_embed.cmake into one object library (tlod_shader_sources)
 * that both backends take. The order a program concatenates them in is
 * layout.h's header comment and docs/shaders.md. */
#ifndef TESSLOD_SHADER_SOURCES_H
#define TESSLOD_SHADER_SOURCES_H

extern const char* const _tlod_shader_layout;
extern const char* const _tlod_shader_uniforms;
extern const char* const _tlod_shader_common;
extern const char* const _tlod_shader_phong;
extern const char* const _tlod_shader_pn;
extern const char* const _tlod_shader_flat;
extern const char* const _tlod_shader_pattern_vert;
extern const char* const _tlod_shader_strip_vert;
extern const char* const _tlod_shader_shade_frag;
extern const char* const _tlod_shader_attributes;
extern const char* const _tlod_shader_varyings;
extern const char* const _tlod_shader_material;
extern const char* const _tlod_shader_tess_vert;
extern const char* const _tlod_shader_tess_tesc;
extern const char* const _tlod_shader_tess_tese;

#endif
