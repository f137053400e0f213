// Second-order (isoparametric quadratic) faces: the 6-node triangle and the
// 9-node biquadratic quad through the record's corners and nodes (Patch.b:
// [0..3] the node of edge 0..3, [4] a quad's centre; Lagrange nodes, not
// Bezier points; docs/design.md "Quadratic faces"). Shading normal: the
// interpolated corner normals, as Phong.

// The quadratic edge through a (t = 0), m (t = 1/2) and b (t = 1), in the
// operation order of core's edge function: t = 0 gives a and t = 1 gives b
// exactly, and both patches of an edge evaluate it with the same inputs.
void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, vec3 m, float t, out vec3 pos, out vec3 nrm) {
  precise float s = 1.0 - t;
  precise vec3 p = pa * (s * (s - t)) + pb * (t * (t - s)) + m * (4.0 * s * t);
  pos = p;
  nrm = safe_normalize(na * s + nb * t, na);
}

// P = sum l_i (2 l_i - 1) P_i + 4 l0 l1 M0 + 4 l1 l2 M1 + 4 l2 l0 M2, l = (u, v, 1 - u - v).
vec3 quadratic_triangle(Patch P, vec2 uv) {
  float l0 = uv.x, l1 = uv.y, l2 = 1.0 - uv.x - uv.y;
  return P.p[0].xyz * (l0 * (2.0 * l0 - 1.0)) + P.p[1].xyz * (l1 * (2.0 * l1 - 1.0)) +
         P.p[2].xyz * (l2 * (2.0 * l2 - 1.0)) + P.b[0].xyz * (4.0 * l0 * l1) + P.b[1].xyz * (4.0 * l1 * l2) +
         P.b[2].xyz * (4.0 * l2 * l0);
}

// The 1D quadratic Lagrange basis at 0, 1/2, 1.
vec3 quadratic_basis(float t) { return vec3((1.0 - t) * (1.0 - 2.0 * t), 4.0 * t * (1.0 - t), t * (2.0 * t - 1.0)); }

// P = sum L_a(u) L_b(v) X_ab over the 3 x 3 nodes: corners (0,0) (1,0)
// (1,1) (0,1), edge nodes (h,0) (1,h) (h,1) (0,h), centre (h,h).
vec3 quadratic_quad(Patch P, vec2 uv) {
  vec3 a = quadratic_basis(uv.x), b = quadratic_basis(uv.y);
  return P.p[0].xyz * (a.x * b.x) + P.p[1].xyz * (a.z * b.x) + P.p[2].xyz * (a.z * b.z) + P.p[3].xyz * (a.x * b.z) +
         P.b[0].xyz * (a.y * b.x) + P.b[1].xyz * (a.z * b.y) + P.b[2].xyz * (a.y * b.z) + P.b[3].xyz * (a.x * b.y) +
         P.b[4].xyz * (a.y * b.y);
}

void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm) {
  float w[4];
  uint n = P.info.x;
  corner_weights(n, uv, w);
  vec3 nn = vec3(0.0);
  for (uint i = 0u; i < n; i++) nn += P.n[i].xyz * w[i];
  pos = n == 3u ? quadratic_triangle(P, uv) : quadratic_quad(P, uv);
  nrm = safe_normalize(nn, P.n[0].xyz);
}
