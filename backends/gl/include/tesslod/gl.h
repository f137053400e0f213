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
 *   first inserted at the drawn level geomorph. Strips are drawn indexed
 *   (each strip point shaded once). A draw whose items' draw lists are
 *   those of the previous draw (same list and surface, and the same
 *   instances, strips and levels byte for byte) uploads nothing
 *   (stats.gl.buffer_streams 0). Timer and primitive queries are read a few
 *   draws late (never stalling).
 *   CPU-mesh mode (desc.gl.gpu_eval OFF, or AUTO on llvmpipe, softpipe or
 *   SwiftShader by GL_RENDERER; stats.cpu_mesh and gpu_eval_reason say
 *   which and why): each PLAIN item's draw list is evaluated on the CPU by
 *   tlod_cpu_tessellate_into (welded, with normals) into its device
 *   surface's mesh, uploaded and drawn with one glDrawElements (two with
 *   wireframe) through mesh.vert; evaluated and uploaded again only when the
 *   list, the surface generation or the mesh generation changed
 *   (stats.mesh_evaluations, mesh_eval_ms, mesh_bytes). The image matches
 *   the vertex-shader path within tests/gl/gl_parity_test.c's tolerances.
 *   Not carried: level and strip flag per vertex (the levels and strips
 *   debug views show level 0, no strip); textured, attribute-reading (with
 *   a hook) and MASK items and hardware_tessellation evaluate on the GPU.
 *
 * DOES NOT
 *   - create or make current a context, or a framebuffer: the engine's (or
 *     the platform/ glue) are used as they are;
 *   - clear, present, or touch state outside the list below (scissor,
 *     stencil, colour mask, framebuffer bindings, textures and samplers of
 *     other units and targets stay as the engine set them);
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
 *      tlod_patch_record (tlod_surface_patch_records()) and one of its
 *      mesh's attributes per patch corner; no program work;
 *      tlod_device_create_texture() per image;
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
 *                  (0 == flat, phong, pn, quadratic: 8 programs), + two
 *                  tessellation programs
 *                  (triangles, quads) per type with hardware_tessellation;
 *                  uniform locations looked up once, at link. These
 *                  (the PLAIN variant) carry no texture coordinates, no
 *                  texture fetch and no attribute reads: an item without
 *                  base_color_texture (and, with a fragment hook, of a mesh
 *                  without attributes) draws with them. Two more variants
 *                  are linked on demand, by the first draw with an item of
 *                  the surface type that needs them, each as many programs
 *                  again (stats gl.program_links; the link time goes to
 *                  gl.mask_link_ms): FULL, for the other non-MASK items
 *                  (v_texcoord, the fetch, with a hook every attribute),
 *                  and MASK, FULL plus the alpha test, for every
 *                  TLOD_BLEND_MASK item. A fragment that can discard loses
 *                  the early depth test and each varying or fetch costs
 *                  per fragment (llvmpipe: also when a uniform skips it;
 *                  docs/shaders.md),
 *                  so the default look carries none of them;
 *     buffers      pattern vertices (binding TLOD_GL_BINDING_PATTERNS) and
 *                  pattern indices (GL_STATIC_DRAW, uploaded once);
 *                  instances, strips, strip references, strip indices
 *                  (GL_STREAM_DRAW, refilled by a draw whose lists changed);
 *     vertex arrays  one for patterns (element buffer: the pattern
 *                  indices), one for strips (attribute 0: strip references;
 *                  element buffer: the strip indices);
 *     CPU-mesh mode: one mesh program per linked surface type (PLAIN), and
 *                  per device surface, at its first draw, a vertex array and
 *                  two buffers (positions then normals; indices, GL_STREAM_DRAW);
 *     queries      4 GL_TIME_ELAPSED + 4 GL_PRIMITIVES_GENERATED (a ring).
 *   Per device surface: one buffer of patch records and one of attributes
 *   (tlod_mesh_patch_attributes(); 16 bytes for a mesh without any), both
 *   GL_STATIC_DRAW, refilled by tlod_device_update_surface().
 *   Per texture (tlod_device_create_texture .. destroy_texture, or the
 *   device's destroy): one GL_TEXTURE_2D of immutable storage
 *   (glTextureStorage2D, GL_SRGB8_ALPHA8 when desc.srgb else GL_RGBA8, the
 *   full mipmap chain generated by glGenerateTextureMipmap unless
 *   mipmaps_off) and one sampler object with the desc's wrap modes and
 *   filters (minification with mipmaps: LINEAR -> LINEAR_MIPMAP_LINEAR,
 *   NEAREST -> NEAREST_MIPMAP_NEAREST). Rows are uploaded as given (top row
 *   first, at t = 0), so glTF texture coordinates sample unchanged. The
 *   upload saves, sets and restores the unpack alignment, row length, skip
 *   rows / pixels, image height and the pixel unpack buffer binding; it
 *   binds nothing else (DSA). glGetError is not read (it would take an
 *   error the engine left pending): an out-of-memory texture is GL's.
 *   All are created with DSA (glCreate*): making them binds nothing.
 *
 * GL STATE
 *   Saved and restored by tlod_device_draw(): current program, vertex
 *   array, array / shader-storage / uniform / draw-indirect buffer bindings
 *   (the element buffer belongs to the vertex array), shader-storage
 *   binding points 0-4 including bound ranges, polygon mode, cull face
 *   enable and mode, front face, depth test enable and function, depth
 *   mask, blend enable, blend function and equation (RGB and alpha each),
 *   polygon offset fill enable and values, viewport, GL_PATCH_VERTICES, the
 *   active texture unit, and on unit TLOD_GL_TEXTURE_UNIT_BASE_COLOR the
 *   GL_TEXTURE_2D binding and the sampler binding. Set during the draw:
 *   depth test on with GL_LESS, front face GL_CCW, cull face GL_BACK,
 *   blend function (GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
 *   GL_ONE_MINUS_SRC_ALPHA) with GL_FUNC_ADD, active unit
 *   TLOD_GL_TEXTURE_UNIT_BASE_COLOR, the viewport of the draw; per item:
 *   culling on with cull_back_faces, blending on and depth writes off for
 *   TLOD_BLEND_BLEND (else off / on), the item's texture and sampler (or 0)
 *   on the unit.
 *   tlod_device_read_image() saves and restores the pack alignment, pack
 *   row length and pixel pack buffer binding.
 *
 * FRAGMENT HOOKS (tlod_device_gl_desc.fragment_hook)
 *   The device's fragment stage is assembled as "#version 450 core" and
 *   its defines (TLOD_GLSL 1; TLOD_ATTRIBUTE_VARYINGS 8 with a hook in
 *   the FULL and MASK programs, else 0; TLOD_TEXCOORD 1 in those, 0 in
 *   PLAIN; TLOD_MASK 1 in the MASK programs) + layout.h + shade.frag +
 *   "#line 100001" + the hook (or, with NULL, the built-in material.glsl),
 *   so the hook is GLSL 4.50 core defining
 *       vec4 tlod_shade(tlod_fragment f);
 *   which returns the fragment's colour (straight alpha). It may define
 *   helper functions and constants, and read storage buffers or textures
 *   the engine binds at binding points / units the device does not use
 *   (binding points past TLOD_GL_BINDING_ATTRIBUTES, units other than
 *   TLOD_GL_TEXTURE_UNIT_BASE_COLOR). It must not define main, outputs or
 *   the names of shade.frag (u_*, v_*, o_color, level_color, fragment),
 *   and reads the base colour texture and attributes through f only (the
 *   PLAIN programs, which it is compiled into at creation, declare no
 *   v_texcoord, v_attr or u_base_color_texture).
 *   tlod_fragment:
 *       vec3 position;     world
 *       vec3 normal;       world, unit; flipped on back faces (gl_FrontFacing)
 *       vec3 light_dir;    world, unit, towards the light (tlod_draw_desc)
 *       vec3 eye;          world position of the camera
 *       vec4 base_color;   the item's colour times its base colour texture
 *                          sample (linear; sRGB textures decoded)
 *       vec4 attributes[8];  the mesh attributes interpolated over the
 *                          patch, (0, 0, 0, 0) past attribute_count, missing
 *                          components (0, 0, 0, 1)
 *       uint attribute_count;
 *       uint level;        refinement level (strips: the side's)
 *       bool strip;        a fragment of a connection strip
 *       bool front_facing;
 *   After the hook: MASK items discard when the returned alpha is below
 *   their cutoff; BLEND items blend with the returned alpha. Debug views
 *   (tlod_draw_desc.debug) do not call the hook. The built-in material:
 *       vec4(f.base_color.rgb * (0.15 + 0.85 * max(dot(f.normal,
 *       f.light_dir), 0)), f.base_color.a)
 *   A hook that does not compile fails tlod_device_create() with
 *   TLOD_ERROR_BACKEND; the last error holds the driver's log with the
 *   hook's lines as "fragment_hook:LINE" (line 1 = the hook's first line).
 *   The same interfaces for an engine's own shaders: docs/shaders.md and
 *   the GLSL installed under share/tesslod/glsl.
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
