// The flat patch: the input triangle, the bilinear quad.

void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, vec3 m, float t, out vec3 pos,
                out vec3 nrm) {
  precise float s = 1.0 - t;
  pos = pa * s + pb * t;
  nrm = safe_normalize(na * s + nb * t, na);
}

void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm) {
  float w[4];
  uint n = P.info.x;
  corner_weights(n, uv, w);
  vec3 q = vec3(0.0), nn = vec3(0.0);
  for (uint i = 0u; i < n; i++) { q += P.p[i].xyz * w[i]; nn += P.n[i].xyz * w[i]; }
  pos = q;
  nrm = safe_normalize(nn, P.n[0].xyz);
}
