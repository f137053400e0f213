/* tesslod::gl -- shader compilation with the driver's log on failure. */
#include <stdio.h>

#include "gl_internal.h"

static GLuint compile(GLenum stage, const char* const* src, int count, char* error, size_t error_size) {
  GLuint sh = glCreateShader(stage);
  glShaderSource(sh, count, src, NULL);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = "";
    glGetShaderInfoLog(sh, sizeof(log), NULL, log);
    snprintf(error, error_size, "%s shader: %s", stage == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    glDeleteShader(sh);
    return 0;
  }
  return sh;
}

GLuint _tlod_gl_program(const char* const* vert, int vert_count, const char* const* frag, int frag_count, char* error,
                        size_t error_size) {
  GLuint vs = compile(GL_VERTEX_SHADER, vert, vert_count, error, error_size);
  GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, frag, frag_count, error, error_size) : 0;
  if (!vs || !fs) {
    if (vs) glDeleteShader(vs);
    return 0;
  }
  GLuint prog = glCreateProgram();
  glAttachShader(prog, vs);
  glAttachShader(prog, fs);
  glLinkProgram(prog);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[1024] = "";
    glGetProgramInfoLog(prog, sizeof(log), NULL, log);
    snprintf(error, error_size, "link: %s", log);
    glDeleteProgram(prog);
    return 0;
  }
  return prog;
}
