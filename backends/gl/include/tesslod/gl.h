/*
 * tesslod/gl.h -- OpenGL interop facts of the "gl" backend (tesslod/backend.h).
 *
 * An engine that shares the context needs to know which binding points the
 * backend uses during tlod_backend_draw() (they are saved and restored, so
 * this matters only to code running inside the same draw, e.g. a debugger).
 */
#ifndef TESSLOD_GL_H
#define TESSLOD_GL_H

/* Shader storage binding points used while drawing. */
#define TLOD_GL_BINDING_PATCHES 0   /* per patch: corners, normals, weld ids, PN control data */
#define TLOD_GL_BINDING_PATTERNS 1  /* pattern vertices of both shapes */
#define TLOD_GL_BINDING_INSTANCES 2 /* per visible patch: level, geomorph blends, edge levels */
#define TLOD_GL_BINDING_STRIPS 3    /* per connection strip: patches, edges, levels, blends */

/* GLSL version of the shaders (backends/shaders), compiled at upload. */
#define TLOD_GL_GLSL_VERSION 450

#endif
