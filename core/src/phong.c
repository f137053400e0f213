/* tesslod::core -- Phong tessellation of triangles and quads, and the flat patch.
 *
 * This work is based on:
 *   T. Boubekeur, M. Alexa. Phong Tessellation. ACM TOG 27(5), 2008.
 *   J. Dupuy. Phong Tessellation for Quads. 2013 (tangents; the surface is C0
 *   across patch edges, not C1 as stated there).
 * Maths and the error bound: docs/design.md. */
#include "surface_eval.h"

void _tlod_phong_edge(v3 pa, v3 na, float alpha_a, v3 pb, v3 nb, float alpha_b, float t, v3* pos, v3* nrm) {
  *pos = _tlod_phong_edge_position(pa, na, alpha_a, pb, nb, alpha_b, t);
  *nrm = v3_normalize_or(v3_mix2(na, 1.0f - t, nb, t), na);
}

void _tlod_flat_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm) {
  float s = 1.0f - t;
  *pos = v3_mix2(pa, s, pb, t);
  *nrm = v3_normalize_or(v3_mix2(na, s, nb, t), na);
}

/* Weights and their u/v derivatives for the corners of a patch. */
typedef struct weights {
  uint32_t n;
  float w[4], du[4], dv[4];
} weights;

static weights corner_weights(uint32_t n, float u, float v) {
  if (n == 3) {
    return (weights){3, {u, v, 1.0f - u - v, 0}, {1, 0, -1, 0}, {0, 1, -1, 0}};
  }
  float su = 1.0f - u, sv = 1.0f - v;
  return (weights){4, {su * sv, u * sv, u * v, su * v}, {-sv, sv, v, -v}, {-su, -u, u, su}};
}

static v3 blend(const v3* x, const weights* w, const float* k) {
  v3 r = v3_scale(x[0], k[0]);
  for (uint32_t i = 1; i < w->n; i++)
    r = v3_add(r, v3_scale(x[i], k[i]));
  return r;
}

static float blendf(const float* x, const weights* w, const float* k) {
  float r = x[0] * k[0];
  for (uint32_t i = 1; i < w->n; i++)
    r += x[i] * k[i];
  return r;
}

/* p* = (1 - a) q + a sum w_x pi_x(q), and its derivatives by the product rule
 * with d(pi_x)/dq = I - n_x n_x^T (Dupuy eq. 6-9, for triangles too). */
void _tlod_phong_eval(const _tlod_corners* c, float u, float v, uint32_t flags, tlod_surface_point* out) {
  weights w = corner_weights(c->n, u, v);
  v3 q = blend(c->p, &w, w.w);
  float a = blendf(c->alpha, &w, w.w);
  v3 pi[4] = {{0.0f, 0.0f, 0.0f}}; /* only n are set; -O2 -Werror=maybe-uninitialized otherwise */
  for (uint32_t i = 0; i < c->n; i++)
    pi[i] = v3_project(q, c->p[i], c->nrm[i]);
  v3 proj = blend(pi, &w, w.w);
  v3_store(out->position, v3_mix2(q, 1.0f - a, proj, a));
  v3 shading = v3_normalize_or(blend(c->nrm, &w, w.w), c->nrm[0]);
  v3_store(out->normal, shading);
  if (!(flags & (_TLOD_EVAL_DERIVS | _TLOD_EVAL_TRUE_NORMAL))) return;
  v3 qu = blend(c->p, &w, w.du), qv = blend(c->p, &w, w.dv);
  float au = blendf(c->alpha, &w, w.du), av = blendf(c->alpha, &w, w.dv);
  v3 su = blend(pi, &w, w.du), sv = blend(pi, &w, w.dv);
  for (uint32_t i = 0; i < c->n; i++) {
    su = v3_add(su, v3_scale(v3_reject(qu, c->nrm[i]), w.w[i]));
    sv = v3_add(sv, v3_scale(v3_reject(qv, c->nrm[i]), w.w[i]));
  }
  v3 tu = v3_add(v3_mix2(qu, 1.0f - a, su, a), v3_scale(v3_sub(proj, q), au));
  v3 tv = v3_add(v3_mix2(qv, 1.0f - a, sv, a), v3_scale(v3_sub(proj, q), av));
  if (flags & _TLOD_EVAL_TRUE_NORMAL) v3_store(out->normal, v3_normalize_or(v3_cross(tu, tv), shading));
  v3_store(out->tangent, tu);
  v3_store(out->bitangent, tv);
}

v3 _tlod_corner_normal(const _tlod_corners* c, float u, float v) {
  weights w = corner_weights(c->n, u, v);
  return v3_normalize_or(blend(c->nrm, &w, w.w), c->nrm[0]);
}

void _tlod_flat_eval(const _tlod_corners* c, float u, float v, tlod_surface_point* out) {
  weights w = corner_weights(c->n, u, v);
  v3 tu = blend(c->p, &w, w.du), tv = blend(c->p, &w, w.dv);
  v3_store(out->position, blend(c->p, &w, w.w));
  v3_store(out->normal, _tlod_corner_normal(c, u, v));
  v3_store(out->tangent, tu);
  v3_store(out->bitangent, tv);
}

static float max_alpha(const _tlod_corners* c) {
  float a = c->alpha[0];
  for (uint32_t i = 1; i < c->n; i++)
    a = c->alpha[i] > a ? c->alpha[i] : a;
  return a;
}

/* Triangle: p* - p = 2uv d_ij + 2vw d_jk + 2wu d_ki, d_e = (pi_i(p_j) +
 * pi_j(p_i))/2 - midpoint, and 2(uv + vw + wu) <= 2/3. */
float _tlod_phong_tri_bound(const _tlod_corners* c, const double (*alpha_net)[3], float* d_max) {
  float d = 0.0f;
  for (uint32_t e = 0; e < 3; e++) {
    uint32_t i = e, j = (e + 1) % 3;
    v3 b = v3_scale(v3_add(v3_project(c->p[j], c->p[i], c->nrm[i]), v3_project(c->p[i], c->p[j], c->nrm[j])), 0.5f);
    v3 mid = v3_scale(v3_add(c->p[i], c->p[j]), 0.5f);
    float len = v3_length(v3_sub(b, mid));
    d = len > d ? len : d;
  }
  *d_max = max_alpha(c) * d;
  if (c->alpha[0] == c->alpha[1] && c->alpha[1] == c->alpha[2]) return *d_max * (2.0f / 3.0f);
  return alpha_net ? _tlod_tri_net_bound(alpha_net, c) : _tlod_phong_alpha_bound(c);
}

/* Per-vertex alpha makes the patch cubic: alpha (linear, net alpha_x) times
 * the quadratic deviation (net: 0 at corners, d_e at edges). The product's
 * net by the Bernstein product rule: B1_K B2_J = (K! J! ... ) B3_{K+J} with
 * weight 2/3 for an edge coefficient (K = 100, J = 110: 2 u^2 v = (2/3) B3_210)
 * and 1/3 for the centre (K = 100, J = 011: 2 u v w = (1/3) B3_111). */
void _tlod_phong_alpha_net(const _tlod_corners* c, double net[10][3]) {
  double dev[3][3];
  for (uint32_t e = 0; e < 3; e++) {
    uint32_t i = e, j = (e + 1) % 3;
    v3 b = v3_scale(v3_add(v3_project(c->p[j], c->p[i], c->nrm[i]), v3_project(c->p[i], c->p[j], c->nrm[j])), 0.5f);
    v3 d = v3_sub(b, v3_scale(v3_add(c->p[i], c->p[j]), 0.5f));
    dev[e][0] = d.x, dev[e][1] = d.y, dev[e][2] = d.z;
  }
  /* Cubic net in _tlod_tri_net order: 300 030 003 210 120 021 012 102 201 111.
   * c_{2x+y} = 2 alpha_x d_xy / 3, c_111 = (alpha_i d_jk + alpha_j d_ki + alpha_k d_ij) / 3. */
  const double* a_ij = dev[0];
  const double* a_jk = dev[1];
  const double* a_ki = dev[2];
  for (int k = 0; k < 3; k++) {
    net[0][k] = net[1][k] = net[2][k] = 0.0;
    net[3][k] = 2.0 * c->alpha[0] * a_ij[k] / 3.0; /* 210: J = 200 (0) or 110 (d_ij) with K = 100 */
    net[4][k] = 2.0 * c->alpha[1] * a_ij[k] / 3.0; /* 120 */
    net[5][k] = 2.0 * c->alpha[1] * a_jk[k] / 3.0; /* 021 */
    net[6][k] = 2.0 * c->alpha[2] * a_jk[k] / 3.0; /* 012 */
    net[7][k] = 2.0 * c->alpha[2] * a_ki[k] / 3.0; /* 102 */
    net[8][k] = 2.0 * c->alpha[0] * a_ki[k] / 3.0; /* 201 */
    net[9][k] = (c->alpha[0] * a_jk[k] + c->alpha[1] * a_ki[k] + c->alpha[2] * a_ij[k]) / 3.0;
  }
}

float _tlod_phong_alpha_bound(const _tlod_corners* c) {
  double net[10][3];
  _tlod_phong_alpha_net(c, net);
  return _tlod_tri_net_bound(net, c);
}

/* Quad: P is a polynomial of bidegree (3, 3) at most (bilinear alpha times a
 * biquadratic), so 16 samples give its tensor Bezier net exactly (up to
 * rounding), and the nets of P_uu, P_vv, P_uv bound the second derivatives
 * (convex hull). Linear interpolation over a right triangle with legs h errs
 * by at most (1/2) M R^2 with R^2 = h^2 / 2 (Taylor at the circumcentre), M
 * bounding |d2P/ds2| over unit directions s: so the level-l pattern is within
 * 4^-l * M / 4 of the surface. The same holds for the flat (bilinear) quad,
 * whose two level-0 triangles differ from it where it is not planar. */
/* b may alias f (the second pass converts in place). */
static void cubic_net(const double f[4], double b[4]) {
  double f0 = f[0], f1 = f[1], f2 = f[2], f3 = f[3];
  b[0] = f0;
  b[1] = (-5.0 * f0 + 18.0 * f1 - 9.0 * f2 + 2.0 * f3) * (1.0 / 6.0);
  b[2] = (2.0 * f0 - 9.0 * f1 + 18.0 * f2 - 5.0 * f3) * (1.0 / 6.0);
  b[3] = f3;
}

double _tlod_norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* Slack for float rounding, relative to the patch's extent. */
double _tlod_bound_slack(const _tlod_corners* c) {
  double extent = 0.0;
  for (uint32_t x = 1; x < c->n; x++) {
    double e[3] = {c->p[x].x - c->p[0].x, c->p[x].y - c->p[0].y, c->p[x].z - c->p[0].z};
    extent = fmax(extent, _tlod_norm3(e));
  }
  return 1e-6 * extent;
}

/* Triangle pattern cells are right triangles with legs h in (u, v), as quad
 * cells are, so the same (M / 4) 4^-l bound holds with M from the cubic net:
 * P_uu, P_vv, P_uv have nets 6 * second differences along (e_u - e_w),
 * (e_v - e_w). Net order: 300 030 003 210 120 021 012 102 201 111. */
float _tlod_tri_net_bound(const double net[10][3], const _tlod_corners* c) {
  /* index of b_{ijk} */
  static const int at[4][4][4] = {
      [3][0][0] = 0, [0][3][0] = 1, [0][0][3] = 2, [2][1][0] = 3, [1][2][0] = 4,
      [0][2][1] = 5, [0][1][2] = 6, [1][0][2] = 7, [2][0][1] = 8, [1][1][1] = 9,
  };
  static const int base[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double uu = 0.0, vv = 0.0, uv = 0.0, d[3];
  for (int b = 0; b < 3; b++) {
    int i = base[b][0], j = base[b][1], k = base[b][2];
    for (int x = 0; x < 3; x++) {
      d[x] = 6.0 * (net[at[i + 2][j][k]][x] - 2.0 * net[at[i + 1][j][k + 1]][x] + net[at[i][j][k + 2]][x]);
    }
    uu = fmax(uu, _tlod_norm3(d));
    for (int x = 0; x < 3; x++) {
      d[x] = 6.0 * (net[at[i][j + 2][k]][x] - 2.0 * net[at[i][j + 1][k + 1]][x] + net[at[i][j][k + 2]][x]);
    }
    vv = fmax(vv, _tlod_norm3(d));
    for (int x = 0; x < 3; x++) {
      d[x] = 6.0 * (net[at[i + 1][j + 1][k]][x] - net[at[i + 1][j][k + 1]][x] - net[at[i][j + 1][k + 1]][x] +
                    net[at[i][j][k + 2]][x]);
    }
    uv = fmax(uv, _tlod_norm3(d));
  }
  return (float)((fmax(uu, vv) + uv) / 4.0 + _tlod_bound_slack(c));
}

void _tlod_quad_net(const _tlod_corners* c, double net[4][4][3]) {
  double f[4][4][3];
  for (int i = 0; i < 4; i++) {
    for (int j = 0; j < 4; j++) {
      tlod_surface_point pt;
      _tlod_phong_eval(c, (float)i / 3.0f, (float)j / 3.0f, 0, &pt);
      for (int k = 0; k < 3; k++)
        f[i][j][k] = pt.position[k];
    }
  }
  for (int k = 0; k < 3; k++) {
    double tmp[4][4];
    for (int j = 0; j < 4; j++) {
      double col[4] = {f[0][j][k], f[1][j][k], f[2][j][k], f[3][j][k]}, b[4];
      cubic_net(col, b);
      for (int i = 0; i < 4; i++)
        tmp[i][j] = b[i];
    }
    for (int i = 0; i < 4; i++)
      cubic_net(tmp[i], tmp[i]);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++)
        net[i][j][k] = tmp[i][j];
  }
}

/* Squared norms first, one sqrt per maximum at the end: sqrt is correctly
 * rounded and monotone, so the result is bitwise the maximum of the norms
 * (33 square roots fewer per quad patch). */
static inline double len2_max(double m, const double d[3]) {
  double x = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  return x > m ? x : m;
}

double _tlod_quad_net_m(const double net[4][4][3]) {
  double uu = 0.0, vv = 0.0, uv = 0.0, d[3];
  for (int i = 0; i < 4; i++) {
    for (int j = 0; j < 4; j++) {
      if (i < 2) {
        for (int k = 0; k < 3; k++)
          d[k] = 6.0 * (net[i + 2][j][k] - 2.0 * net[i + 1][j][k] + net[i][j][k]);
        uu = len2_max(uu, d);
      }
      if (j < 2) {
        for (int k = 0; k < 3; k++)
          d[k] = 6.0 * (net[i][j + 2][k] - 2.0 * net[i][j + 1][k] + net[i][j][k]);
        vv = len2_max(vv, d);
      }
      if (i < 3 && j < 3) {
        for (int k = 0; k < 3; k++)
          d[k] = 9.0 * (net[i + 1][j + 1][k] - net[i + 1][j][k] - net[i][j + 1][k] + net[i][j][k]);
        uv = len2_max(uv, d);
      }
    }
  }
  return fmax(sqrt(uu), sqrt(vv)) + sqrt(uv);
}

float _tlod_quad_net_bound(const double net[4][4][3], const _tlod_corners* c, float* d_max) {
  double bound = _tlod_quad_net_m(net) / 4.0 + _tlod_bound_slack(c);
  *d_max = (float)bound;
  return (float)bound;
}

float _tlod_quad_bound(const _tlod_corners* c, float* d_max) {
  double net[4][4][3];
  _tlod_quad_net(c, net);
  return _tlod_quad_net_bound(net, c, d_max);
}
