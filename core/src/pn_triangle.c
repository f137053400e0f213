/* tesslod::core -- curved PN triangles: cubic geometry, quadratic normals.
 *
 * This work is based on:
 *   A. Vlachos, J. Peters, C. Boyd, J. L. Mitchell. Curved PN Triangles.
 *   I3D 2001 (control points, normal field; its normal blend uses unit
 *   coefficients on the mid-edge terms, kept here as every implementation does).
 *   M. Schwarz, M. Staginski, M. Stamminger. GPU-based rendering of PN
 *   triangle meshes with adaptive tessellation. VMV 2006 (error bound 9/4 d'_max).
 * Control point order: b300 b030 b003 b210 b120 b021 b012 b102 b201 b111. */
#include "surface_eval.h"

enum { B300, B030, B003, B210, B120, B021, B012, B102, B201, B111 };

/* Tangent control point next to pi on edge pi -> pj. */
static v3 tangent_point(v3 pi, v3 ni, v3 pj) {
  float w = v3_dot(v3_sub(pj, pi), ni);
  return v3_scale(v3_sub(v3_add(v3_scale(pi, 2.0f), pj), v3_scale(ni, w)), 1.0f / 3.0f);
}

/* Mid-edge normal: the average normal reflected in the plane
 * perpendicular to the edge (Vlachos eq. for n110). */
static v3 mid_normal(v3 pi, v3 ni, v3 pj, v3 nj) {
  v3 d = v3_sub(pj, pi);
  float dd = v3_dot(d, d);
  v3 sum = v3_add(ni, nj);
  float vij = dd > 0.0f ? 2.0f * v3_dot(d, sum) / dd : 0.0f;
  v3 n = v3_normalize(v3_sub(sum, v3_scale(d, vij)));
  /* Opposite normals cancel; fall back on the first so nothing is NaN. */
  return (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) ? ni : n;
}

void _tlod_pn_build(const _tlod_corners* c, _tlod_pn_patch* out) {
  const v3 *p = c->p, *n = c->nrm;
  v3 b[10];
  b[B300] = p[0];
  b[B030] = p[1];
  b[B003] = p[2];
  b[B210] = tangent_point(p[0], n[0], p[1]);
  b[B120] = tangent_point(p[1], n[1], p[0]);
  b[B021] = tangent_point(p[1], n[1], p[2]);
  b[B012] = tangent_point(p[2], n[2], p[1]);
  b[B102] = tangent_point(p[2], n[2], p[0]);
  b[B201] = tangent_point(p[0], n[0], p[2]);
  v3 e = b[B210];
  for (int i = B120; i <= B201; i++)
    e = v3_add(e, b[i]);
  e = v3_scale(e, 1.0f / 6.0f);
  v3 centroid = v3_scale(v3_add(v3_add(p[0], p[1]), p[2]), 1.0f / 3.0f);
  b[B111] = v3_add(e, v3_scale(v3_sub(e, centroid), 0.5f));
  for (int i = 0; i < 10; i++)
    v3_store(out->b[i], b[i]);
  v3_store(out->n[0], mid_normal(p[0], n[0], p[1], n[1]));
  v3_store(out->n[1], mid_normal(p[1], n[1], p[2], n[2]));
  v3_store(out->n[2], mid_normal(p[2], n[2], p[0], n[0]));
}

void _tlod_pn_edge_build(v3 pa, v3 na, v3 pb, v3 nb, _tlod_pn_edge_ctl* e) {
  e->pa = pa, e->na = na, e->pb = pb, e->nb = nb;
  e->bab = tangent_point(pa, na, pb);
  e->bba = tangent_point(pb, nb, pa);
  e->nab = mid_normal(pa, na, pb, nb);
}

void _tlod_pn_edge_at(const _tlod_pn_edge_ctl* e, float t, v3* pos, v3* nrm) {
  float s = 1.0f - t;
  float k0 = s * s * s, k1 = 3.0f * s * s * t, k2 = 3.0f * s * t * t, k3 = t * t * t;
  *pos = v3_add(v3_add(v3_add(v3_scale(e->pa, k0), v3_scale(e->bab, k1)), v3_scale(e->bba, k2)), v3_scale(e->pb, k3));
  v3 n = v3_add(v3_add(v3_scale(e->na, s * s), v3_scale(e->nab, s * t)), v3_scale(e->nb, t * t));
  v3 unit = v3_normalize(n);
  *nrm = (unit.x == 0.0f && unit.y == 0.0f && unit.z == 0.0f) ? e->na : unit;
}

void _tlod_pn_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm) {
  _tlod_pn_edge_ctl e;
  _tlod_pn_edge_build(pa, na, pb, nb, &e);
  _tlod_pn_edge_at(&e, t, pos, nrm);
}

static v3 ld(const _tlod_pn_patch* p, int i) { return v3_load(p->b[i]); }

/* Partials in (u, v, w); along the surface d/du = f_u - f_w, d/dv = f_v - f_w. */
static void pn_derivs(const _tlod_pn_patch* pt, float u, float v, float w, tlod_surface_point* out) {
  float uu = u * u, vv = v * v, ww = w * w;
  v3 fu = v3_scale(ld(pt, B300), 3.0f * uu);
  fu = v3_add(fu, v3_scale(ld(pt, B210), 6.0f * u * v));
  fu = v3_add(fu, v3_scale(ld(pt, B120), 3.0f * vv));
  fu = v3_add(fu, v3_scale(ld(pt, B201), 6.0f * u * w));
  fu = v3_add(fu, v3_scale(ld(pt, B102), 3.0f * ww));
  fu = v3_add(fu, v3_scale(ld(pt, B111), 6.0f * v * w));
  v3 fv = v3_scale(ld(pt, B030), 3.0f * vv);
  fv = v3_add(fv, v3_scale(ld(pt, B210), 3.0f * uu));
  fv = v3_add(fv, v3_scale(ld(pt, B120), 6.0f * u * v));
  fv = v3_add(fv, v3_scale(ld(pt, B021), 6.0f * v * w));
  fv = v3_add(fv, v3_scale(ld(pt, B012), 3.0f * ww));
  fv = v3_add(fv, v3_scale(ld(pt, B111), 6.0f * u * w));
  v3 fw = v3_scale(ld(pt, B003), 3.0f * ww);
  fw = v3_add(fw, v3_scale(ld(pt, B201), 3.0f * uu));
  fw = v3_add(fw, v3_scale(ld(pt, B021), 3.0f * vv));
  fw = v3_add(fw, v3_scale(ld(pt, B102), 6.0f * u * w));
  fw = v3_add(fw, v3_scale(ld(pt, B012), 6.0f * v * w));
  fw = v3_add(fw, v3_scale(ld(pt, B111), 6.0f * u * v));
  v3_store(out->tangent, v3_sub(fu, fw));
  v3_store(out->bitangent, v3_sub(fv, fw));
}

void _tlod_pn_eval(const _tlod_pn_patch* pt, const _tlod_corners* c, float u, float v, uint32_t flags,
                   tlod_surface_point* out) {
  float w = 1.0f - u - v;
  float uu = u * u, vv = v * v, ww = w * w;
  v3 pos = v3_scale(ld(pt, B300), uu * u);
  pos = v3_add(pos, v3_scale(ld(pt, B030), vv * v));
  pos = v3_add(pos, v3_scale(ld(pt, B003), ww * w));
  pos = v3_add(pos, v3_scale(ld(pt, B210), 3.0f * uu * v));
  pos = v3_add(pos, v3_scale(ld(pt, B120), 3.0f * u * vv));
  pos = v3_add(pos, v3_scale(ld(pt, B201), 3.0f * uu * w));
  pos = v3_add(pos, v3_scale(ld(pt, B021), 3.0f * vv * w));
  pos = v3_add(pos, v3_scale(ld(pt, B102), 3.0f * u * ww));
  pos = v3_add(pos, v3_scale(ld(pt, B012), 3.0f * v * ww));
  pos = v3_add(pos, v3_scale(ld(pt, B111), 6.0f * u * v * w));
  v3 n = v3_scale(c->nrm[0], uu);
  n = v3_add(n, v3_scale(c->nrm[1], vv));
  n = v3_add(n, v3_scale(c->nrm[2], ww));
  n = v3_add(n, v3_scale(v3_load(pt->n[0]), u * v));
  n = v3_add(n, v3_scale(v3_load(pt->n[1]), v * w));
  n = v3_add(n, v3_scale(v3_load(pt->n[2]), w * u));
  v3 unit = v3_normalize(n);
  bool zero = unit.x == 0.0f && unit.y == 0.0f && unit.z == 0.0f;
  v3_store(out->normal, zero ? c->nrm[0] : unit);
  v3_store(out->position, pos);
  if (flags & (_TLOD_EVAL_DERIVS | _TLOD_EVAL_TRUE_NORMAL)) pn_derivs(pt, u, v, w, out);
}

/* Distance of each tangent control point from its edge line: d'_max; the
 * paper bounds the level-l deviation by 4^-l * 9/4 * d'_max (Schwarz et al.,
 * sec. 3). */
float _tlod_pn_bound(const _tlod_pn_patch* pt, const _tlod_corners* c, float* d_max) {
  static const int pts[6][3] = {{B210, B300, B030}, {B120, B030, B300}, {B021, B030, B003},
                                {B012, B003, B030}, {B102, B003, B300}, {B201, B300, B003}};
  float d = 0.0f;
  for (int i = 0; i < 6; i++) {
    v3 b = ld(pt, pts[i][0]), a = ld(pt, pts[i][1]), e = v3_sub(ld(pt, pts[i][2]), a);
    float ee = v3_dot(e, e);
    v3 rel = v3_sub(b, a);
    v3 off = ee > 0.0f ? v3_sub(rel, v3_scale(e, v3_dot(rel, e) / ee)) : rel;
    float len = v3_length(off);
    d = len > d ? len : d;
  }
  *d_max = d;
  /* The paper's bound follows the edge curves; interior points can exceed it
   * (measured up to 4% on random triangles), so the rigorous one may win. */
  double net[10][3];
  for (int i = 0; i < 10; i++)
    for (int k = 0; k < 3; k++)
      net[i][k] = pt->b[i][k];
  float hessian = _tlod_tri_net_bound(net, c);
  return fmaxf(2.25f * d, hessian);
}
