// Curved PN triangles (Vlachos et al. 2001): cubic positions, quadratic normals.

vec3 tangent_point(vec3 pi, vec3 ni, vec3 pj) {
  precise float w = dot(pj - pi, ni);
  precise vec3 r = (pi * 2.0 + pj - ni * w) * (1.0 / 3.0);
  return r;
}

vec3 mid_normal(vec3 pi, vec3 ni, vec3 pj, vec3 nj) {
  vec3 d = pj - pi;
  float dd = dot(d, d);
  vec3 sum = ni + nj;
  float v = dd > 0.0 ? 2.0 * dot(d, sum) / dd : 0.0;
  return safe_normalize(sum - d * v, ni);
}

void edge_point(vec3 pa, vec3 na, float aa, vec3 pb, vec3 nb, float ab, vec3 m, float t, out vec3 pos,
                out vec3 nrm) {
  precise float s = 1.0 - t;
  precise vec3 bab = tangent_point(pa, na, pb);
  precise vec3 bba = tangent_point(pb, nb, pa);
  precise float k0 = s * s * s, k1 = 3.0 * s * s * t, k2 = 3.0 * s * t * t, k3 = t * t * t;
  pos = ((pa * k0 + bab * k1) + bba * k2) + pb * k3;
  vec3 nab = mid_normal(pa, na, pb, nb);
  nrm = safe_normalize(na * (s * s) + nab * (s * t) + nb * (t * t), na);
}

void interior_point(Patch P, vec2 uv, out vec3 pos, out vec3 nrm) {
  float u = uv.x, v = uv.y, w = 1.0 - u - v;
  float uu = u * u, vv = v * v, ww = w * w;
  pos = P.b[0].xyz * (uu * u) + P.b[1].xyz * (vv * v) + P.b[2].xyz * (ww * w) + P.b[3].xyz * (3.0 * uu * v) +
        P.b[4].xyz * (3.0 * u * vv) + P.b[8].xyz * (3.0 * uu * w) + P.b[5].xyz * (3.0 * vv * w) +
        P.b[7].xyz * (3.0 * u * ww) + P.b[6].xyz * (3.0 * v * ww) + P.b[9].xyz * (6.0 * u * v * w);
  vec3 n = P.n[0].xyz * uu + P.n[1].xyz * vv + P.n[2].xyz * ww + P.mn[0].xyz * (u * v) + P.mn[1].xyz * (v * w) +
           P.mn[2].xyz * (w * u);
  nrm = safe_normalize(n, P.n[0].xyz);
}
