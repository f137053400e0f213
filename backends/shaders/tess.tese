// Evaluates the patch at the tessellator's point, through the canonical edge
// function on edges (exact k / 2^l parameters) like the pattern path.
#if TLOD_CORNERS == 3
layout(triangles, equal_spacing, ccw) in;
#else
layout(quads, equal_spacing, ccw) in;
#endif
layout(location = TLOD_LOCATION_TESS_INSTANCE) patch in uint tc_inst;

layout(location = TLOD_LOCATION_NORMAL) out vec3 v_normal;
layout(location = TLOD_LOCATION_WORLD) out vec3 v_world;
layout(location = TLOD_LOCATION_LEVEL) flat out uint v_level;
layout(location = TLOD_LOCATION_STRIP) flat out uint v_strip;

void main() {
  Instance ins = instances[tc_inst];
  Patch P = patches[ins.patch_id];
  vec3 c = gl_TessCoord;
  vec2 uv = c.xy;
  uint kind = 8u, num = 0u;
  float N = float(u_grid);
#if TLOD_CORNERS == 3
  // Weights: u on corner i (0), v on j (1), w on k (2).
  if (c.x == 1.0) kind = 0u; else if (c.y == 1.0) kind = 1u; else if (c.z == 1.0) kind = 2u;
  else if (c.z == 0.0) { kind = 4u; num = uint(c.y * N); }
  else if (c.x == 0.0) { kind = 5u; num = uint(c.z * N); }
  else if (c.y == 0.0) { kind = 6u; num = uint(c.x * N); }
#else
  bool eu = c.x == 0.0 || c.x == 1.0, ev = c.y == 0.0 || c.y == 1.0;
  if (eu && ev) kind = c.x == 0.0 ? (c.y == 0.0 ? 0u : 3u) : (c.y == 0.0 ? 1u : 2u);
  else if (c.y == 0.0) { kind = 4u; num = uint(c.x * N); }
  else if (c.x == 1.0) { kind = 5u; num = uint(c.y * N); }
  else if (c.y == 1.0) { kind = 6u; num = uint((1.0 - c.x) * N); }
  else if (c.x == 0.0) { kind = 7u; num = uint((1.0 - c.y) * N); }
#endif
  vec3 pos, nrm;
  if (kind < 4u) { pos = P.p[kind].xyz; nrm = P.n[kind].xyz; }
  else if (kind < 8u) patch_edge_point(P, kind - 4u, num, pos, nrm);
  else interior_point(P, uv, pos, nrm);
  write_varyings(ins.patch_id, P, kind, num, uv);
  v_normal = world_normal(nrm);
  v_world = world_position(pos);
  v_level = ins.level;
  v_strip = 0u;
  gl_Position = u_view_proj * vec4(pos, 1.0);
}
