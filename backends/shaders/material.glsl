// The built-in material (tlod_device_gl_desc.fragment_hook NULL): Lambert
// with an ambient term on the base colour (tesslod/backend.h, tlod_draw_desc).
vec4 tlod_shade(tlod_fragment f) {
  float lambert = 0.15 + 0.85 * max(dot(f.normal, f.light_dir), 0.0);
  return vec4(f.base_color.rgb * lambert, f.base_color.a);
}
