/*
 * tesslod/gl.h -- the "gl" device (module tesslod::gl): what it makes in
 * and changes on an engine's OpenGL context. The API is tesslod/backend.h
 * (tlod_device_create with .backend = "gl"); this header holds the GL facts.
 *
 * WHAT IT DOES
 *   Draws the items of tlod_device_draw() with OpenGL 4.5 core into the
 *   context current on the calling thread and the framebuffer bound there:
 *   each patch is drawn as an instance of its level's refinement pattern,
 *   every vertex evaluating the surface in the vertex shader through the
 *   canonical edge function; connection strips fill level changes; vertices
 *   first inserted at the drawn level geomorph. Timer and primitive queries
 *   are read a few draws late (never stalling).
 *
 * DOES NOT
 *   - create or make current a context, or a framebuffer: the engine's (or
 *     the platform/ glue) are used as they are;
 *   - clear, present, or touch state outside the list below (scissor,
 *     stencil, colour mask, blend function, framebuffer bindings, textures,
 *     samplers stay as the engine set them);
 *   - begin queries while the engine has a GL_TIME_ELAPSED or
 *     GL_PRIMITIVES_GENERATED query active (gpu_ms then stays as it was).
 *
 * STEP BY STEP
 *   1. make a 4.5 core context current;
 *   2. tlod_device_create(ctx, &(tlod_device_desc){ .backend = "gl",
 *      .patterns = p, .gl = { .surface_types = 1u << TLOD_SURFACE_PHONG } },
 *      &dev): links the programs (two per surface type, four with
 *      .gl.hardware_tessellation) and uploads the pattern buffers, once;
 *   3. tlod_device_create_surface() per object: one storage buffer of
 *      tlod_patch_record (tlod_surface_patch_records()); no program work;
 *   4. tlod_device_draw() per view: three buffer uploads (instances, strips,
 *      strip references of all items), then per item a few draw calls;
 *   5. destroy surfaces and the device with the same context current.
 *
 * THREADING AND ALLOCATION
 *   GL calls are made only on the calling thread, inside the tlod_device_*
 *   calls. CPU staging goes through the context's allocator and is grown,
 *   never shrunk; GL storage of the per-draw buffers is orphaned and
 *   refilled each draw (glNamedBufferData + glNamedBufferSubData).
 *
 * GL OBJECTS
 *   Per device (tlod_device_create .. tlod_device_destroy):
 *     programs     pattern + strip per surface type in desc.gl.surface_types
 *                  (0 == flat, phong, pn), + two tessellation programs
 *                  (triangles, quads) per type with hardware_tessellation;
 *                  uniform locations looked up once, at link;
 *     buffers      pattern vertices (binding TLOD_GL_BINDING_PATTERNS) and
 *                  pattern indices (GL_STATIC_DRAW, uploaded once);
 *                  instances, strips, strip references (GL_STREAM_DRAW,
 *                  refilled every draw);
 *     vertex arrays  one for patterns (element buffer: the pattern
 *                  indices), one for strips (attribute 0: strip references);
 *     queries      4 GL_TIME_ELAPSED + 4 GL_PRIMITIVES_GENERATED (a ring).
 *   Per device surface: one buffer of patch records (GL_STATIC_DRAW),
 *   refilled by tlod_device_update_surface().
 *   All are created with DSA (glCreate*): making them binds nothing.
 *
 * GL STATE
 *   Saved and restored by tlod_device_draw(): current program, vertex
 *   array, array / shader-storage / uniform / draw-indirect buffer bindings
 *   (the element buffer belongs to the vertex array), shader-storage
 *   binding points 0-3 including bound ranges, polygon mode, cull face
 *   enable and mode, depth test enable and function, depth mask, blend
 *   enable, polygon offset fill enable and values, viewport,
 *   GL_PATCH_VERTICES. Set during the draw: depth test on with GL_LESS,
 *   depth writes on, culling and blending off, the viewport of the draw.
 *   tlod_device_read_image() saves and restores the pack alignment, pack
 *   row length and pixel pack buffer binding.
 *
 * BINDING POINTS
 *   Shader storage binding points used while drawing (the same values as
 *   backends/shaders/layout.h, shared by C and GLSL; checked at build time).
 */
#ifndef TESSLOD_GL_H
#define TESSLOD_GL_H

#include "tesslod/core.h" /* tlod_patch_record: the layout at TLOD_GL_BINDING_PATCHES */

#define TLOD_GL_BINDING_PATCHES 0    /* per patch: tlod_patch_record (corners, normals, weld ids, PN data) */
#define TLOD_GL_BINDING_PATTERNS 1   /* pattern vertices of both shapes */
#define TLOD_GL_BINDING_INSTANCES 2  /* per visible patch: level, geomorph blends, edge levels */
#define TLOD_GL_BINDING_STRIPS 3     /* per connection strip: patches, edges, levels, blends */
#define TLOD_GL_BINDING_ATTRIBUTES 4 /* per patch and corner: vec4 mesh attributes (tlod_mesh_patch_attributes) */

/* Texture unit of the base colour texture while drawing (sampler2D
 * u_base_color_texture of the fragment stage). */
#define TLOD_GL_TEXTURE_UNIT_BASE_COLOR 0

/* GLSL version of the shaders (backends/shaders), compiled at device creation. */
#define TLOD_GL_GLSL_VERSION 450

#endif
