/* consumer_gl.c: draws the consumer's surface with the installed "gl" backend in a headless EGL context;
 * returns 1 when the image holds the square and only the square. */
#ifndef CONSUMER_GL_H
#define CONSUMER_GL_H
#include <tesslod/core.h>
#include <tesslod/lod.h>
int consumer_gl(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns);
#endif
