/* tesslod::gl -- shader compilation with the driver's log on failure. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include "gl_internal.h"

static const char* stage_name(GLenum stage) {
  switch (stage) {
  case GL_VERTEX_SHADER:
    return "vertex";
  case GL_TESS_CONTROL_SHADER:
    return "tessellation control";
  case GL_TESS_EVALUATION_SHADER:
    return "tessellation evaluation";
  default:
    return "fragment";
  }
}

/* Writes the driver's log with the lines of the fragment stage's material
 * (the device's fragment hook, numbered from TLOD_GL_HOOK_LINE by a #line
 * directive) named "fragment_hook:LINE": Mesa writes "S:LINE(COL): ...",
 * NVIDIA "S(LINE) : ..."; the source string number S is not used (Mesa
 * applies a #line string number to some messages only). */
static void name_sources(const char* log, char* out, size_t size) {
  size_t o = 0;
  for (const char* p = log; *p && o + 1 < size; p++) {
    const char* q = p;
    while (*q >= '0' && *q <= '9')
      q++;
    char* end = NULL;
    unsigned long line = (q > p && (*q == ':' || *q == '(')) ? strtoul(q + 1, &end, 10) : 0;
    bool line_start = p == log || p[-1] == '\n';
    if (line_start && line >= TLOD_GL_HOOK_LINE && end) {
      o += (size_t)snprintf(out + o, size - o, "fragment_hook%c%lu", *q, line - TLOD_GL_HOOK_LINE + 1);
      if (o >= size) break;
      p = end - 1;
      continue;
    }
    out[o++] = *p;
  }
  out[o < size ? o : size - 1] = '\0';
}

static GLuint compile(GLenum stage, const char* const* src, int count, char* error, size_t error_size) {
  GLuint sh = glCreateShader(stage);
  glShaderSource(sh, count, src, NULL);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = "", named[1200] = "";
    glGetShaderInfoLog(sh, sizeof(log), NULL, log);
    if (stage == GL_FRAGMENT_SHADER) name_sources(log, named, sizeof(named));
    snprintf(error, error_size, "%s shader: %s", stage_name(stage), stage == GL_FRAGMENT_SHADER ? named : log);
    glDeleteShader(sh);
    return 0;
  }
  return sh;
}

GLuint _tlod_gl_program_tess(const char* const* stages[4], const int counts[4], char* error, size_t error_size) {
  static const GLenum kinds[4] = {GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER, GL_TESS_EVALUATION_SHADER,
                                  GL_FRAGMENT_SHADER};
  GLuint sh[4] = {0};
  bool ok = true;
  for (int i = 0; i < 4 && ok; i++) {
    if (!stages[i]) continue;
    sh[i] = compile(kinds[i], stages[i], counts[i], error, error_size);
    ok = sh[i] != 0;
  }
  GLuint prog = ok ? glCreateProgram() : 0;
  for (int i = 0; i < 4; i++) {
    if (sh[i] && prog) glAttachShader(prog, sh[i]);
  }
  if (prog) glLinkProgram(prog);
  for (int i = 0; i < 4; i++) {
    if (sh[i]) glDeleteShader(sh[i]);
  }
  if (!prog) return 0;
  GLint linked = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[1024] = "";
    glGetProgramInfoLog(prog, sizeof(log), NULL, log);
    snprintf(error, error_size, "link: %s", log);
    glDeleteProgram(prog);
    return 0;
  }
  return prog;
}

GLuint _tlod_gl_program(const char* const* vert, int vert_count, const char* const* frag, int frag_count, char* error,
                        size_t error_size) {
  const char* const* stages[4] = {vert, NULL, NULL, frag};
  const int counts[4] = {vert_count, 0, 0, frag_count};
  return _tlod_gl_program_tess(stages, counts, error, error_size);
}
