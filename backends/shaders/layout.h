/*
 * backends/shaders/layout.h -- the buffer layouts and binding points the GPU
 * backends and their shaders share. One file, valid C and GLSL:
 *   - GLSL: the GPU backends assemble every program as
 *       "#version 450 core" + "#define TLOD_GLSL 1" (+ "#define TLOD_VULKAN 1"
 *       for Vulkan) + this file + uniforms.glsl + common.glsl + ...
 *     so the shaders get the binding points, the structs and the buffer blocks;
 *   - C: backends/gl and backends/vulkan include it (TLOD_GLSL undefined) and
 *     get the same binding points and C mirrors of the structs, checked with
 *     _Static_assert against std430 / std140 and against core's tlod_patch_record.
 * Only the preprocessor subset both languages share is used (#define, #if,
 * #ifdef, comments). The binding points are public as TLOD_GL_BINDING_* in
 * tesslod/gl.h; gl_internal.h checks they agree.
 */
#ifndef TLOD_SHADER_LAYOUT_H
#define TLOD_SHADER_LAYOUT_H

/* Shader storage binding points. */
#define TLOD_BINDING_PATCHES 0    /* per patch: tlod_patch_record (core.h) */
#define TLOD_BINDING_PATTERN 1    /* pattern vertices of both shapes */
#define TLOD_BINDING_INSTANCES 2  /* per visible patch of the draw: level, geomorph blends, edge levels */
#define TLOD_BINDING_STRIPS 3     /* per connection strip of the draw: patches, edges, levels, blends */
#define TLOD_BINDING_ATTRIBUTES 4 /* per patch and corner: the mesh attributes (tlod_mesh_patch_attributes) */
#define TLOD_BINDING_COUNT 5

/* Texture unit of the base colour texture (sampler u_base_color_texture). */
#define TLOD_TEXTURE_UNIT_BASE_COLOR 0

/* Vulkan: every resource in descriptor set 0. The storage buffers keep the
 * TLOD_BINDING_* numbers above (instances and strips as dynamic storage
 * buffers into the frame ring); the uniforms of one item (block TlodUniforms,
 * tlod_vk_uniforms) are a dynamic uniform buffer, the base colour texture a
 * combined image sampler. */
#define TLOD_VK_BINDING_UNIFORMS 5   /* UNIFORM_BUFFER_DYNAMIC, std140, 256 bytes per item */
#define TLOD_VK_BINDING_BASE_COLOR 6 /* COMBINED_IMAGE_SAMPLER (GL: texture unit 0) */
#define TLOD_VK_UNIFORM_BYTES 256
#define TLOD_VK_PUSH_BYTES 16

/* Varying locations (both APIs: the same sources): vertex-side outputs =
 * fragment inputs; the attribute array takes TLOD_SHADER_MAX_ATTRIBUTES
 * locations from TLOD_LOCATION_ATTRIBUTES. The hardware path's vertex ->
 * control stage outputs and its per-patch output start at 0 in their own
 * interfaces. */
#define TLOD_LOCATION_NORMAL 0
#define TLOD_LOCATION_WORLD 1
#define TLOD_LOCATION_LEVEL 2
#define TLOD_LOCATION_STRIP 3
#define TLOD_LOCATION_TEXCOORD 4
#define TLOD_LOCATION_ATTRIBUTES 5
#define TLOD_LOCATION_TESS_INSTANCE 0 /* vc_inst (vertex -> control), tc_inst (patch, control -> evaluation) */
#define TLOD_LOCATION_TESS_CORNER 1   /* vc_corner */

/* Attributes interpolated per vertex (== TLOD_MAX_ATTRIBUTES of core.h). */
#define TLOD_SHADER_MAX_ATTRIBUTES 8

/* Vertex attribute of the strip program: (strip, point) pairs. */
#define TLOD_ATTRIB_STRIP_REF 0
/* CPU-mesh mode (mesh.vert): the evaluated mesh's positions and normals. */
#define TLOD_ATTRIB_MESH_POSITION 0
#define TLOD_ATTRIB_MESH_NORMAL 1

/* Pattern vertex code: kind | level << 8 (kind: 0-3 corner, 4-7 edge, 8 interior,
 * as tlod_grid_point_kind()). */
#define TLOD_CODE_LEVEL_SHIFT 8

/* std430 sizes in bytes (every member a multiple of 16 bytes or packed uints). */
#define TLOD_PATCH_BYTES 368 /* 23 vec4 */
#define TLOD_PATTERN_VERTEX_BYTES 32
#define TLOD_INSTANCE_BYTES 48
#define TLOD_STRIP_BYTES 32

#ifdef TLOD_GLSL
/* ---- GLSL --------------------------------------------------------------- */

/* The one built-in that differs by name: Vulkan's gl_VertexIndex and
 * gl_InstanceIndex include the draw's vertexOffset and firstInstance; the
 * device draws with both 0, so they equal GL's gl_VertexID and gl_InstanceID. */
#ifdef TLOD_VULKAN
#define TLOD_VERTEX_ID gl_VertexIndex
#define TLOD_INSTANCE_ID gl_InstanceIndex
#else
#define TLOD_VERTEX_ID gl_VertexID
#define TLOD_INSTANCE_ID gl_InstanceID
#endif

struct Patch { /* == tlod_patch_record */
  vec4 p[4];   /* corner positions, alpha in w */
  vec4 n[4];   /* corner normals */
  uvec4 weld;  /* welded position id per corner (canonical edge direction) */
  uvec4 info;  /* x: corner count */
  vec4 b[10];  /* PN control points b300 b030 b003 b210 b120 b021 b012 b102 b201 b111 */
  vec4 mn[3];  /* PN mid-edge normals n110 n011 n101 */
};

struct PatternVertex {
  vec2 uv;
  uint parent0, parent1;
  uint code;  /* kind | level << 8 */
  uint param; /* edge: numerator of the end corner's weight over N */
  uint pad0, pad1;
};

struct Instance {
  uint patch_id, level;
  uint edge_levels; /* hardware path: outer level exponent per edge, 8 bits each */
  uint pad1;
  vec4 morph;    /* x: interior blend; y, z, w: edges 0-2 */
  vec4 morph_e3; /* x: edge 3 */
};

struct Strip {
  uint patch_a, patch_b, edges, levels; /* edges: ea | eb << 8; levels: la | lb << 8 */
  vec4 morph;                           /* x: a's edge blend, y: b's edge blend */
};

layout(std430, binding = TLOD_BINDING_PATCHES) readonly buffer Patches { Patch patches[]; };
layout(std430, binding = TLOD_BINDING_PATTERN) readonly buffer Pattern { PatternVertex pattern[]; };
layout(std430, binding = TLOD_BINDING_INSTANCES) readonly buffer Instances { Instance instances[]; };
layout(std430, binding = TLOD_BINDING_STRIPS) readonly buffer Strips { Strip strips[]; };
// Patch p, corner c, attribute a at [(p * 4 + c) * attribute_count + a] (corner 3 of a triangle zero).
layout(std430, binding = TLOD_BINDING_ATTRIBUTES) readonly buffer Attributes { vec4 patch_attributes[]; };

#else
/* ---- C ------------------------------------------------------------------ */

#include <stddef.h>
#include <stdint.h>

#include "tesslod/core.h"

/* Patch: tlod_patch_record (tesslod/core.h), written by tlod_surface_patch_records(). */
_Static_assert(sizeof(tlod_patch_record) == TLOD_PATCH_BYTES, "tlod_patch_record is the std430 Patch");
_Static_assert(offsetof(tlod_patch_record, corner) == 0, "Patch.p");
_Static_assert(offsetof(tlod_patch_record, normal) == 64, "Patch.n");
_Static_assert(offsetof(tlod_patch_record, weld) == 128, "Patch.weld");
_Static_assert(offsetof(tlod_patch_record, info) == 144, "Patch.info");
_Static_assert(offsetof(tlod_patch_record, pn_control) == 160, "Patch.b");
_Static_assert(offsetof(tlod_patch_record, pn_normal) == 320, "Patch.mn");

typedef struct tlod_gl_pattern_vertex { /* PatternVertex */
  float uv[2];
  uint32_t parent0, parent1;
  uint32_t code, param;
  uint32_t pad[2];
} tlod_gl_pattern_vertex;

typedef struct tlod_gl_instance { /* Instance */
  uint32_t patch, level;
  uint32_t edge_levels;
  uint32_t pad;
  float morph[4];
  float morph_e3[4];
} tlod_gl_instance;

typedef struct tlod_gl_strip { /* Strip */
  uint32_t patch_a, patch_b, edges, levels;
  float morph[4];
} tlod_gl_strip;

_Static_assert(TLOD_SHADER_MAX_ATTRIBUTES == TLOD_MAX_ATTRIBUTES, "one varying per core attribute");
_Static_assert(sizeof(tlod_gl_pattern_vertex) == TLOD_PATTERN_VERTEX_BYTES, "PatternVertex");
_Static_assert(offsetof(tlod_gl_pattern_vertex, code) == 16, "PatternVertex.code");
_Static_assert(sizeof(tlod_gl_instance) == TLOD_INSTANCE_BYTES, "Instance");
_Static_assert(offsetof(tlod_gl_instance, morph) == 16, "Instance.morph");
_Static_assert(offsetof(tlod_gl_instance, morph_e3) == 32, "Instance.morph_e3");
_Static_assert(sizeof(tlod_gl_strip) == TLOD_STRIP_BYTES, "Strip");
_Static_assert(offsetof(tlod_gl_strip, morph) == 16, "Strip.morph");

/* Vulkan: block TlodUniforms (uniforms.glsl), std140. view_proj is the
 * clip-corrected proj * view * model (z' = 0.5 z + 0.5 w); mat3 columns
 * are vec4s. */
typedef struct tlod_vk_uniforms {
  float view_proj[16], model[16];
  float normal_matrix[12]; /* 3 vec4 columns, w unused */
  float light_dir[3];
  uint32_t pad0;
  float base_color[4];
  float eye[3];
  uint32_t ortho;
  float forward[3];
  float alpha_cutoff;
  uint32_t grid, max_level, texcoord, attribute_count;
} tlod_vk_uniforms;

/* Vulkan: push constant block TlodPush, per draw call. */
typedef struct tlod_vk_push {
  uint32_t first_instance, shape_base, corners, debug;
} tlod_vk_push;

_Static_assert(sizeof(tlod_vk_uniforms) == TLOD_VK_UNIFORM_BYTES, "TlodUniforms");
_Static_assert(offsetof(tlod_vk_uniforms, model) == 64, "TlodUniforms.u_model");
_Static_assert(offsetof(tlod_vk_uniforms, normal_matrix) == 128, "TlodUniforms.u_normal_matrix");
_Static_assert(offsetof(tlod_vk_uniforms, light_dir) == 176, "TlodUniforms.u_light_dir");
_Static_assert(offsetof(tlod_vk_uniforms, base_color) == 192, "TlodUniforms.u_base_color");
_Static_assert(offsetof(tlod_vk_uniforms, eye) == 208, "TlodUniforms.u_eye");
_Static_assert(offsetof(tlod_vk_uniforms, ortho) == 220, "TlodUniforms.u_ortho");
_Static_assert(offsetof(tlod_vk_uniforms, forward) == 224, "TlodUniforms.u_forward");
_Static_assert(offsetof(tlod_vk_uniforms, alpha_cutoff) == 236, "TlodUniforms.u_alpha_cutoff");
_Static_assert(offsetof(tlod_vk_uniforms, grid) == 240, "TlodUniforms.u_grid");
_Static_assert(offsetof(tlod_vk_uniforms, attribute_count) == 252, "TlodUniforms.u_attribute_count");
_Static_assert(sizeof(tlod_vk_push) == TLOD_VK_PUSH_BYTES, "TlodPush");

#endif
#endif
