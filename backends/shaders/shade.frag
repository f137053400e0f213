// Shading: Lambert on the interpolated surface normal, or a debug colour.
in vec3 v_normal;
in vec3 v_world;
flat in uint v_level;
flat in uint v_strip;

uniform vec3 u_light_dir;   // normalised, towards the light
uniform vec4 u_base_color;
uniform uint u_debug;       // 0 shaded, 1 levels, 2 silhouette depth, 3 strips, 4 wire
uniform vec3 u_eye;
uniform uint u_ortho;
uniform vec3 u_forward;

layout(location = 0) out vec4 o_color;

vec3 level_color(uint l) {
  const vec3 c[8] = vec3[8](vec3(0.2, 0.3, 0.9), vec3(0.1, 0.7, 0.9), vec3(0.1, 0.8, 0.3), vec3(0.7, 0.9, 0.1),
                            vec3(1.0, 0.7, 0.1), vec3(1.0, 0.35, 0.1), vec3(0.9, 0.1, 0.2), vec3(0.8, 0.1, 0.8));
  return c[min(l, 7u)];
}

void main() {
  vec3 n = normalize(v_normal);
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
