// Phong tessellation (Boubekeur & Alexa 2008; quads: Dupuy), alpha per vertex.

vec3 project_onto(vec3 q, vec3 p, vec3 n) { return q - dot(q - p, n) * n; }

void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, vec3 m, float t, out vec3 pos,
                out vec3 nrm) {
  precise float s = 1.0 - t;
  precise vec3 p = pa * s + pb * t;
  precise float alpha = aa * s + ab * t;
  precise vec3 proj = project_onto(p, pa, na) * s + project_onto(p, pb, nb) * t;
  pos = p * (1.0 - alpha) + proj * alpha;
  nrm = safe_normalize(na * s + nb * t, na);
}

void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm) {
  float w[4];
  uint n = P.info.x;
  corner_weights(n, uv, w);
  vec3 q = vec3(0.0), nn = vec3(0.0);
  float alpha = 0.0;
  for (uint i = 0u; i < n; i++) { q += P.p[i].xyz * w[i]; alpha += P.p[i].w * w[i]; nn += P.n[i].xyz * w[i]; }
  vec3 proj = vec3(0.0);
  for (uint i = 0u; i < n; i++) proj += project_onto(q, P.p[i].xyz, P.n[i].xyz) * w[i];
  pos = q * (1.0 - alpha) + proj * alpha;
  nrm = safe_normalize(nn, P.n[0].xyz);
}
