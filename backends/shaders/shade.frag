// Shading: the material function tlod_shade() (the built-in one,
// material.glsl, or the device's fragment hook, compiled after this file)
// on the interpolated surface point, or a debug colour.
// The uniforms are in uniforms.glsl.
layout(location = TLOD_LOCATION_NORMAL) in vec3 v_normal;
layout(location = TLOD_LOCATION_WORLD) in vec3 v_world;
layout(location = TLOD_LOCATION_LEVEL) flat in uint v_level;
layout(location = TLOD_LOCATION_STRIP) flat in uint v_strip;
#if TLOD_TEXCOORD  // FULL and MASK programs only: the fetch costs per fragment even when skipped
layout(location = TLOD_LOCATION_TEXCOORD) in vec2 v_texcoord;
#endif
#if TLOD_ATTRIBUTE_VARYINGS > 0
layout(location = TLOD_LOCATION_ATTRIBUTES) in vec4 v_attr[TLOD_SHADER_MAX_ATTRIBUTES];
#endif

layout(location = 0) out vec4 o_color;

// What a material function sees of a fragment (tesslod/gl.h, docs/shaders.md).
struct tlod_fragment {
  vec3 position;    // world
  vec3 normal;      // world, unit, towards the viewer's side on back faces (flipped)
  vec3 light_dir;   // world, unit, towards the light (tlod_draw_desc.light_dir)
  vec3 eye;         // world position of the camera
  vec4 base_color;  // the item's colour times its base colour texture sample (linear)
  vec4 attributes[TLOD_SHADER_MAX_ATTRIBUTES];  // the mesh attributes, (0, 0, 0, 0) past attribute_count
                                                 // (fragment hooks only: zero for the built-in material)
  uint attribute_count;
  uint level;       // refinement level of the patch (strips: the side's)
  bool strip;       // a connection strip's fragment
  bool front_facing;
};

vec4 tlod_shade(tlod_fragment f);

vec3 level_color(uint l) {
  const vec3 c[8] = vec3[8](vec3(0.2, 0.3, 0.9), vec3(0.1, 0.7, 0.9), vec3(0.1, 0.8, 0.3), vec3(0.7, 0.9, 0.1),
                            vec3(1.0, 0.7, 0.1), vec3(1.0, 0.35, 0.1), vec3(0.9, 0.1, 0.2), vec3(0.8, 0.1, 0.8));
  return c[min(l, 7u)];
}

tlod_fragment fragment(vec3 n) {
  tlod_fragment f;
  f.position = v_world;
  f.normal = n;
  f.light_dir = u_light_dir;
  f.eye = u_eye;
  f.base_color = u_base_color;
#if TLOD_TEXCOORD
  if (u_texcoord < uint(TLOD_SHADER_MAX_ATTRIBUTES))
    f.base_color *= texture(u_base_color_texture, v_texcoord);
#endif
  for (int a = 0; a < TLOD_SHADER_MAX_ATTRIBUTES; a++)
#if TLOD_ATTRIBUTE_VARYINGS > 0
    f.attributes[a] = v_attr[a];
#else
    f.attributes[a] = vec4(0.0);  // the built-in material reads none
#endif
  f.attribute_count = u_attribute_count;
  f.level = v_level;
  f.strip = v_strip == 1u;
  f.front_facing = gl_FrontFacing;
  return f;
}

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  if (u_debug == 0u) {
    vec4 c = tlod_shade(fragment(n));
#if TLOD_MASK
    if (c.a < u_alpha_cutoff) discard;  // the MASK programs only: discard costs the early depth test
#endif
    o_color = c;
    return;
  }
  float lambert = 0.15 + 0.85 * max(dot(n, u_light_dir), 0.0);
  vec3 base = u_base_color.rgb;
  if (u_debug == 1u) base = level_color(v_level);
  if (u_debug == 2u) {
    vec3 d = u_ortho == 1u ? -u_forward : normalize(u_eye - v_world);
    float s = 1.0 - abs(dot(n, d));
    base = mix(vec3(0.1, 0.2, 0.8), vec3(1.0, 0.2, 0.1), s);
  }
  if (u_debug == 3u && v_strip == 1u) base = vec3(1.0, 0.1, 0.6);
  o_color = u_debug == 4u ? vec4(0.05, 0.05, 0.05, 1.0) : vec4(base * lambert, u_base_color.a);
}
