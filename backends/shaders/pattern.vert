// Refinement patterns drawn instanced: one instance per patch, the pattern
// vertex from gl_VertexID (the element buffer holds pattern indices);
// u_first_instance and u_shape_base (uniforms.glsl) place the draw call.
layout(location = TLOD_LOCATION_NORMAL) out vec3 v_normal;
layout(location = TLOD_LOCATION_WORLD) out vec3 v_world;
layout(location = TLOD_LOCATION_LEVEL) flat out uint v_level;
layout(location = TLOD_LOCATION_STRIP) flat out uint v_strip;

void main() {
  Instance ins = instances[u_first_instance + uint(TLOD_INSTANCE_ID)];
  Patch P = patches[ins.patch_id];
  PatternVertex v = pattern[u_shape_base + uint(TLOD_VERTEX_ID)];
  vec3 pos, nrm;
  pattern_point(P, v, pos, nrm);
  uint kind = v.code & 255u, level = v.code >> 8;
  if (level == ins.level && level > 0u) {
    float a = kind == 8u ? ins.morph.x : (kind == 4u ? ins.morph.y : kind == 5u ? ins.morph.z : kind == 6u ? ins.morph.w : ins.morph_e3.x);
    if (a < 1.0) {
      vec3 p0, n0, p1, n1;
      pattern_point(P, pattern[u_shape_base + v.parent0], p0, n0);
      pattern_point(P, pattern[u_shape_base + v.parent1], p1, n1);
      morph_point(a, p0, n0, p1, n1, pos, nrm);
    }
  }
  write_varyings(ins.patch_id, P, kind, v.param, v.uv);
  v_normal = world_normal(nrm);
  v_world = world_position(pos);
  v_level = ins.level;
  v_strip = 0u;
  gl_Position = u_view_proj * vec4(pos, 1.0);
}
