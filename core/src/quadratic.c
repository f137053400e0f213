/* tesslod::core -- second-order (isoparametric quadratic) faces (issue 14):
 * the 6-node triangle and the 9-node biquadratic Lagrange quad through the
 * face's nodes, as the finite-element solver evaluates them. A missing node
 * is the neighbour's (shared at mesh creation) or else the Phong node, so a
 * linear face is its Phong patch; an 8-node (serendipity) quad is the
 * biquadratic with the serendipity centre, the same surface.
 * Maths, the error bound and the node rules: docs/design.md "Quadratic faces".
 *
 * This work is based on:
 *   O. C. Zienkiewicz, R. L. Taylor. The Finite Element Method, vol. 1
 *   (Lagrange and serendipity shape functions).
 *   T. Boubekeur, M. Alexa. Phong Tessellation. ACM TOG 27(5), 2008 (the
 *   Phong triangle is the quadratic triangle through its Phong nodes).
 */
#include <string.h>

#include "surface_eval.h"

static double comp(v3 a, int k) { return k == 0 ? a.x : (k == 1 ? a.y : a.z); }

/* The canonical edge function (docs/design.md 3.4), in exactly this order so
 * the GLSL (`precise`) rounds the same way: t = 0 gives a, t = 1 gives b. */
void _tlod_quadratic_edge(v3 pa, v3 na, v3 pb, v3 nb, v3 m, float t, v3* pos, v3* nrm) {
  float s = 1.0f - t;
  float wa = s * (s - t), wb = t * (t - s), wm = 4.0f * s * t;
  *pos = v3_add(v3_add(v3_scale(pa, wa), v3_scale(pb, wb)), v3_scale(m, wm));
  *nrm = v3_normalize_or(v3_mix2(na, s, nb, t), na);
}

/* The Phong edge's midpoint, (p_a + p_b)/2 - alpha/4 D with D = ((p_b -
 * p_a).n_a) n_a + ((p_a - p_b).n_b) n_b and alpha the ends' mean. Every
 * operation is symmetric in a and b (float + and * commute), so both faces
 * of an edge get the same bits whichever way they list it. */
static v3 phong_node(v3 pa, v3 na, float aa, v3 pb, v3 nb, float ab) {
  v3 d = v3_add(v3_scale(na, v3_dot(v3_sub(pb, pa), na)), v3_scale(nb, v3_dot(v3_sub(pa, pb), nb)));
  float alpha = 0.5f * (aa + ab);
  return v3_sub(v3_scale(v3_add(pa, pb), 0.5f), v3_scale(d, 0.25f * alpha));
}

/* C = -1/4 (P0 + P1 + P2 + P3) + 1/2 (M0 + M1 + M2 + M3), in double: the
 * centre that makes the biquadratic the 8-node serendipity surface. */
static void serendipity_centre(const _tlod_corners* c, const _tlod_quad_patch* q, float out[3]) {
  for (int k = 0; k < 3; k++) {
    double corners = 0.0, mids = 0.0;
    for (int i = 0; i < 4; i++)
      corners += comp(c->p[i], k), mids += q->node[i][k];
    out[k] = (float)(0.5 * mids - 0.25 * corners);
  }
}

static void resolve_centre(const tlod_mesh* m, const uint32_t* nodes, const _tlod_corners* c, _tlod_quad_patch* q) {
  bool any_edge = false;
  for (int e = 0; nodes && e < 4; e++)
    any_edge = any_edge || nodes[e] != _TLOD_NONE;
  if (nodes && nodes[4] != _TLOD_NONE) {
    memcpy(q->node[4], m->positions[nodes[4]], sizeof(q->node[4]));
  } else if (any_edge) {
    serendipity_centre(c, q, q->node[4]);
  } else {
    tlod_surface_point pt; /* the Phong quad is biquadratic: its centre completes it */
    _tlod_phong_eval(c, 0.5f, 0.5f, 0, &pt);
    memcpy(q->node[4], pt.position, sizeof(q->node[4]));
  }
}

/* Given or shared nodes from the mesh, the Phong node elsewhere, and a quad's centre. */
static void resolve_nodes(const tlod_surface* s, uint32_t f, const _tlod_corners* c, _tlod_quad_patch* q) {
  const tlod_mesh* m = s->mesh;
  const uint32_t* nodes = m->face_nodes ? m->face_nodes[f] : NULL;
  memset(q, 0, sizeof(*q));
  for (uint32_t e = 0; e < c->n; e++) {
    uint32_t v = nodes ? nodes[e] : _TLOD_NONE, b = (e + 1) % c->n;
    v3 x = v != _TLOD_NONE ? v3_load(m->positions[v])
                           : phong_node(c->p[e], c->nrm[e], c->alpha[e], c->p[b], c->nrm[b], c->alpha[b]);
    v3_store(q->node[e], x);
  }
  if (c->n == 4) resolve_centre(m, nodes, c, q);
  q->given = m->node_given && m->node_given[f] ? 1u : 0u;
}

/* ------------------------------------------------------------------------ */
/* Evaluation                                                               */
/* ------------------------------------------------------------------------ */

static v3 weighted(const v3* x, const float* w, int n) {
  v3 r = v3_scale(x[0], w[0]);
  for (int i = 1; i < n; i++)
    r = v3_add(r, v3_scale(x[i], w[i]));
  return r;
}

/* P = sum l_i (2 l_i - 1) P_i + 4 l0 l1 M0 + 4 l1 l2 M1 + 4 l2 l0 M2, l = (u, v, w). */
static void eval_triangle(const _tlod_quad_patch* q, const _tlod_corners* c, float u, float v, v3 out[3]) {
  float w = 1.0f - u - v;
  v3 x[6] = {c->p[0], c->p[1], c->p[2], v3_load(q->node[0]), v3_load(q->node[1]), v3_load(q->node[2])};
  float k[6] = {u * (2.0f * u - 1.0f), v * (2.0f * v - 1.0f), w * (2.0f * w - 1.0f),
                4.0f * u * v,          4.0f * v * w,          4.0f * w * u};
  float ku[6] = {4.0f * u - 1.0f, 0.0f, 1.0f - 4.0f * w, 4.0f * v, -4.0f * v, 4.0f * (w - u)};
  float kv[6] = {0.0f, 4.0f * v - 1.0f, 1.0f - 4.0f * w, 4.0f * u, 4.0f * (w - v), -4.0f * u};
  out[0] = weighted(x, k, 6), out[1] = weighted(x, ku, 6), out[2] = weighted(x, kv, 6);
}

/* 1D quadratic Lagrange basis at t = 0, 1/2, 1 and its derivative. */
static void lagrange(float t, float l[3], float dl[3]) {
  float s = 1.0f - t;
  l[0] = s * (1.0f - 2.0f * t), l[1] = 4.0f * t * s, l[2] = t * (2.0f * t - 1.0f);
  dl[0] = 4.0f * t - 3.0f, dl[1] = 4.0f - 8.0f * t, dl[2] = 4.0f * t - 1.0f;
}

/* The 3 x 3 nodes X[a][b] at (a/2, b/2), row-major in a (u). */
static void quad_nodes(const _tlod_quad_patch* q, const _tlod_corners* c, v3 x[9]) {
  x[0] = c->p[0], x[1] = v3_load(q->node[3]), x[2] = c->p[3];
  x[3] = v3_load(q->node[0]), x[4] = v3_load(q->node[4]), x[5] = v3_load(q->node[2]);
  x[6] = c->p[1], x[7] = v3_load(q->node[1]), x[8] = c->p[2];
}

/* P = sum_ab L_a(u) L_b(v) X_ab. */
static void eval_quad(const _tlod_quad_patch* q, const _tlod_corners* c, float u, float v, v3 out[3]) {
  v3 x[9];
  quad_nodes(q, c, x);
  float lu[3], du[3], lv[3], dv[3], k[9], ku[9], kv[9];
  lagrange(u, lu, du), lagrange(v, lv, dv);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      k[3 * a + b] = lu[a] * lv[b], ku[3 * a + b] = du[a] * lv[b], kv[3 * a + b] = lu[a] * dv[b];
  out[0] = weighted(x, k, 9), out[1] = weighted(x, ku, 9), out[2] = weighted(x, kv, 9);
}

void _tlod_quadratic_eval(const _tlod_quad_patch* q, const _tlod_corners* c, float u, float v,
                          tlod_surface_point* out) {
  v3 r[3];
  if (c->n == 3)
    eval_triangle(q, c, u, v, r);
  else
    eval_quad(q, c, u, v, r);
  v3_store(out->position, r[0]);
  v3_store(out->tangent, r[1]);
  v3_store(out->bitangent, r[2]);
  v3_store(out->normal, _tlod_corner_normal(c, u, v));
}

/* ------------------------------------------------------------------------ */
/* Precomputation: nodes, bounds, tables, sphere                            */
/* ------------------------------------------------------------------------ */

/* Triangle: S - flat = 2 sum l_i l_j dev_ij with dev = 2 (M - mid) (the
 * Phong form, alpha d -> dev), |S - flat| <= (2/3) max |dev|; the edge's
 * quadratic Bezier point is 2 M - (a + b) / 2 = mid + dev. */
static float triangle_bound(const _tlod_corners* c, const _tlod_quad_patch* q, double dev[3][3], v3 bez[6],
                            float* d_max) {
  double worst = 0.0;
  for (uint32_t e = 0; e < 3; e++) {
    v3 a = c->p[e], b = c->p[(e + 1) % 3];
    float p[3];
    for (int k = 0; k < 3; k++) {
      double mid = 0.5 * (comp(a, k) + comp(b, k));
      dev[e][k] = 2.0 * ((double)q->node[e][k] - mid);
      p[k] = (float)(mid + dev[e][k]);
    }
    worst = fmax(worst, _tlod_norm3(dev[e]));
    bez[e] = c->p[e], bez[3 + e] = v3_load(p);
  }
  *d_max = (float)worst;
  return (float)(worst * (2.0 / 3.0) + _tlod_bound_slack(c));
}

/* Lagrange values at 0, 1/2, 1 to the quadratic Bezier coefficients. */
static void lagrange_to_bezier(const double x[3], double out[3]) {
  out[0] = x[0], out[1] = 2.0 * x[1] - 0.5 * (x[0] + x[2]), out[2] = x[2];
}

/* Degree elevation of a quadratic Bezier row to the cubic one. */
static void elevate(const double b[3], double out[4]) {
  out[0] = b[0], out[1] = (b[0] + 2.0 * b[1]) / 3.0, out[2] = (2.0 * b[1] + b[2]) / 3.0, out[3] = b[2];
}

/* Per axis k the biquadratic Bezier net bq[a][b] of the nodes x[3a + b]. */
static void quad_bezier(const v3 x[9], int k, double bq[3][3]) {
  double t[3][3];
  for (int a = 0; a < 3; a++) { /* along v for each u node */
    double row[3] = {comp(x[3 * a], k), comp(x[3 * a + 1], k), comp(x[3 * a + 2], k)};
    lagrange_to_bezier(row, t[a]);
  }
  for (int b = 0; b < 3; b++) { /* then along u */
    double col[3] = {t[0][b], t[1][b], t[2][b]}, out[3];
    lagrange_to_bezier(col, out);
    for (int a = 0; a < 3; a++)
      bq[a][b] = out[a];
  }
}

/* Quad: the biquadratic's bicubic tensor net (phong.c's layout, net[i][j]
 * at u = i/3, v = j/3 in Bezier terms) and its 9 Bezier points. */
static void quad_net(const _tlod_corners* c, const _tlod_quad_patch* q, double net[4][4][3], v3 bez[9]) {
  v3 x[9];
  quad_nodes(q, c, x);
  float pts[9][3];
  for (int k = 0; k < 3; k++) {
    double bq[3][3], t[3][4];
    quad_bezier(x, k, bq);
    for (int a = 0; a < 3; a++)
      elevate(bq[a], t[a]);
    for (int j = 0; j < 4; j++) {
      double col[3] = {t[0][j], t[1][j], t[2][j]}, out[4];
      elevate(col, out);
      for (int i = 0; i < 4; i++)
        net[i][j][k] = out[i];
    }
    for (int i = 0; i < 9; i++)
      pts[i][k] = (float)bq[i / 3][i % 3];
  }
  for (int i = 0; i < 9; i++)
    bez[i] = v3_load(pts[i]);
}

/* The smaller of two rigorous spheres about the corners' centroid: the
 * Bezier control points' (convex hull) and the corners' grown by the bound. */
static void patch_sphere(const _tlod_corners* c, const v3* bez, uint32_t nb, tlod_patch_info* info) {
  tlod_patch_info grown = *info;
  _tlod_sphere_of(c, bez, nb, 0.0f, info);
  _tlod_sphere_of(c, NULL, 0, info->error_bound, &grown);
  if (grown.radius < info->radius) info->radius = grown.radius;
}

void _tlod_quadratic_build(const tlod_surface* s, uint32_t f, const _tlod_corners* c, _tlod_quad_patch* q,
                           tlod_patch_info* info) {
  resolve_nodes(s, f, c, q);
  double dev[3][3], net[4][4][3], nodes[5][3];
  v3 bez[9];
  int nn = c->n == 4 ? 5 : 3;
  for (int i = 0; i < nn; i++)
    for (int k = 0; k < 3; k++)
      nodes[i][k] = q->node[i][k];
  if (c->n == 3) {
    info->error_bound = triangle_bound(c, q, dev, bez, &info->d_max);
  } else {
    quad_net(c, q, net, bez);
    info->error_bound = _tlod_quad_net_bound((const double(*)[4][3])net, c, &info->d_max);
  }
  patch_sphere(c, bez, c->n == 4 ? 9 : 6, info);
  if (s->desc.error_tables != TLOD_ERROR_TABLES_MEASURED) /* NONE: overwritten by surface.c */
    _tlod_error_table_quadratic_closed(c, (const double(*)[3])nodes, nn, info);
  else
    _tlod_error_table_quadratic(c, c->n == 3 ? (const double(*)[3])dev : NULL,
                                c->n == 4 ? (const double(*)[4][3])net : NULL, (const double(*)[3])nodes, nn, info);
}

/* Edge e of a patch in canonical direction a -> b (a, b mesh vertices). */
void _tlod_quadratic_edge_point(const tlod_surface* s, uint32_t patch, uint32_t edge, uint32_t a, uint32_t b, float t,
                                float pos[3], float nrm[3]) {
  const tlod_mesh* m = s->mesh;
  v3 p, n;
  _tlod_quadratic_edge(v3_load(m->positions[a]), v3_load(m->normals[a]), v3_load(m->positions[b]),
                       v3_load(m->normals[b]), v3_load(s->quad[patch].node[edge]), t, &p, &n);
  v3_store(pos, p);
  v3_store(nrm, n);
}
