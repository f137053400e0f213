// Every uniform of every stage of the device's programs, in one place
// (after layout.h, before common.glsl). A stage uses what it reads; the rest
// costs nothing.
//   GL: loose uniforms, looked up by name when the device links a program.
//   Vulkan (TLOD_VULKAN): one std140 block per item (tlod_vk_uniforms in
//   layout.h, a dynamic offset into the frame's ring) and one push constant
//   block per draw call (tlod_vk_push); the names are the same, so the code
//   after this file does not depend on the API.
#ifdef TLOD_VULKAN
layout(std140, set = 0, binding = TLOD_VK_BINDING_UNIFORMS) uniform TlodUniforms {
  mat4 u_view_proj;  // clip-corrected: z' = 0.5 z + 0.5 w (Vulkan's depth range 0..1)
  mat4 u_model;
  mat3 u_normal_matrix;
  vec3 u_light_dir;
  vec4 u_base_color;
  vec3 u_eye;
  uint u_ortho;
  vec3 u_forward;
  float u_alpha_cutoff;
  uint u_grid;
  uint u_max_level;
  uint u_texcoord;
  uint u_attribute_count;
};
layout(push_constant) uniform TlodPush {
  uint u_first_instance;
  uint u_shape_base;
  uint u_corners;
  uint u_debug;
};
#if defined(TLOD_TEXCOORD) && TLOD_TEXCOORD
layout(set = 0, binding = TLOD_VK_BINDING_BASE_COLOR) uniform sampler2D u_base_color_texture;
#endif

#else
// Surface evaluation (common.glsl, attributes.glsl): also an engine's.
uniform mat4 u_view_proj;        // proj * view * model of the item drawn
uniform mat4 u_model;            // the item's model matrix (world position for shading)
uniform mat3 u_normal_matrix;    // inverse transpose of the model's 3x3
uniform uint u_grid;             // N = 2^max_level (set at link time)
uniform uint u_max_level;        // (set at link time)
uniform uint u_attribute_count;  // of the item's mesh, 0..TLOD_SHADER_MAX_ATTRIBUTES
// The device's draws.
uniform uint u_first_instance;  // first instance of the draw call in Instances
uniform uint u_shape_base;      // pattern.vert: offset of this shape's vertices in Pattern
uniform uint u_corners;         // tess.vert: 3 or 4
uniform vec3 u_light_dir;       // normalised, towards the light
uniform vec4 u_base_color;
uniform uint u_debug;  // 0 shaded, 1 levels, 2 silhouette depth, 3 strips, 4 wire
uniform vec3 u_eye;
uniform uint u_ortho;
uniform vec3 u_forward;
uniform float u_alpha_cutoff;  // MASK (TLOD_MASK programs)
#if defined(TLOD_TEXCOORD) && TLOD_TEXCOORD
uniform uint u_texcoord;  // attribute of the base colour texture's coordinates (v_texcoord); >= 8: none
layout(binding = TLOD_TEXTURE_UNIT_BASE_COLOR) uniform sampler2D u_base_color_texture;
#endif
#endif
