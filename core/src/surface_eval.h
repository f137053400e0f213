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

/* Flat: the input triangle, the bilinear quad. */
void _tlod_flat_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm);
void _tlod_flat_eval(const _tlod_corners* c, float u, float v, tlod_surface_point* out);

/* PN triangles (Vlachos et al. 2001), bound per Schwarz et al. 2006. */
void _tlod_pn_build(const _tlod_corners* c, _tlod_pn_patch* out);
void _tlod_pn_edge(v3 pa, v3 na, v3 pb, v3 nb, float t, v3* pos, v3* nrm);
/* Normals blend the corner normals of c with the patch's mid-edge normals. */
void _tlod_pn_eval(const _tlod_pn_patch* patch, const _tlod_corners* c, float u, float v, uint32_t flags,
                   tlod_surface_point* out);
/* d_max: the paper's d'_max; returns max(9/4 d'_max, the second-derivative bound). */
float _tlod_pn_bound(const _tlod_pn_patch* patch, const _tlod_corners* c, float* d_max);

/* error_table.c: per-level error tables (issue #9, docs/design.md "Error
 * tables"). Fills error_table, error_tail and error_slack of info. net: the
 * cubic triangle net of surface minus flat patch (per-vertex-alpha Phong)
 * or of the surface (PN); NULL for flat and global-alpha Phong triangles.
 * quad_net: the tensor net of a quad (Phong; NULL for flat quads). */
void _tlod_error_table(tlod_surface_type type, const _tlod_corners* c, const double (*net)[3],
                       const double (*quad_net)[4][3], tlod_patch_info* info);
/* TLOD_ERROR_TABLES_CLOSED_FORM: the table from info->error_bound (already
 * set) alone, error_bound * 4^-l plus the measured tables' evaluation slack
 * (pn_net: the PN control net, NULL for other surfaces). */
void _tlod_error_table_closed(const _tlod_corners* c, const float (*pn_net)[3], tlod_patch_info* info);

/* surface.c: a patch's corner data, and evaluation with those corners
 * gathered once (tangents only when flags ask). */
void _tlod_patch_corners(const tlod_surface* s, uint32_t patch, _tlod_corners* c);
void _tlod_patch_eval_with(const tlod_surface* s, uint32_t patch, const _tlod_corners* c, float u, float v,
                           uint32_t flags, tlod_surface_point* out);

#endif
