/* The order in which a device's programs concatenate the files of
 * backends/shaders (shader_sources.h): one list for GL and Vulkan. */
#include <stdio.h>

#include "shader_sources.h"

void _tlod_shader_defines(const _tlod_shader_variant* v, char out[_TLOD_SHADER_DEFINES_BYTES]) {
  snprintf(out, _TLOD_SHADER_DEFINES_BYTES,
           "#version 450 core\n#define TLOD_GLSL 1\n%s#define TLOD_ATTRIBUTE_VARYINGS %d\n#define TLOD_TEXCOORD %d\n"
           "#define TLOD_MASK %d\n",
           v->vulkan ? "#define TLOD_VULKAN 1\n" : "", v->attribute_varyings, v->texcoord ? 1 : 0, v->mask ? 1 : 0);
}

const char* _tlod_shader_corners(int corners) {
  return corners == 4 ? "#define TLOD_CORNERS 4\n" : "#define TLOD_CORNERS 3\n";
}

const char* _tlod_shader_surface(tlod_surface_type type) {
  switch (type) {
  case TLOD_SURFACE_PN:
    return _tlod_shader_pn;
  case TLOD_SURFACE_FLAT:
    return _tlod_shader_flat;
  case TLOD_SURFACE_QUADRATIC:
    return _tlod_shader_quadratic;
  default:
    return _tlod_shader_phong;
  }
}

int _tlod_shader_vertex_side(const char* out[_TLOD_SHADER_STAGE_SOURCES], const char* defines, const char* corners,
                             const char* surface, bool last, const char* main_src) {
  int n = 0;
  out[n++] = defines;
  if (corners) out[n++] = corners;
  out[n++] = _tlod_shader_layout;
  out[n++] = _tlod_shader_uniforms;
  out[n++] = _tlod_shader_common;
  out[n++] = _tlod_shader_attributes;
  if (last) out[n++] = _tlod_shader_varyings;
  out[n++] = surface;
  out[n++] = main_src;
  return n;
}

int _tlod_shader_fragment(const char* out[_TLOD_SHADER_FRAGMENT_SOURCES], const char* defines, const char* before_hook,
                          const char* hook) {
  int n = 0;
  out[n++] = defines;
  out[n++] = _tlod_shader_layout;
  out[n++] = _tlod_shader_uniforms;
  out[n++] = _tlod_shader_shade_frag;
  if (before_hook) out[n++] = before_hook;
  out[n++] = hook ? hook : _tlod_shader_material;
  return n;
}

static const char* file_name(const char* text) {
  for (int i = 0; i < _tlod_shader_file_count; i++) {
    if (_tlod_shader_files[i].text == text) return _tlod_shader_files[i].name;
  }
  return NULL;
}

void _tlod_shader_names(const char* const* sources, int count, const char* hook, const char** names) {
  for (int i = 0; i < count; i++) {
    const char* name = file_name(sources[i]);
    names[i] = name ? name : hook && sources[i] == hook ? "fragment_hook" : "defines";
  }
}

/* One vertex-side stage to fn, named. */
static bool vertex_side(_tlod_shader_stage_fn fn, void* user, _tlod_shader_stage stage, const char* defines,
                        int corners, const char* surface, bool last, const char* main_src) {
  const char *src[_TLOD_SHADER_STAGE_SOURCES], *names[_TLOD_SHADER_STAGE_SOURCES];
  int n =
      _tlod_shader_vertex_side(src, defines, corners ? _tlod_shader_corners(corners) : NULL, surface, last, main_src);
  _tlod_shader_names(src, n, NULL, names);
  return fn(user, stage, src, names, n);
}

bool _tlod_shader_each_stage(tlod_surface_type type, const _tlod_shader_variant* v, const char* hook, bool hardware,
                             _tlod_shader_stage_fn fn, void* user) {
  char d[_TLOD_SHADER_DEFINES_BYTES];
  _tlod_shader_defines(v, d);
  const char* surface = _tlod_shader_surface(type);
  const char *frag[_TLOD_SHADER_FRAGMENT_SOURCES], *names[_TLOD_SHADER_FRAGMENT_SOURCES];
  int nf = _tlod_shader_fragment(frag, d, NULL, hook);
  _tlod_shader_names(frag, nf, hook, names);
  bool go = vertex_side(fn, user, _TLOD_SHADER_VERTEX, d, 0, surface, true, _tlod_shader_pattern_vert) &&
            vertex_side(fn, user, _TLOD_SHADER_VERTEX, d, 0, surface, true, _tlod_shader_strip_vert) &&
            fn(user, _TLOD_SHADER_FRAGMENT, frag, names, nf);
  for (int c = 3; c <= 4 && go && hardware; c++) {
    go = vertex_side(fn, user, _TLOD_SHADER_VERTEX, d, c, surface, false, _tlod_shader_tess_vert) &&
         vertex_side(fn, user, _TLOD_SHADER_TESS_CONTROL, d, c, surface, false, _tlod_shader_tess_tesc) &&
         vertex_side(fn, user, _TLOD_SHADER_TESS_EVALUATION, d, c, surface, true, _tlod_shader_tess_tese);
  }
  return go;
}
