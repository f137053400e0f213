/* Private: per-surface-type evaluation kernels (phong.c, pn_triangle.c). */
#ifndef TESSLOD_SURFACE_EVAL_H
#define TESSLOD_SURFACE_EVAL_H

#include "internal.h"
#include "vec3.h"

/* The corner data of one patch, gathered from the mesh. */
typedef struct _tlod_corners {
  uint32_t n; /* 3 or 4 */
  v3 p[4];
  v3 nrm[4];
  float alpha[4];
} _tlod_corners;

/* Evaluation flags: tangents wanted; shading normal from the tangents. */
enum { _TLOD_EVAL_DERIVS = 1, _TLOD_EVAL_TRUE_NORMAL = 2 };

/* Phong (Boubekeur & Alexa 2008; quads: Dupuy). The edge function is shared by
 * triangles and quads: on an edge both reduce to it exactly. */
void _tlod_phong_edge(v3 pa, v3 na, float alpha_a, v3 pb, v3 nb, float alpha_b, float t, v3* pos, v3* nrm);
/* Its position alone (positions-only callers skip the normal's square root
 * and division); _tlod_phong_edge takes its position from here, so both
 * round alike. */
static inline v3 _tlod_phong_edge_position(v3 pa, v3 na, float alpha_a, v3 pb, v3 nb, float alpha_b, float t) {
  float s = 1.0f - t;
  v3 p = v3_mix2(pa, s, pb, t);
  float alpha = alpha_a * s + alpha_b * t;
  v3 proj = v3_mix2(v3_project(p, pa, na), s, v3_project(p, pb, nb), t);
  return v3_mix2(p, 1.0f - alpha, proj, alpha);
}
/* Triangle or quad by c->n. */
void _tlod_phong_eval(const _tlod_corners* c, float u, float v, uint32_t flags, tlod_surface_point* out);
/* Bound on |surface - flat patch| and the d_max it comes from. alpha_net:
 * _tlod_phong_alpha_net of c when its alphas differ (NULL: computed here). */
float _tlod_phong_tri_bound(const _tlod_corners* c, const double (*alpha_net)[3], float* d_max);
/* Bounds from second derivatives (phong.c): the level-l pattern is within
 * 4^-l times the result. _tlod_tri_net_bound takes a cubic triangle net. */
float _tlod_tri_net_bound(const double net[10][3], const _tlod_corners* c);
float _tlod_phong_alpha_bound(const _tlod_corners* c);
double _tlod_norm3(const double v[3]);
double _tlod_bound_slack(const _tlod_corners* c);
/* Quads, Phong or flat (alphas zero): from the second derivatives. */
float _tlod_quad_bound(const _tlod_corners* c, float* d_max);
/* The pieces of the two above: the per-vertex-alpha deviation net (surface
 * minus flat patch, cubic, corners zero, _tlod_tri_net order); the quad's
 * tensor Bezier net (bidegree 3, from 16 evaluations); M bounding
 * |d2P/ds2| over unit directions s from that net; the old bound from it. */
void _tlod_phong_alpha_net(const _tlod_corners* c, double net[10][3]);
void _tlod_quad_net(const _tlod_corners* c, double net[4][4][3]);
double _tlod_quad_net_m(const double net[4][4][3]);
float _tlod_quad_net_bound(const double net[4][4][3], const _tlod_corners* c, float* d_max);

/* The interpolated shading normal: normalize(sum of corner weights *
 * corner normals), the first corner's where that cancels (Phong, flat and
 * quadratic faces). */
v3 _tlod_corner_normal(const _tlod_corners* c, float u, float v);

/* Flat: the input triangle, the bilinear quad. */
void _tlod_flat_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm);
void _tlod_flat_eval(const _tlod_corners* c, float u, float v, tlod_surface_point* out);

/* PN triangles (Vlachos et al. 2001), bound per Schwarz et al. 2006. */
void _tlod_pn_build(const _tlod_corners* c, _tlod_pn_patch* out);
void _tlod_pn_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm);
/* _tlod_pn_edge in two steps: the edge's cubic control points and mid-edge
 * normal once (an edge's many points), then a point at t; bitwise the same. */
typedef struct _tlod_pn_edge_ctl {
  v3 pa, na, pb, nb, bab, bba, nab;
} _tlod_pn_edge_ctl;
void _tlod_pn_edge_build(v3 pa, v3 na, v3 pb, v3 nb, _tlod_pn_edge_ctl* e);
void _tlod_pn_edge_at(const _tlod_pn_edge_ctl* e, float t, v3* pos, v3* nrm);
/* Normals blend the corner normals of c with the patch's mid-edge normals. */
void _tlod_pn_eval(const _tlod_pn_patch* patch, const _tlod_corners* c, float u, float v, uint32_t flags,
                   tlod_surface_point* out);
/* d_max: the paper's d'_max; returns max(9/4 d'_max, the second-derivative bound). */
float _tlod_pn_bound(const _tlod_pn_patch* patch, const _tlod_corners* c, float* d_max);

/* Quadratic faces (quadratic.c). The canonical edge function through the
 * edge's node m; one patch (u, v) with tangents and the interpolated normal;
 * the patch's resolved nodes, bounds, sphere and error tables; edge e of a
 * patch in canonical direction a -> b (mesh vertices). */
void _tlod_quadratic_edge(v3 pa, v3 na, v3 pb, v3 nb, v3 m, float t, v3* pos, v3* nrm);
void _tlod_quadratic_eval(const _tlod_quad_patch* q, const _tlod_corners* c, float u, float v, tlod_surface_point* out);
void _tlod_quadratic_build(const tlod_surface* s, uint32_t f, const _tlod_corners* c, _tlod_quad_patch* q,
                           tlod_patch_info* info);
void _tlod_quadratic_edge_point(const tlod_surface* s, uint32_t patch, uint32_t edge, uint32_t a, uint32_t b, float t,
                                float pos[3], float nrm[3]);

/* error_table.c: per-level error tables (issue #9, docs/design.md "Error
 * tables"). Fills error_table, error_tail and error_slack of info. net: the
 * cubic triangle net of surface minus flat patch (per-vertex-alpha Phong)
 * or of the surface (PN); NULL for flat and global-alpha Phong triangles.
 * quad_net: the tensor net of a quad (Phong; NULL for flat quads). */
void _tlod_error_table(tlod_surface_type type, const _tlod_corners* c, const double (*net)[3],
                       const double (*quad_net)[4][3], tlod_patch_info* info);
/* TLOD_ERROR_TABLES_CLOSED_FORM: the table from info->error_bound (already
 * set) alone, error_bound * 4^-l plus the measured tables' evaluation slack
 * (extra: points besides the corners the evaluation reads, the PN control
 * net or a quadratic face's nodes; extra_n 0 for other surfaces). */
void _tlod_error_table_closed(const _tlod_corners* c, const double (*extra)[3], int extra_n, tlod_patch_info* info);
/* Quadratic faces: a triangle's edge deviations dev[e] = 2 (M_e - mid_e)
 * (S - flat = 2 sum l_i l_j dev_ij), or a quad's bicubic net (its
 * biquadratic degree-elevated); nodes: the resolved nodes (for the slack). */
void _tlod_error_table_quadratic(const _tlod_corners* c, const double (*dev)[3], const double (*quad_net)[4][3],
                                 const double (*nodes)[3], int node_n, tlod_patch_info* info);
/* Its TLOD_ERROR_TABLES_CLOSED_FORM table (error_bound 4^-l, the same slack). */
void _tlod_error_table_quadratic_closed(const _tlod_corners* c, const double (*nodes)[3], int node_n,
                                        tlod_patch_info* info);

/* surface.c: a bounding sphere about the corners' centroid through the
 * corners and extra points, radius grown by grow (and a relative slack). */
void _tlod_sphere_of(const _tlod_corners* c, const v3* extra, uint32_t extra_n, float grow, tlod_patch_info* info);
/* surface.c: a patch's corner data, and evaluation with those corners
 * gathered once (tangents only when flags ask). */
void _tlod_patch_corners(const tlod_surface* s, uint32_t patch, _tlod_corners* c);
void _tlod_patch_eval_with(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, float u, float v,
                           uint32_t flags, tlod_surface_point* out);

#endif
