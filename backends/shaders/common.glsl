// tesslod shaders -- shared declarations: patch, pattern and frame data in
// storage buffers (backends/gl/src/gl_internal.h mirrors the layout), and the
// canonical edge evaluation (docs/design.md invariant 1: both patches of an edge
// evaluate its points with the same function, inputs and order, marked
// precise so no FMA contraction can differ).

struct Patch {
  vec4 p[4];   // corner positions, alpha in w
  vec4 n[4];   // corner normals
  uvec4 weld;  // welded position id per corner (canonical edge direction)
  uvec4 info;  // x: corner count
  vec4 b[10];  // PN control points b300 b030 b003 b210 b120 b021 b012 b102 b201 b111
  vec4 mn[3];  // PN mid-edge normals n110 n011 n101
};

struct PatternVertex {
  vec2 uv;
  uint parent0, parent1;
  uint code;   // kind (0-3 corner, 4-7 edge, 8 interior) | level << 8
  uint param;  // edge: numerator of the end corner's weight over N
  uint pad0, pad1;
};

struct Instance {
  uint patch_id, level;
  uint edge_levels;  // hardware path: outer level exponent per edge, 8 bits each
  uint pad1;
  vec4 morph;      // x: interior blend; y, z, w: edges 0-2
  vec4 morph_e3;   // x: edge 3
};

struct Strip {
  uint patch_a, patch_b, edges, levels;  // edges: ea | eb << 8; levels: la | lb << 8
  vec4 morph;                            // x: a's edge blend, y: b's edge blend
};

layout(std430, binding = 0) readonly buffer Patches { Patch patches[]; };
layout(std430, binding = 1) readonly buffer Pattern { PatternVertex pattern[]; };
layout(std430, binding = 2) readonly buffer Instances { Instance instances[]; };
layout(std430, binding = 3) readonly buffer Strips { Strip strips[]; };

uniform mat4 u_view_proj;
uniform uint u_grid;      // N = 2^max_level
uniform uint u_max_level;

// The canonical edge point from a to b at t (a has the smaller welded id).
void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, float t, out vec3 pos, out vec3 nrm);
// A surface point inside the patch at (u, v).
void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm);

// Point on edge e of patch P with weight t_end on its end corner.
void patch_edge_point(Patch P, uint e, uint num, out vec3 pos, out vec3 nrm) {
  uint n = P.info.x, a = e, b = (e + 1u) % n;
  if (num == 0u) { pos = P.p[a].xyz; nrm = P.n[a].xyz; return; }
  if (num == u_grid) { pos = P.p[b].xyz; nrm = P.n[b].xyz; return; }
  precise float t = float(num) / float(u_grid);
  if (P.weld[a] < P.weld[b]) {
    edge_point(P.p[a].xyz, P.n[a].xyz, P.p[a].w, P.p[b].xyz, P.n[b].xyz, P.p[b].w, t, pos, nrm);
  } else {
    edge_point(P.p[b].xyz, P.n[b].xyz, P.p[b].w, P.p[a].xyz, P.n[a].xyz, P.p[a].w, 1.0 - t, pos, nrm);
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
