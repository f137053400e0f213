// tesslod shaders -- shared declarations after layout.h (the storage
// buffers, their structs and binding points, shared with C) and
// uniforms.glsl (u_grid, u_model, u_normal_matrix): the canonical edge
// evaluation (docs/design.md invariant 1: both patches of an edge evaluate
// its points with the same function, inputs and order, marked precise so no
// FMA contraction can differ).

// World-space outputs of a surface point (identity model: exactly pos and nrm).
vec3 world_position(vec3 pos) { return (u_model * vec4(pos, 1.0)).xyz; }
vec3 world_normal(vec3 nrm) { return u_normal_matrix * nrm; }

// The canonical edge point from a to b at t (a has the smaller welded id);
// m is the edge's node (Patch.b[e]: the quadratic surface's mid-edge node,
// direction-free; the other types ignore it).
void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, vec3 m, float t, out vec3 pos, out vec3 nrm);
// A surface point inside the patch at (u, v).
void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm);

// Point on edge e of patch P with weight t_end on its end corner.
void patch_edge_point(Patch P, uint e, uint num, out vec3 pos, out vec3 nrm) {
  uint n = P.info.x, a = e, b = (e + 1u) % n;
  if (num == 0u) { pos = P.p[a].xyz; nrm = P.n[a].xyz; return; }
  if (num == u_grid) { pos = P.p[b].xyz; nrm = P.n[b].xyz; return; }
  precise float t = float(num) / float(u_grid);
  if (P.weld[a] < P.weld[b]) {
    edge_point(P.p[a].xyz, P.n[a].xyz, P.p[a].w, P.p[b].xyz, P.n[b].xyz, P.p[b].w, P.b[e].xyz, t, pos, nrm);
  } else {
    edge_point(P.p[b].xyz, P.n[b].xyz, P.p[b].w, P.p[a].xyz, P.n[a].xyz, P.p[a].w, P.b[e].xyz, 1.0 - t, pos, nrm);
  }
}

// The exact surface point of a pattern vertex.
void pattern_point(Patch P, PatternVertex v, out vec3 pos, out vec3 nrm) {
  uint kind = v.code & 255u;
  if (kind < 4u) { pos = P.p[kind].xyz; nrm = P.n[kind].xyz; return; }
  if (kind < 8u) { patch_edge_point(P, kind - 4u, v.param, pos, nrm); return; }
  interior_point(P, v.uv, pos, nrm);
}

// Geomorph: blend from the parents' midpoint (the coarser level) at 0 to the surface at 1.
void morph_point(float a, vec3 p0, vec3 n0, vec3 p1, vec3 n1, inout vec3 pos, inout vec3 nrm) {
  precise vec3 mid = 0.5 * (p0 + p1);
  pos = mid + a * (pos - mid);
  vec3 n = 0.5 * (n0 + n1) * (1.0 - a) + nrm * a;
  nrm = length(n) > 0.0 ? normalize(n) : nrm;
}

vec3 safe_normalize(vec3 v, vec3 fallback) {
  float l = length(v);
  return l > 0.0 ? v / l : fallback;
}

// Corner weights at (u, v): barycentric (u, v, 1 - u - v) or bilinear.
void corner_weights(uint n, vec2 uv, out float w[4]) {
  if (n == 3u) {
    w[0] = uv.x; w[1] = uv.y; w[2] = 1.0 - uv.x - uv.y; w[3] = 0.0;
  } else {
    w[0] = (1.0 - uv.x) * (1.0 - uv.y); w[1] = uv.x * (1.0 - uv.y); w[2] = uv.x * uv.y; w[3] = (1.0 - uv.x) * uv.y;
  }
}
