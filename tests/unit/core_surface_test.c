/*
 * core_surface_test.c -- independent verification of the curved surfaces of
 * tesslod/core.h (Phong triangles, Phong quads, PN triangles, flat patches).
 * Owned by the verification tests. Reads private state: none (public API only).
 *
 * This work is based on: Boubekeur & Alexa 2008 (Phong tessellation), Dupuy
 * (Phong tessellation for quads), Vlachos et al. 2001 (curved PN triangles),
 * Schwarz, Staginski, Stamminger 2006 (error bound, refinement patterns), with
 * the corrections of docs/design.md.
 *
 * Every reference below is written from the papers and docs/design.md in double
 * precision, without reading the library's evaluation code. The library
 * evaluates in float from float inputs, so it is compared with the
 * reference evaluated on the very same float inputs (the mesh's final,
 * normalised normals and its positions, read back through the API).
 *
 * Tolerances (why each is what it is):
 *   EVAL_REL   1e-6   position error / patch size (longest edge); float
 *                     evaluation of a handful of products and sums of O(1)
 *                     coordinates costs a few ulps (2^-24 = 6e-8 each).
 *   FLAT_REL   1e-7   alpha = 0 or equal normals versus the library's own
 *                     flat patch (same float inputs), relative to
 *                     max(size, largest |coordinate|): 1.7 ulps of the
 *                     coordinates.
 *   FLAT_EXACT_REL 2.5e-7  the same versus the exact flat patch: a float
 *                     barycentric (bilinear) sum of 3 (4) products rounds
 *                     by up to ~2.5 ulps of the coordinates on its own.
 *   NORMAL_TOL 1e-5   unit normals (componentwise): a normalisation in float.
 *   DERIV_REL  1e-5   tangents / size, versus central differences of the double
 *                     reference (the reference is a polynomial; truncation
 *                     error of the difference is below 1e-9).
 *   REF_REL    1e-12  double reference versus double reference (identities).
 *   Error bound: measured <= error_bound * 4^-l + 1e-6 (float evaluation
 *                     slack); bounding sphere: |p - center| <= radius + 1e-6.
 *   Exact (memcmp) for corners and shared edges: docs/design.md invariants 1, 2.
 *   PN with equal normals is held to FLAT_EXACT_REL, not FLAT_REL (see
 *   test_equal_normals_are_flat).
 *
 * The error-bound tests take ~20 s under the sanitizers (a few million
 * evaluations); everything else is well under a second per test.
 */
#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "shapes.h"
#include "tesslod/core.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"

#define EVAL_REL 1e-6
#define FLAT_REL 1e-7
#define FLAT_EXACT_REL 2.5e-7
#define NORMAL_TOL 1e-5
#define DERIV_REL 1e-5
#define REF_REL 1e-12

/* ------------------------------------------------------------------------ */
/* Small double vector helpers                                              */
/* ------------------------------------------------------------------------ */

static void v_set(double o[3], double x, double y, double z) { o[0] = x, o[1] = y, o[2] = z; }
static void v_copy(double o[3], const double a[3]) { o[0] = a[0], o[1] = a[1], o[2] = a[2]; }
static void v_sub(double o[3], const double a[3], const double b[3]) {
  for (int c = 0; c < 3; ++c)
    o[c] = a[c] - b[c];
}
static void v_add(double o[3], const double a[3], const double b[3]) {
  for (int c = 0; c < 3; ++c)
    o[c] = a[c] + b[c];
}
static void v_scale(double o[3], const double a[3], double s) {
  for (int c = 0; c < 3; ++c)
    o[c] = a[c] * s;
}
/* o += s * a */
static void v_axpy(double o[3], double s, const double a[3]) {
  for (int c = 0; c < 3; ++c)
    o[c] += s * a[c];
}
static double v_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double v_len(const double a[3]) { return sqrt(v_dot(a, a)); }
static void v_cross(double o[3], const double a[3], const double b[3]) {
  double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  v_copy(o, t);
}
static void v_normalize(double a[3]) { v_scale(a, a, 1.0 / v_len(a)); }
static void v_from_f(double o[3], const float a[3]) { o[0] = a[0], o[1] = a[1], o[2] = a[2]; }
static double v_dist(const double a[3], const double b[3]) {
  double d[3];
  v_sub(d, a, b);
  return v_len(d);
}
/* Largest componentwise difference between a float and a double vector. */
static double v_maxdiff_f(const float a[3], const double b[3]) {
  double m = 0;
  for (int c = 0; c < 3; ++c)
    m = fmax(m, fabs((double)a[c] - b[c]));
  return m;
}
static double v_maxdiff(const double a[3], const double b[3]) {
  double m = 0;
  for (int c = 0; c < 3; ++c)
    m = fmax(m, fabs(a[c] - b[c]));
  return m;
}

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

static tlod_mesh* new_mesh(tlod_context* ctx, const tlod_mesh_desc* desc) {
  tlod_mesh* mesh = NULL;
  tlod_result r = tlod_mesh_create(ctx, desc, &mesh);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_mesh_create(%s): %s: %s\n", desc->label ? desc->label : "?", tlod_result_string(r),
            tlod_context_last_error(ctx));
    return NULL;
  }
  return mesh;
}

typedef struct surf_cfg {
  tlod_surface_type type;
  double alpha;      /* global alpha (Phong) */
  bool vertex_alpha; /* per-vertex alphas from the mesh */
  tlod_shading_normal shading;
} surf_cfg;

static tlod_surface* new_surface(tlod_context* ctx, const tlod_mesh* mesh, const surf_cfg* cfg) {
  tlod_surface_desc d = {.type = cfg->type,
                         .alpha_mode = cfg->vertex_alpha ? TLOD_ALPHA_PER_VERTEX : TLOD_ALPHA_GLOBAL,
                         .alpha = (float)cfg->alpha,
                         .shading_normal = cfg->shading,
                         .label = "test"};
  tlod_surface* s = NULL;
  tlod_result r = tlod_surface_create(ctx, mesh, &d, &s);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_surface_create: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
    return NULL;
  }
  return s;
}

/* One patch's inputs as the library holds them (final normals). */
typedef struct patch_ref {
  uint32_t n;
  uint32_t vid[4];
  float pf[4][3];
  double p[4][3], nrm[4][3], a[4];
  double size;  /* longest edge or diagonal */
  double scale; /* max(size, largest |coordinate|): the float resolution scale */
} patch_ref;

static patch_ref get_patch(const tlod_mesh* mesh, uint32_t face, const float* alphas) {
  patch_ref r;
  memset(&r, 0, sizeof r);
  r.n = tlod_mesh_face_corners(mesh, face, r.vid);
  for (uint32_t c = 0; c < r.n; ++c) {
    float nf[3];
    tlod_mesh_vertex(mesh, r.vid[c], r.pf[c], nf);
    v_from_f(r.p[c], r.pf[c]);
    v_from_f(r.nrm[c], nf);
    r.a[c] = alphas ? alphas[r.vid[c]] : 0.0;
  }
  for (uint32_t a = 0; a < r.n; ++a)
    for (uint32_t b = a + 1; b < r.n; ++b)
      r.size = fmax(r.size, v_dist(r.p[a], r.p[b]));
  r.scale = r.size;
  for (uint32_t a = 0; a < r.n; ++a)
    for (int c = 0; c < 3; ++c)
      r.scale = fmax(r.scale, fabs(r.p[a][c]));
  return r;
}

/* ------------------------------------------------------------------------ */
/* Reference surfaces (double)                                              */
/* ------------------------------------------------------------------------ */

/* pi_x(q) = q - ((q - p_x) . n_x) n_x */
static void project(double o[3], const double q[3], const double p[3], const double n[3]) {
  double d[3];
  v_sub(d, q, p);
  double s = v_dot(d, n);
  for (int c = 0; c < 3; ++c)
    o[c] = q[c] - s * n[c];
}

/* Phong triangle, projection form; alpha interpolated from a[] when
 * vertex_alpha, else the global one. */
static void ref_phong_tri(const patch_ref* r, double alpha, bool vertex_alpha, double u, double v, double out[3]) {
  double w = 1.0 - u - v, bw[3] = {u, v, w}, p[3] = {0, 0, 0}, proj[3] = {0, 0, 0};
  for (int x = 0; x < 3; ++x)
    v_axpy(p, bw[x], r->p[x]);
  for (int x = 0; x < 3; ++x) {
    double pi[3];
    project(pi, p, r->p[x], r->nrm[x]);
    v_axpy(proj, bw[x], pi);
  }
  double a = vertex_alpha ? u * r->a[0] + v * r->a[1] + w * r->a[2] : alpha;
  for (int c = 0; c < 3; ++c)
    out[c] = (1.0 - a) * p[c] + a * proj[c];
}

/* Phong triangle at alpha = 1, closed quadratic form of docs/design.md. */
static void ref_phong_tri_closed(const patch_ref* r, double u, double v, double out[3]) {
  double w = 1.0 - u - v, bw[3] = {u, v, w};
  v_set(out, 0, 0, 0);
  for (int x = 0; x < 3; ++x)
    v_axpy(out, bw[x] * bw[x], r->p[x]);
  for (int e = 0; e < 3; ++e) {
    int i = e, j = (e + 1) % 3;
    double a[3], b[3];
    project(a, r->p[j], r->p[i], r->nrm[i]); /* pi_i(p_j) */
    project(b, r->p[i], r->p[j], r->nrm[j]); /* pi_j(p_i) */
    v_axpy(out, bw[i] * bw[j], a);
    v_axpy(out, bw[i] * bw[j], b);
  }
}

/* PN control net b[i][j][k], i + j + k = 3: i powers u (corner 0 = P1), j
 * powers v (P2), k powers w (P3). */
typedef double pn_net[4][4][4][3];

static void pn_tangent_point(double o[3], const double pi[3], const double pj[3], const double ni[3]) {
  /* (2 P_i + P_j - w_ij N_i) / 3, w_ij = (P_j - P_i) . N_i */
  double d[3];
  v_sub(d, pj, pi);
  double wij = v_dot(d, ni);
  for (int c = 0; c < 3; ++c)
    o[c] = (2.0 * pi[c] + pj[c] - wij * ni[c]) / 3.0;
}

static void ref_pn_net(const patch_ref* r, pn_net b, bool schwarz_center) {
  memset(b, 0, sizeof(pn_net));
  const double *P1 = r->p[0], *P2 = r->p[1], *P3 = r->p[2];
  const double *N1 = r->nrm[0], *N2 = r->nrm[1], *N3 = r->nrm[2];
  v_copy(b[3][0][0], P1);
  v_copy(b[0][3][0], P2);
  v_copy(b[0][0][3], P3);
  pn_tangent_point(b[2][1][0], P1, P2, N1); /* b210 */
  pn_tangent_point(b[1][2][0], P2, P1, N2); /* b120 */
  pn_tangent_point(b[0][2][1], P2, P3, N2); /* b021 */
  pn_tangent_point(b[0][1][2], P3, P2, N3); /* b012 */
  pn_tangent_point(b[1][0][2], P3, P1, N3); /* b102 */
  pn_tangent_point(b[2][0][1], P1, P3, N1); /* b201 */
  double sum6[3] = {0, 0, 0}, sum3[3] = {0, 0, 0};
  v_add(sum6, sum6, b[2][1][0]);
  v_add(sum6, sum6, b[1][2][0]);
  v_add(sum6, sum6, b[0][2][1]);
  v_add(sum6, sum6, b[0][1][2]);
  v_add(sum6, sum6, b[1][0][2]);
  v_add(sum6, sum6, b[2][0][1]);
  v_add(sum3, P1, P2);
  v_add(sum3, sum3, P3);
  if (schwarz_center) {
    /* Schwarz et al.: 1/4 sum of the six - 1/6 sum of the corners */
    for (int c = 0; c < 3; ++c)
      b[1][1][1][c] = sum6[c] / 4.0 - sum3[c] / 6.0;
  } else {
    /* Vlachos: E + (E - V) / 2, E = sum6 / 6, V = sum3 / 3 */
    for (int c = 0; c < 3; ++c) {
      double E = sum6[c] / 6.0, V = sum3[c] / 3.0;
      b[1][1][1][c] = E + (E - V) / 2.0;
    }
  }
}

static double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

static void ref_pn_bernstein(pn_net b, double u, double v, double out[3]) {
  double w = 1.0 - u - v;
  v_set(out, 0, 0, 0);
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j + i <= 3; ++j) {
      int k = 3 - i - j;
      double coef = 6.0 / (factorial(i) * factorial(j) * factorial(k)) * pow(u, i) * pow(v, j) * pow(w, k);
      v_axpy(out, coef, b[i][j][k]);
    }
}

static void ref_pn_casteljau(pn_net b0, double u, double v, double out[3]) {
  double w = 1.0 - u - v;
  pn_net b;
  memcpy(b, b0, sizeof b);
  for (int deg = 3; deg > 0; --deg)
    for (int i = 0; i < deg; ++i)
      for (int j = 0; j + i < deg; ++j) {
        int k = deg - 1 - i - j;
        double t[3];
        for (int c = 0; c < 3; ++c)
          t[c] = u * b[i + 1][j][k][c] + v * b[i][j + 1][k][c] + w * b[i][j][k + 1][c];
        v_copy(b[i][j][k], t);
      }
  v_copy(out, b[0][0][0]);
}

/* Vlachos' mid-edge normal between corners a and b. */
static void pn_mid_normal(double o[3], const double pa[3], const double na[3], const double pb[3], const double nb[3]) {
  double d[3], s[3];
  v_sub(d, pb, pa);
  v_add(s, na, nb);
  double vij = 2.0 * v_dot(d, s) / v_dot(d, d);
  for (int c = 0; c < 3; ++c)
    o[c] = s[c] - vij * d[c];
  v_normalize(o);
}

static void ref_pn_normal(const patch_ref* r, double u, double v, double out[3]) {
  double w = 1.0 - u - v, n110[3], n011[3], n101[3];
  pn_mid_normal(n110, r->p[0], r->nrm[0], r->p[1], r->nrm[1]);
  pn_mid_normal(n011, r->p[1], r->nrm[1], r->p[2], r->nrm[2]);
  pn_mid_normal(n101, r->p[2], r->nrm[2], r->p[0], r->nrm[0]);
  v_set(out, 0, 0, 0);
  v_axpy(out, u * u, r->nrm[0]);
  v_axpy(out, v * v, r->nrm[1]);
  v_axpy(out, w * w, r->nrm[2]);
  v_axpy(out, u * v, n110);
  v_axpy(out, v * w, n011);
  v_axpy(out, w * u, n101);
  v_normalize(out);
}

static void quad_weights(double u, double v, double wt[4]) {
  wt[0] = (1 - u) * (1 - v), wt[1] = u * (1 - v), wt[2] = u * v, wt[3] = (1 - u) * v;
}

/* Dupuy's Phong quad, blended with the bilinear quad by alpha. */
static void ref_phong_quad(const patch_ref* r, double alpha, double u, double v, double out[3]) {
  double wt[4], q[3] = {0, 0, 0}, P[3] = {0, 0, 0};
  quad_weights(u, v, wt);
  for (int x = 0; x < 4; ++x)
    v_axpy(q, wt[x], r->p[x]);
  for (int x = 0; x < 4; ++x) {
    double pi[3];
    project(pi, q, r->p[x], r->nrm[x]);
    v_axpy(P, wt[x], pi);
  }
  for (int c = 0; c < 3; ++c)
    out[c] = (1 - alpha) * q[c] + alpha * P[c];
}

/* The linear (triangle) or bilinear (quad) blend of per-corner values. */
static void ref_corner_blend(const patch_ref* r, const double (*corner)[3], double u, double v, double out[3]) {
  v_set(out, 0, 0, 0);
  if (r->n == 3) {
    double bw[3] = {u, v, 1.0 - u - v};
    for (int x = 0; x < 3; ++x)
      v_axpy(out, bw[x], corner[x]);
  } else {
    double wt[4];
    quad_weights(u, v, wt);
    for (int x = 0; x < 4; ++x)
      v_axpy(out, wt[x], corner[x]);
  }
}

static void ref_flat(const patch_ref* r, double u, double v, double out[3]) { ref_corner_blend(r, r->p, u, v, out); }

/* The reference position of any surface kind. */
static void ref_position(const surf_cfg* cfg, const patch_ref* r, double u, double v, double out[3]) {
  switch (cfg->type) {
  case TLOD_SURFACE_FLAT:
    ref_flat(r, u, v, out);
    return;
  case TLOD_SURFACE_PN: {
    pn_net b;
    ref_pn_net(r, b, false);
    ref_pn_bernstein(b, u, v, out);
    return;
  }
  default:
    if (r->n == 3)
      ref_phong_tri(r, cfg->alpha, cfg->vertex_alpha, u, v, out);
    else
      ref_phong_quad(r, cfg->alpha, u, v, out);
    return;
  }
}

/* dP/du and dP/dv by central differences of the reference (a polynomial of
 * degree <= 4, so the truncation error is O(h^2 * coefficients)). */
static void ref_derivatives(const surf_cfg* cfg, const patch_ref* r, double u, double v, double du[3], double dv[3]) {
  const double h = 1e-4;
  double a[3], b[3];
  ref_position(cfg, r, u + h, v, a);
  ref_position(cfg, r, u - h, v, b);
  for (int c = 0; c < 3; ++c)
    du[c] = (a[c] - b[c]) / (2 * h);
  ref_position(cfg, r, u, v + h, a);
  ref_position(cfg, r, u, v - h, b);
  for (int c = 0; c < 3; ++c)
    dv[c] = (a[c] - b[c]) / (2 * h);
}

/* Interpolated shading normal of Phong (and flat) patches. */
static void ref_interp_normal(const patch_ref* r, double u, double v, double out[3]) {
  ref_corner_blend(r, r->nrm, u, v, out);
  v_normalize(out);
}

/* ------------------------------------------------------------------------ */
/* Random test meshes                                                       */
/* ------------------------------------------------------------------------ */

/* `count` independent random triangles (or planar-ish random quads) in
 * [-1, 1]^3, well shaped (every angle > 15 degrees). Normals: the first half
 * uniformly random unit vectors, the second half the face normal tilted by
 * at most ~53 degrees. Alphas uniform in [0, 1]. */
typedef struct random_mesh {
  float* positions;
  float* normals;
  float* alphas;
  uint32_t* indices;
  uint32_t vertex_count, index_count, corners;
} random_mesh;

static random_mesh random_patches(uint64_t seed, uint32_t count, uint32_t corners, bool tilted_only) {
  shape_rng rng = {seed};
  random_mesh m;
  m.corners = corners;
  m.vertex_count = count * corners;
  m.index_count = count * corners;
  m.positions = malloc(sizeof(float) * 3 * m.vertex_count);
  m.normals = malloc(sizeof(float) * 3 * m.vertex_count);
  m.alphas = malloc(sizeof(float) * m.vertex_count);
  m.indices = malloc(sizeof(uint32_t) * m.index_count);
  for (uint32_t f = 0; f < count; ++f) {
    double p[4][3];
    for (;;) {
      if (corners == 3) {
        for (int x = 0; x < 3; ++x)
          for (int c = 0; c < 3; ++c)
            p[x][c] = shape_rng_range(&rng, -1, 1);
      } else {
        /* a random parallelogram-ish quad, corners jittered off its plane */
        double o[3], a[3], b[3];
        for (int c = 0; c < 3; ++c)
          o[c] = shape_rng_range(&rng, -0.5, 0.5);
        shape_rng_direction(&rng, a);
        shape_rng_direction(&rng, b);
        double la = shape_rng_range(&rng, 0.5, 1.2), lb = shape_rng_range(&rng, 0.5, 1.2);
        for (int c = 0; c < 3; ++c) {
          p[0][c] = o[c];
          p[1][c] = o[c] + la * a[c];
          p[2][c] = o[c] + la * a[c] + lb * b[c];
          p[3][c] = o[c] + lb * b[c];
        }
        for (int x = 0; x < 4; ++x)
          for (int c = 0; c < 3; ++c)
            p[x][c] += shape_rng_range(&rng, -0.15, 0.15);
      }
      /* every corner angle above 15 degrees (quads: of each corner triangle) */
      bool ok = true;
      for (uint32_t x = 0; x < corners && ok; ++x) {
        double e1[3], e2[3];
        v_sub(e1, p[(x + 1) % corners], p[x]);
        v_sub(e2, p[(x + corners - 1) % corners], p[x]);
        double cosang = v_dot(e1, e2) / (v_len(e1) * v_len(e2));
        if (!(cosang < cos(15.0 * SHAPES_PI / 180.0)) || cosang < cos(165.0 * SHAPES_PI / 180.0)) ok = false;
        if (v_len(e1) < 0.2) ok = false;
      }
      if (ok) break;
    }
    double fn[3], e1[3], e2[3];
    v_sub(e1, p[1], p[0]);
    v_sub(e2, p[corners - 1], p[0]);
    v_cross(fn, e1, e2);
    if (corners == 4) {
      double d1[3], d2[3];
      v_sub(d1, p[2], p[0]);
      v_sub(d2, p[3], p[1]);
      v_cross(fn, d1, d2);
    }
    v_normalize(fn);
    for (uint32_t x = 0; x < corners; ++x) {
      uint32_t vi = f * corners + x;
      double n[3], d[3];
      shape_rng_direction(&rng, d);
      if (!tilted_only && f < count / 2) {
        v_copy(n, d);
      } else {
        for (int c = 0; c < 3; ++c)
          n[c] = fn[c] + 0.8 * shape_rng_unit(&rng) * d[c];
        v_normalize(n);
      }
      for (int c = 0; c < 3; ++c) {
        m.positions[3 * vi + c] = (float)p[x][c];
        m.normals[3 * vi + c] = (float)n[c];
      }
      m.alphas[vi] = (float)shape_rng_unit(&rng);
      m.indices[vi] = vi;
    }
  }
  return m;
}

static void random_mesh_free(random_mesh* m) {
  free(m->positions);
  free(m->normals);
  free(m->alphas);
  free(m->indices);
}

static tlod_mesh_desc random_mesh_desc(const random_mesh* m) {
  tlod_mesh_desc d = {0};
  d.positions = m->positions;
  d.normals = m->normals;
  d.alphas = m->alphas;
  d.vertex_count = m->vertex_count;
  d.indices = m->indices;
  d.index_count = m->index_count;
  d.face_type = m->corners == 4 ? TLOD_FACE_QUADS : TLOD_FACE_TRIANGLES;
  d.normal_mode = TLOD_NORMALS_KEEP;
  d.label = "random";
  return d;
}

/* A random (u, v) in the patch domain (float, as the API takes it). */
static void random_uv(shape_rng* rng, uint32_t corners, float* u, float* v) {
  double a = shape_rng_unit(rng), b = shape_rng_unit(rng);
  if (corners == 3 && a + b > 1) a = 1 - a, b = 1 - b;
  *u = (float)a, *v = (float)b;
  if (corners == 3 && (double)*u + (double)*v > 1.0) *v = (float)(1.0 - (double)*u);
}

/* ------------------------------------------------------------------------ */
/* 1. Phong triangles                                                       */
/* ------------------------------------------------------------------------ */

/* The reference against itself: projection form at alpha = 1 equals the
 * closed quadratic form, and the alpha blend identity
 * p*_alpha = (1 - alpha) p + alpha * closed form holds for any alpha. */
TEST(test_phong_reference_identities) {
  random_mesh m = random_patches(11, 16, 3, false);
  shape_rng rng = {12};
  double worst = 0;
  for (uint32_t f = 0; f < 16; ++f) {
    patch_ref r;
    memset(&r, 0, sizeof r);
    r.n = 3;
    for (int x = 0; x < 3; ++x) {
      v_from_f(r.p[x], m.positions + 3 * (3 * f + x));
      v_from_f(r.nrm[x], m.normals + 3 * (3 * f + x));
      v_normalize(r.nrm[x]);
    }
    for (int k = 0; k < 100; ++k) {
      double u = shape_rng_unit(&rng), v = shape_rng_unit(&rng) * (1 - u), alpha = shape_rng_unit(&rng);
      double proj1[3], closed[3], proja[3], flat[3], blend[3];
      ref_phong_tri(&r, 1.0, false, u, v, proj1);
      ref_phong_tri_closed(&r, u, v, closed);
      ref_phong_tri(&r, alpha, false, u, v, proja);
      ref_flat(&r, u, v, flat);
      for (int c = 0; c < 3; ++c)
        blend[c] = (1 - alpha) * flat[c] + alpha * closed[c];
      worst = fmax(worst, fmax(v_maxdiff(proj1, closed), v_maxdiff(proja, blend)));
    }
  }
  random_mesh_free(&m);
  CHECK_MSG(worst <= REF_REL, "projection form vs closed form: %.3g", worst);
}

/* Compares tlod_surface_eval positions with ref_position over `samples`
 * random (u, v) per patch; returns the largest error / size. */
static double compare_positions(const tlod_surface* s, const tlod_mesh* mesh, const float* alphas, const surf_cfg* cfg,
                                uint32_t samples, uint64_t seed) {
  shape_rng rng = {seed};
  double worst = 0;
  uint32_t patches = tlod_surface_patch_count(s);
  for (uint32_t f = 0; f < patches; ++f) {
    patch_ref r = get_patch(mesh, f, alphas);
    for (uint32_t k = 0; k < samples; ++k) {
      float u, v;
      random_uv(&rng, r.n, &u, &v);
      tlod_surface_point pt;
      tlod_surface_eval(s, f, u, v, &pt);
      double ref[3];
      ref_position(cfg, &r, u, v, ref);
      worst = fmax(worst, v_maxdiff_f(pt.position, ref) / r.size);
    }
  }
  return worst;
}

TEST(test_phong_triangle_eval) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(21, 8, 3, false);
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  CHECK(tlod_mesh_face_count(mesh) == 8);
  const double alphas[] = {1.0, 0.75, 0.3};
  for (int a = 0; a < 3; ++a) {
    surf_cfg cfg = {TLOD_SURFACE_PHONG, alphas[a], false, TLOD_SHADING_NORMAL_DEFAULT};
    tlod_surface* s = new_surface(ctx, mesh, &cfg);
    CHECK(s);
    CHECK(tlod_surface_patch_count(s) == 8);
    double worst = compare_positions(s, mesh, m.alphas, &cfg, 1000, 22 + a);
    printf("  phong triangle alpha %.2f: max relative position error %.3g (8 x 1000 samples)\n", alphas[a], worst);
    tlod_surface_destroy(s);
    CHECK_MSG(worst <= EVAL_REL, "alpha %.2f: relative error %.3g", alphas[a], worst);
  }
  /* The default desc (alpha not set) is the paper's 0.75. */
  {
    tlod_surface* s = NULL;
    CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &s) == TLOD_SUCCESS);
    surf_cfg cfg = {TLOD_SURFACE_PHONG, 0.75, false, TLOD_SHADING_NORMAL_DEFAULT};
    double worst = compare_positions(s, mesh, m.alphas, &cfg, 200, 29);
    tlod_surface_destroy(s);
    CHECK_MSG(worst <= EVAL_REL, "default alpha: relative error %.3g", worst);
  }
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
}

TEST(test_phong_vertex_alpha) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(31, 8, 3, false);
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  surf_cfg cfg = {TLOD_SURFACE_PHONG, 0.2, true, TLOD_SHADING_NORMAL_DEFAULT};
  tlod_surface* s = new_surface(ctx, mesh, &cfg);
  CHECK(s);
  double worst = compare_positions(s, mesh, m.alphas, &cfg, 1000, 32);
  printf("  phong triangle per-vertex alpha: max relative position error %.3g\n", worst);
  /* The global alpha (0.2) must not be what was used: the vertex alphas
   * differ from it by a lot somewhere, and so do the surfaces. */
  surf_cfg global = cfg;
  global.vertex_alpha = false;
  double vs_global = compare_positions(s, mesh, m.alphas, &global, 200, 33);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
  CHECK_MSG(worst <= EVAL_REL, "relative error %.3g", worst);
  CHECK_MSG(vs_global > 100 * EVAL_REL, "per-vertex alpha looks ignored (%.3g)", vs_global);
}

/* Shading normal (interpolated and true) and tangents of Phong triangles. */
TEST(test_phong_triangle_frame) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(41, 8, 3, true);
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  for (int vertex_alpha = 0; vertex_alpha < 2; ++vertex_alpha) {
    surf_cfg cfg = {TLOD_SURFACE_PHONG, 0.75, vertex_alpha != 0, TLOD_SHADING_NORMAL_INTERPOLATED};
    surf_cfg cfg_true = cfg;
    cfg_true.shading = TLOD_SHADING_NORMAL_TRUE;
    tlod_surface* s = new_surface(ctx, mesh, &cfg);
    tlod_surface* st = new_surface(ctx, mesh, &cfg_true);
    CHECK(s && st);
    shape_rng rng = {42};
    double worst_n = 0, worst_t = 0, worst_true = 0;
    for (uint32_t f = 0; f < 8; ++f) {
      patch_ref r = get_patch(mesh, f, m.alphas);
      for (int k = 0; k < 200; ++k) {
        float u, v;
        random_uv(&rng, 3, &u, &v);
        tlod_surface_point pt, ptt;
        tlod_surface_eval(s, f, u, v, &pt);
        tlod_surface_eval(st, f, u, v, &ptt);
        double n[3], du[3], dv[3], tn[3];
        ref_interp_normal(&r, u, v, n);
        ref_derivatives(&cfg, &r, u, v, du, dv);
        v_cross(tn, du, dv);
        v_normalize(tn);
        worst_n = fmax(worst_n, v_maxdiff_f(pt.normal, n));
        worst_t = fmax(worst_t, fmax(v_maxdiff_f(pt.tangent, du), v_maxdiff_f(pt.bitangent, dv)) / r.size);
        worst_true = fmax(worst_true, v_maxdiff_f(ptt.normal, tn));
        /* same position whatever the normal option */
        CHECK(memcmp(pt.position, ptt.position, sizeof pt.position) == 0);
      }
    }
    tlod_surface_destroy(s);
    tlod_surface_destroy(st);
    printf("  phong triangle%s: normal %.3g, tangents %.3g (rel), true normal %.3g\n",
           vertex_alpha ? " (vertex alpha)" : "", worst_n, worst_t, worst_true);
    CHECK_MSG(worst_n <= NORMAL_TOL, "interpolated normal error %.3g", worst_n);
    CHECK_MSG(worst_t <= DERIV_REL, "tangent error %.3g", worst_t);
    CHECK_MSG(worst_true <= NORMAL_TOL, "true normal error %.3g", worst_true);
  }
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 2. PN triangles                                                          */
/* ------------------------------------------------------------------------ */

TEST(test_pn_reference_self) {
  random_mesh m = random_patches(51, 16, 3, false);
  shape_rng rng = {52};
  double worst_casteljau = 0, worst_center = 0, worst_corner = 0;
  for (uint32_t f = 0; f < 16; ++f) {
    patch_ref r;
    memset(&r, 0, sizeof r);
    r.n = 3;
    for (int x = 0; x < 3; ++x) {
      v_from_f(r.p[x], m.positions + 3 * (3 * f + x));
      v_from_f(r.nrm[x], m.normals + 3 * (3 * f + x));
      v_normalize(r.nrm[x]);
    }
    pn_net b, bs;
    ref_pn_net(&r, b, false);
    ref_pn_net(&r, bs, true);
    worst_center = fmax(worst_center, v_maxdiff(b[1][1][1], bs[1][1][1]));
    for (int k = 0; k < 200; ++k) {
      double u = shape_rng_unit(&rng), v = shape_rng_unit(&rng) * (1 - u);
      double a[3], c[3];
      ref_pn_bernstein(b, u, v, a);
      ref_pn_casteljau(b, u, v, c);
      worst_casteljau = fmax(worst_casteljau, v_maxdiff(a, c));
    }
    /* corners of the cubic are the input points */
    double c0[3], c1[3], c2[3];
    ref_pn_bernstein(b, 1, 0, c0);
    ref_pn_bernstein(b, 0, 1, c1);
    ref_pn_bernstein(b, 0, 0, c2);
    worst_corner = fmax(worst_corner, fmax(v_maxdiff(c0, r.p[0]), fmax(v_maxdiff(c1, r.p[1]), v_maxdiff(c2, r.p[2]))));
  }
  random_mesh_free(&m);
  CHECK_MSG(worst_casteljau <= REF_REL, "Bernstein vs de Casteljau %.3g", worst_casteljau);
  CHECK_MSG(worst_center <= REF_REL, "b111 Vlachos vs Schwarz %.3g", worst_center);
  CHECK_MSG(worst_corner <= REF_REL, "corners %.3g", worst_corner);
}

TEST(test_pn_eval) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(61, 8, 3, false);
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  surf_cfg cfg = {TLOD_SURFACE_PN, 0.75, false, TLOD_SHADING_NORMAL_DEFAULT};
  surf_cfg cfg_true = cfg;
  cfg_true.shading = TLOD_SHADING_NORMAL_TRUE;
  tlod_surface* s = new_surface(ctx, mesh, &cfg);
  tlod_surface* st = new_surface(ctx, mesh, &cfg_true);
  CHECK(s && st);
  shape_rng rng = {62};
  double worst_p = 0, worst_pc = 0, worst_n = 0, worst_t = 0, worst_true = 0;
  for (uint32_t f = 0; f < 8; ++f) {
    patch_ref r = get_patch(mesh, f, NULL);
    pn_net b;
    ref_pn_net(&r, b, false);
    for (int k = 0; k < 1000; ++k) {
      float u, v;
      random_uv(&rng, 3, &u, &v);
      tlod_surface_point pt, ptt;
      tlod_surface_eval(s, f, u, v, &pt);
      tlod_surface_eval(st, f, u, v, &ptt);
      double bern[3], cast[3], n[3], du[3], dv[3], tn[3];
      ref_pn_bernstein(b, u, v, bern);
      ref_pn_casteljau(b, u, v, cast);
      ref_pn_normal(&r, u, v, n);
      ref_derivatives(&cfg, &r, u, v, du, dv);
      v_cross(tn, du, dv);
      v_normalize(tn);
      worst_p = fmax(worst_p, v_maxdiff_f(pt.position, bern) / r.size);
      worst_pc = fmax(worst_pc, v_maxdiff_f(pt.position, cast) / r.size);
      worst_n = fmax(worst_n, v_maxdiff_f(pt.normal, n));
      worst_t = fmax(worst_t, fmax(v_maxdiff_f(pt.tangent, du), v_maxdiff_f(pt.bitangent, dv)) / r.size);
      double cr[3];
      v_cross(cr, du, dv);
      /* away from folds, where T x B vanishes and its direction is ill-conditioned */
      if (v_len(cr) > 1e-2 * r.size * r.size) worst_true = fmax(worst_true, v_maxdiff_f(ptt.normal, tn));
    }
  }
  printf("  pn: position vs Bernstein %.3g, vs de Casteljau %.3g (rel), normal field %.3g, tangents %.3g, "
         "true normal %.3g\n",
         worst_p, worst_pc, worst_n, worst_t, worst_true);
  tlod_surface_destroy(s);
  tlod_surface_destroy(st);
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
  CHECK_MSG(worst_p <= EVAL_REL, "position vs Bernstein %.3g", worst_p);
  CHECK_MSG(worst_pc <= EVAL_REL, "position vs de Casteljau %.3g", worst_pc);
  CHECK_MSG(worst_n <= NORMAL_TOL, "quadratic normal field %.3g", worst_n);
  CHECK_MSG(worst_t <= DERIV_REL, "tangents %.3g", worst_t);
  /* Random normals can fold the cubic, where T x B is tiny and its
   * direction ill-conditioned; 1e-4 there. */
  CHECK_MSG(worst_true <= 1e-4, "true normal %.3g", worst_true);
}

/* ------------------------------------------------------------------------ */
/* 3. Phong quads and flat patches                                          */
/* ------------------------------------------------------------------------ */

TEST(test_phong_quad) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(71, 8, 4, false);
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  CHECK(tlod_mesh_face_count(mesh) == 8);
  const double alphas[] = {1.0, 0.75};
  for (int a = 0; a < 2; ++a) {
    surf_cfg cfg = {TLOD_SURFACE_PHONG, alphas[a], false, TLOD_SHADING_NORMAL_INTERPOLATED};
    surf_cfg cfg_true = cfg;
    cfg_true.shading = TLOD_SHADING_NORMAL_TRUE;
    tlod_surface* s = new_surface(ctx, mesh, &cfg);
    tlod_surface* st = new_surface(ctx, mesh, &cfg_true);
    CHECK(s && st);
    shape_rng rng = {72};
    double worst_p = 0, worst_t = 0, worst_n = 0, worst_true = 0, worst_true_ref = 0;
    for (uint32_t f = 0; f < 8; ++f) {
      patch_ref r = get_patch(mesh, f, NULL);
      CHECK(r.n == 4);
      CHECK(tlod_surface_patch(s, f).corner_count == 4);
      for (int k = 0; k < 1000; ++k) {
        float u, v;
        random_uv(&rng, 4, &u, &v);
        tlod_surface_point pt, ptt;
        tlod_surface_eval(s, f, u, v, &pt);
        tlod_surface_eval(st, f, u, v, &ptt);
        double ref[3], du[3], dv[3], n[3], tn[3], lt[3], lb[3], ltn[3];
        ref_phong_quad(&r, alphas[a], u, v, ref);
        ref_derivatives(&cfg, &r, u, v, du, dv);
        ref_interp_normal(&r, u, v, n);
        v_cross(tn, du, dv);
        double tn_len = v_len(tn);
        v_normalize(tn);
        v_from_f(lt, ptt.tangent);
        v_from_f(lb, ptt.bitangent);
        v_cross(ltn, lt, lb);
        v_normalize(ltn);
        worst_p = fmax(worst_p, v_maxdiff_f(pt.position, ref) / r.size);
        worst_t = fmax(worst_t, fmax(v_maxdiff_f(pt.tangent, du), v_maxdiff_f(pt.bitangent, dv)) / r.size);
        worst_n = fmax(worst_n, v_maxdiff_f(pt.normal, n));
        if (tn_len > 1e-2 * r.size * r.size) {                                /* away from folds */
          worst_true = fmax(worst_true, v_maxdiff_f(ptt.normal, ltn));        /* = normalize(T x B) of its own T, B */
          worst_true_ref = fmax(worst_true_ref, v_maxdiff_f(ptt.normal, tn)); /* and of the reference's */
        }
      }
    }
    printf("  phong quad alpha %.2f: position %.3g (rel), tangents vs differences %.3g (rel), interpolated "
           "normal %.3g, true normal vs T x B %.3g, vs reference %.3g\n",
           alphas[a], worst_p, worst_t, worst_n, worst_true, worst_true_ref);
    tlod_surface_destroy(s);
    tlod_surface_destroy(st);
    CHECK_MSG(worst_p <= EVAL_REL, "alpha %.2f position %.3g", alphas[a], worst_p);
    CHECK_MSG(worst_t <= DERIV_REL, "alpha %.2f tangents %.3g", alphas[a], worst_t);
    CHECK_MSG(worst_n <= NORMAL_TOL, "alpha %.2f interpolated normal %.3g", alphas[a], worst_n);
    CHECK_MSG(worst_true <= NORMAL_TOL, "alpha %.2f true normal vs own T x B %.3g", alphas[a], worst_true);
    CHECK_MSG(worst_true_ref <= 1e-4, "alpha %.2f true normal vs reference %.3g", alphas[a], worst_true_ref);
  }
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
}

TEST(test_flat_eval) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  for (uint32_t corners = 3; corners <= 4; ++corners) {
    random_mesh m = random_patches(81 + corners, 8, corners, false);
    tlod_mesh_desc md = random_mesh_desc(&m);
    tlod_mesh* mesh = new_mesh(ctx, &md);
    CHECK(mesh);
    surf_cfg cfg = {TLOD_SURFACE_FLAT, 0.75, false, TLOD_SHADING_NORMAL_DEFAULT};
    tlod_surface* s = new_surface(ctx, mesh, &cfg);
    CHECK(s);
    double worst = compare_positions(s, mesh, NULL, &cfg, 500, 90 + corners);
    tlod_surface_destroy(s);
    tlod_mesh_destroy(mesh);
    random_mesh_free(&m);
    printf("  flat %s: max relative position error %.3g\n", corners == 3 ? "triangle" : "quad", worst);
    CHECK_MSG(worst <= EVAL_REL, "flat %u corners: %.3g", corners, worst);
  }
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 4. Corners, alpha = 0, equal normals                                     */
/* ------------------------------------------------------------------------ */

static const float k_tri_corner_uv[3][2] = {{1, 0}, {0, 1}, {0, 0}};
static const float k_quad_corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

static void check_corners(const tlod_surface* s, const tlod_mesh* mesh, const char* what) {
  uint32_t patches = tlod_surface_patch_count(s);
  CHECK(patches > 0);
  for (uint32_t f = 0; f < patches; ++f) {
    uint32_t vid[4];
    uint32_t n = tlod_mesh_face_corners(mesh, f, vid);
    for (uint32_t c = 0; c < n; ++c) {
      const float* uv = n == 3 ? k_tri_corner_uv[c] : k_quad_corner_uv[c];
      float p[3], nn[3];
      tlod_mesh_vertex(mesh, vid[c], p, nn);
      tlod_surface_point pt;
      tlod_surface_eval(s, f, uv[0], uv[1], &pt);
      CHECK_MSG(memcmp(pt.position, p, sizeof p) == 0,
                "%s patch %u corner %u: (%.9g %.9g %.9g) != input (%.9g %.9g %.9g)", what, f, c, pt.position[0],
                pt.position[1], pt.position[2], p[0], p[1], p[2]);
    }
  }
}

TEST(test_corners_exact) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  const surf_cfg cfgs[] = {{TLOD_SURFACE_FLAT, 0.75, false, 0},
                           {TLOD_SURFACE_PHONG, 0.75, false, 0},
                           {TLOD_SURFACE_PHONG, 1.0, false, 0},
                           {TLOD_SURFACE_PHONG, 0.5, true, 0},
                           {TLOD_SURFACE_PN, 0.75, false, 0}};
  const char* names[] = {"flat", "phong", "phong alpha 1", "phong vertex alpha", "pn"};
  for (uint32_t corners = 3; corners <= 4; ++corners) {
    random_mesh m = random_patches(101 + corners, 32, corners, false);
    tlod_mesh_desc md = random_mesh_desc(&m);
    tlod_mesh* mesh = new_mesh(ctx, &md);
    CHECK(mesh);
    for (int c = 0; c < 5; ++c) {
      if (corners == 4 && cfgs[c].type == TLOD_SURFACE_PN) continue;
      tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
      CHECK(s);
      CALL(check_corners(s, mesh, names[c]));
      tlod_surface_destroy(s);
    }
    tlod_mesh_destroy(mesh);
    random_mesh_free(&m);
  }
  /* and on a real mesh */
  shape sph = shape_icosphere(1);
  tlod_mesh_desc md = shape_mesh_desc(&sph);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  for (int c = 0; c < 5; ++c) {
    if (cfgs[c].vertex_alpha) continue;
    tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
    CHECK(s);
    CALL(check_corners(s, mesh, names[c]));
    tlod_surface_destroy(s);
  }
  tlod_mesh_destroy(mesh);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* Largest |surface - flat patch| / scale over a dense grid of every patch:
 * dev[0] against the exact (double) flat patch, dev[1] against the
 * library's own flat surface. */
static void flat_deviation(const tlod_surface* s, const tlod_surface* flat, const tlod_mesh* mesh, double dev[2]) {
  const int N = 24;
  dev[0] = dev[1] = 0;
  for (uint32_t f = 0; f < tlod_surface_patch_count(s); ++f) {
    patch_ref r = get_patch(mesh, f, NULL);
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= (r.n == 3 ? N - i : N); ++j) {
        float u = (float)i / N, v = (float)j / N;
        if (r.n == 3 && (double)u + (double)v > 1.0) continue;
        tlod_surface_point pt, pf;
        tlod_surface_eval(s, f, u, v, &pt);
        tlod_surface_eval(flat, f, u, v, &pf);
        double ref[3], fl[3];
        ref_flat(&r, u, v, ref);
        v_from_f(fl, pf.position);
        dev[0] = fmax(dev[0], v_maxdiff_f(pt.position, ref) / r.scale);
        dev[1] = fmax(dev[1], v_maxdiff_f(pt.position, fl) / r.scale);
      }
  }
}

TEST(test_alpha_zero_is_flat) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  double worst[2][2][2] = {{{0}}}; /* [corners - 3][global, vertex alpha][exact, library flat] */
  for (uint32_t corners = 3; corners <= 4; ++corners) {
    random_mesh m = random_patches(111 + corners, 16, corners, false);
    for (uint32_t k = 0; k < m.vertex_count; ++k)
      m.alphas[k] = 0.0f;
    tlod_mesh_desc md = random_mesh_desc(&m);
    tlod_mesh* mesh = new_mesh(ctx, &md);
    CHECK(mesh);
    surf_cfg cf = {TLOD_SURFACE_FLAT, 0.0, false, 0};
    tlod_surface* flat = new_surface(ctx, mesh, &cf);
    surf_cfg cfg = {TLOD_SURFACE_PHONG, 0.0, false, 0};
    tlod_surface* s = new_surface(ctx, mesh, &cfg);
    surf_cfg cv = {TLOD_SURFACE_PHONG, 0.75, true, 0}; /* per-vertex alphas, all 0 */
    tlod_surface* sv = new_surface(ctx, mesh, &cv);
    CHECK(flat && s && sv);
    flat_deviation(s, flat, mesh, worst[corners - 3][0]);
    flat_deviation(sv, flat, mesh, worst[corners - 3][1]);
    printf("  alpha 0 (%s): deviation from flat: exact %.3g, library flat %.3g; vertex alphas 0: %.3g, %.3g "
           "(relative to scale)\n",
           corners == 3 ? "triangles" : "quads", worst[corners - 3][0][0], worst[corners - 3][0][1],
           worst[corners - 3][1][0], worst[corners - 3][1][1]);
    tlod_surface_destroy(s);
    tlod_surface_destroy(sv);
    tlod_surface_destroy(flat);
    tlod_mesh_destroy(mesh);
    random_mesh_free(&m);
  }
  tlod_context_destroy(ctx);
  for (int c = 0; c < 2; ++c)
    for (int a = 0; a < 2; ++a) {
      CHECK_MSG(worst[c][a][0] <= FLAT_EXACT_REL, "%s%s: %.3g from the exact flat patch", c ? "quads" : "triangles",
                a ? " vertex alpha" : "", worst[c][a][0]);
      CHECK_MSG(worst[c][a][1] <= FLAT_REL, "%s%s: %.3g from the library's flat patch", c ? "quads" : "triangles",
                a ? " vertex alpha" : "", worst[c][a][1]);
    }
}

TEST(test_equal_normals_are_flat) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  random_mesh m = random_patches(121, 16, 3, false);
  for (uint32_t f = 0; f < 16; ++f) {
    double p[3][3], e1[3], e2[3], n[3];
    for (int x = 0; x < 3; ++x)
      v_from_f(p[x], m.positions + 3 * (3 * f + x));
    v_sub(e1, p[1], p[0]);
    v_sub(e2, p[2], p[0]);
    v_cross(n, e1, e2);
    v_normalize(n);
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 3; ++c)
        m.normals[3 * (3 * f + x) + c] = (float)n[c];
  }
  tlod_mesh_desc md = random_mesh_desc(&m);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  surf_cfg cf = {TLOD_SURFACE_FLAT, 0.0, false, 0};
  tlod_surface* flat = new_surface(ctx, mesh, &cf);
  CHECK(flat);
  const surf_cfg cfgs[] = {
      {TLOD_SURFACE_PHONG, 1.0, false, 0}, {TLOD_SURFACE_PHONG, 0.75, false, 0}, {TLOD_SURFACE_PN, 0.75, false, 0}};
  double worst[3][2];
  for (int c = 0; c < 3; ++c) {
    tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
    CHECK(s);
    flat_deviation(s, flat, mesh, worst[c]);
    tlod_surface_destroy(s);
    printf("  equal normals, %s alpha %.2f: deviation from flat: exact %.3g, library flat %.3g (relative to scale)\n",
           cfgs[c].type == TLOD_SURFACE_PN ? "pn" : "phong", cfgs[c].alpha, worst[c][0], worst[c][1]);
  }
  tlod_surface_destroy(flat);
  tlod_mesh_destroy(mesh);
  random_mesh_free(&m);
  tlod_context_destroy(ctx);
  /* Phong: the projections are the identity up to the rounding of one dot
   * product, FLAT_REL from the library's flat triangle. PN: the float
   * Bernstein sum of ten control points reproduces a linear function only
   * to ~2-3 ulps (1.4e-7 measured), so FLAT_EXACT_REL for both comparisons;
   * a wrong control point (b111 with 1/3 for 1/6, say) is off by ~0.1. */
  for (int c = 0; c < 3; ++c) {
    double tol = cfgs[c].type == TLOD_SURFACE_PN ? FLAT_EXACT_REL : FLAT_REL;
    CHECK_MSG(worst[c][0] <= FLAT_EXACT_REL, "case %d: %.3g from the exact flat triangle", c, worst[c][0]);
    CHECK_MSG(worst[c][1] <= tol, "case %d: %.3g from the library's flat triangle", c, worst[c][1]);
  }
}

/* ------------------------------------------------------------------------ */
/* 5. Sphere approximation                                                  */
/* ------------------------------------------------------------------------ */

static void sphere_error(const tlod_surface* s, double* max_err, double* mean_err) {
  const int N = 32;
  double mx = 0, sum = 0;
  long count = 0;
  for (uint32_t f = 0; f < tlod_surface_patch_count(s); ++f)
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= N - i; ++j) {
        tlod_surface_point pt;
        tlod_surface_eval(s, f, (float)i / N, (float)j / N, &pt);
        double p[3];
        v_from_f(p, pt.position);
        double e = fabs(v_len(p) - 1.0);
        mx = fmax(mx, e);
        sum += e;
        count++;
      }
  *max_err = mx;
  *mean_err = sum / (double)count;
}

TEST(test_sphere_approximation) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  tlod_mesh_desc md = shape_mesh_desc(&sph);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  const surf_cfg cfgs[] = {{TLOD_SURFACE_FLAT, 0, false, 0},
                           {TLOD_SURFACE_PHONG, 0.75, false, 0},
                           {TLOD_SURFACE_PHONG, 1.0, false, 0},
                           {TLOD_SURFACE_PN, 0.75, false, 0}};
  const char* names[] = {"flat", "phong 0.75", "phong 1.0", "pn"};
  double mx[4], mean[4];
  for (int c = 0; c < 4; ++c) {
    tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
    CHECK(s);
    sphere_error(s, &mx[c], &mean[c]);
    tlod_surface_destroy(s);
    printf("  icosphere(1), %-10s: distance from the unit sphere max %.5f mean %.5f\n", names[c], mx[c], mean[c]);
  }
  tlod_mesh_destroy(mesh);
  shape_free(&sph);
  tlod_context_destroy(ctx);
  /* Margins: Phong (alpha 0.75) at least 2x better than flat, PN at least 3x. */
  CHECK_MSG(mx[1] * 2 < mx[0] && mean[1] * 2 < mean[0], "phong 0.75 not 2x better than flat");
  CHECK_MSG(mx[3] * 3 < mx[0] && mean[3] * 3 < mean[0], "pn not 3x better than flat");
}

/* ------------------------------------------------------------------------ */
/* 6. Error bound and bounding sphere                                       */
/* ------------------------------------------------------------------------ */

typedef struct bound_stats {
  double max_ratio[5]; /* max over patches of measured / bound, per level */
  double sum_ratio[5];
  uint32_t ratio_count[5];
  double worst_excess; /* max of measured - (bound * 4^-l + slack) */
  uint32_t worst_patch, worst_level;
  double sphere_excess; /* max of |p - center| - radius */
} bound_stats;

/* Measures the deviation of the level-l pattern of `patch` from the
 * surface: the surface at the pattern vertices, interpolated linearly in
 * each pattern triangle, against the surface at a grid of points inside. */
static double pattern_deviation(const tlod_surface* s, const tlod_patterns* pat, uint32_t patch, uint32_t level,
                                const tlod_patch_info* info, double* sphere_excess) {
  tlod_pattern_shape pshape = info->corner_count == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
  uint32_t vcount = 0, icount = 0;
  const tlod_pattern_vertex* pv = tlod_patterns_vertices(pat, pshape, &vcount);
  const uint32_t* idx = tlod_patterns_indices(pat, pshape, level, &icount);
  int M = 48 >> level; /* a multiple of 6: edge midpoints and centroids are sampled */
  if (M < 6) M = 6;
  double worst = 0;
  double center[3];
  v_from_f(center, info->center);
  for (uint32_t t = 0; t < icount; t += 3) {
    const tlod_pattern_vertex* tv[3] = {&pv[idx[t]], &pv[idx[t + 1]], &pv[idx[t + 2]]};
    double P[3][3];
    for (int x = 0; x < 3; ++x) {
      tlod_surface_point pt;
      tlod_surface_eval(s, patch, tv[x]->u, tv[x]->v, &pt);
      v_from_f(P[x], pt.position);
    }
    double ua = tv[0]->u, va = tv[0]->v, ub = tv[1]->u, vb = tv[1]->v, uc = tv[2]->u, vc = tv[2]->v;
    double det = (ua - uc) * (vb - vc) - (ub - uc) * (va - vc);
    for (int i = 0; i <= M; ++i)
      for (int j = 0; j <= M - i; ++j) {
        double l0 = (double)i / M, l1 = (double)j / M, l2 = 1 - l0 - l1;
        float uf = (float)(l0 * ua + l1 * ub + l2 * uc), vf = (float)(l0 * va + l1 * vb + l2 * vc);
        /* barycentrics of the float point, exactly (in double) */
        double m0 = ((double)uf - uc) * (vb - vc) - (ub - uc) * ((double)vf - vc);
        double m1 = (ua - uc) * ((double)vf - vc) - ((double)uf - uc) * (va - vc);
        m0 /= det, m1 /= det;
        double m2 = 1 - m0 - m1, L[3];
        for (int c = 0; c < 3; ++c)
          L[c] = m0 * P[0][c] + m1 * P[1][c] + m2 * P[2][c];
        tlod_surface_point pt;
        tlod_surface_eval(s, patch, uf, vf, &pt);
        double S[3];
        v_from_f(S, pt.position);
        worst = fmax(worst, v_dist(S, L));
        *sphere_excess = fmax(*sphere_excess, v_dist(S, center) - (double)info->radius);
      }
  }
  return worst;
}

static void measure_bounds(const tlod_surface* s, const tlod_patterns* pat, bound_stats* st) {
  memset(st, 0, sizeof *st);
  st->worst_excess = -1e300;
  st->sphere_excess = -1e300;
  for (uint32_t f = 0; f < tlod_surface_patch_count(s); ++f) {
    tlod_patch_info info = tlod_surface_patch(s, f);
    for (uint32_t l = 0; l <= 4; ++l) {
      double dev = pattern_deviation(s, pat, f, l, &info, &st->sphere_excess);
      double bound = (double)info.error_bound * ldexp(1.0, -2 * (int)l);
      double excess = dev - (bound + 1e-6);
      if (excess > st->worst_excess) st->worst_excess = excess, st->worst_patch = f, st->worst_level = l;
      if (bound > 1e-5) {
        double ratio = dev / bound;
        st->max_ratio[l] = fmax(st->max_ratio[l], ratio);
        st->sum_ratio[l] += ratio;
        st->ratio_count[l]++;
      }
    }
  }
}

/* Measures every patch of the meshes selected by run_mask (bit c of
 * run_mask[mesh] selects cfgs[c]) at levels 0..4, prints the tightness,
 * and fails on any violation of the error bound or the bounding sphere. */
static void error_bound_family(const unsigned run_mask[5]) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 6}, &pat) == TLOD_SUCCESS);
  shape shapes[3] = {shape_icosphere(1), shape_torus(8, 4), shape_quad_sphere(2)};
  random_mesh rt = random_patches(131, 24, 3, true), rq = random_patches(132, 12, 4, true);
  tlod_mesh_desc descs[5] = {shape_mesh_desc(&shapes[0]), shape_mesh_desc(&shapes[1]), shape_mesh_desc(&shapes[2]),
                             random_mesh_desc(&rt), random_mesh_desc(&rq)};
  const char* mesh_names[5] = {"icosphere1", "torus", "quad_sphere", "random tris", "random quads"};
  const surf_cfg cfgs[] = {{TLOD_SURFACE_FLAT, 0, false, 0},
                           {TLOD_SURFACE_PHONG, 0.75, false, 0},
                           {TLOD_SURFACE_PHONG, 1.0, false, 0},
                           {TLOD_SURFACE_PHONG, 0.75, true, 0},
                           {TLOD_SURFACE_PN, 0, false, 0}};
  const char* names[] = {"flat", "phong 0.75", "phong 1.0", "phong vtx-alpha", "pn"};
  int failures = 0;
  for (int mi = 0; mi < 5; ++mi) {
    if (!run_mask[mi]) continue;
    tlod_mesh* mesh = new_mesh(ctx, &descs[mi]);
    CHECK(mesh);
    bool quads = descs[mi].face_type == TLOD_FACE_QUADS;
    for (int c = 0; c < 5; ++c) {
      if (!(run_mask[mi] >> c & 1u)) continue;
      if (quads && cfgs[c].type == TLOD_SURFACE_PN) continue;
      if (cfgs[c].vertex_alpha && !descs[mi].alphas) continue;
      tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
      CHECK(s);
      bound_stats st;
      measure_bounds(s, pat, &st);
      tlod_patch_info wi = tlod_surface_patch(s, st.worst_patch);
      printf("  bound %-12s %-15s measured/bound max per level:", mesh_names[mi], names[c]);
      for (int l = 0; l <= 4; ++l)
        printf(" %.3f", st.max_ratio[l]);
      printf(" (mean l0 %.3f, l4 %.3f); sphere excess %.2g\n",
             st.ratio_count[0] ? st.sum_ratio[0] / st.ratio_count[0] : 0.0,
             st.ratio_count[4] ? st.sum_ratio[4] / st.ratio_count[4] : 0.0, st.sphere_excess);
      if (st.worst_excess > 0) {
        fprintf(stderr, "%s:%d: %s %s: patch %u level %u exceeds error_bound %.6g * 4^-l by %.3g\n", __FILE__, __LINE__,
                mesh_names[mi], names[c], st.worst_patch, st.worst_level, (double)wi.error_bound, st.worst_excess);
        failures++;
      }
      if (st.sphere_excess > 1e-6) {
        fprintf(stderr, "%s:%d: %s %s: a surface point lies %.3g outside its patch's bounding sphere\n", __FILE__,
                __LINE__, mesh_names[mi], names[c], st.sphere_excess);
        failures++;
      }
      tlod_surface_destroy(s);
    }
    tlod_mesh_destroy(mesh);
  }
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  random_mesh_free(&rt);
  random_mesh_free(&rq);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  CHECK_MSG(failures == 0, "%d error-bound / bounding-sphere violations (see above)", failures);
}

/* Families, so that each verdict stands on its own. Not every mesh runs
 * every surface, to keep the run short (under the sanitizers an evaluation
 * costs microseconds; phong 1.0 has exactly the ratios of phong 0.75 with a
 * global alpha). Meshes: icosphere1, torus, quad_sphere, random tris,
 * random quads; cfgs: flat, phong 0.75, phong 1.0, phong vertex alpha, pn. */
TEST(test_error_bound_flat) { error_bound_family((const unsigned[5]){0x01, 0, 0x01, 0x01, 0x01}); }
TEST(test_error_bound_phong_triangles) { error_bound_family((const unsigned[5]){0x02, 0x02, 0, 0x06, 0}); }
TEST(test_error_bound_phong_quads) { error_bound_family((const unsigned[5]){0, 0, 0x02, 0, 0x02}); }
TEST(test_error_bound_phong_vertex_alpha) { error_bound_family((const unsigned[5]){0, 0, 0, 0x08, 0x08}); }
TEST(test_error_bound_pn) { error_bound_family((const unsigned[5]){0x10, 0x10, 0, 0x10, 0}); }

/* ------------------------------------------------------------------------ */
/* 7. Invariant 1 through the API                                           */
/* ------------------------------------------------------------------------ */

/* (u, v) of the point at parameter t along edge e of a patch with n corners. */
static void edge_uv(uint32_t n, uint32_t e, float t, float* u, float* v) {
  const float(*c)[2] = n == 3 ? k_tri_corner_uv : k_quad_corner_uv;
  const float* a = c[e];
  const float* b = c[(e + 1) % n];
  /* every term is exact for dyadic t: one of a, b is 0 or both equal */
  *u = a[0] == b[0] ? a[0] : (a[0] == 0 ? t : 1.0f - t);
  *v = a[1] == b[1] ? a[1] : (a[1] == 0 ? t : 1.0f - t);
}

static void check_shared_edges(const tlod_surface* s, const tlod_mesh* mesh, const char* what, uint32_t* checked,
                               uint32_t* smooth_edges, uint32_t* linked_edges) {
  const uint32_t N = 64; /* t = k / 64 covers every dyadic k / 2^l, l <= 6 */
  uint32_t faces = tlod_mesh_face_count(mesh);
  for (uint32_t f = 0; f < faces; ++f) {
    uint32_t vid[4], n = tlod_mesh_face_corners(mesh, f, vid);
    for (uint32_t e = 0; e < n; ++e) {
      tlod_edge_link link = tlod_mesh_edge_link(mesh, f, e);
      if (link.face == UINT32_MAX) continue;
      ++*linked_edges;
      if (!link.smooth) continue;
      ++*smooth_edges;
      uint32_t gvid[4], gn = tlod_mesh_face_corners(mesh, link.face, gvid);
      CHECK(link.edge < gn);
      /* direction: g's edge must run from f's corner e+1 to f's corner e */
      float fa[3], fb[3], ga[3], gb[3], nn[3];
      tlod_mesh_vertex(mesh, vid[e], fa, nn);
      tlod_mesh_vertex(mesh, vid[(e + 1) % n], fb, nn);
      tlod_mesh_vertex(mesh, gvid[link.edge], ga, nn);
      tlod_mesh_vertex(mesh, gvid[(link.edge + 1) % gn], gb, nn);
      CHECK_MSG(memcmp(fa, gb, sizeof fa) == 0 && memcmp(fb, ga, sizeof fb) == 0,
                "%s: face %u edge %u and its link (face %u edge %u) do not share end points oppositely", what, f, e,
                link.face, link.edge);
      for (uint32_t k = 0; k <= N; ++k) {
        float t = (float)k / (float)N, u, v, gu, gv;
        edge_uv(n, e, t, &u, &v);
        edge_uv(gn, link.edge, 1.0f - t, &gu, &gv);
        tlod_surface_point p, q;
        tlod_surface_eval(s, f, u, v, &p);
        tlod_surface_eval(s, link.face, gu, gv, &q);
        CHECK_MSG(memcmp(p.position, q.position, sizeof p.position) == 0,
                  "%s: face %u edge %u t=%u/%u (%.9g %.9g %.9g) != face %u edge %u (%.9g %.9g %.9g), diff %.3g", what,
                  f, e, k, N, p.position[0], p.position[1], p.position[2], link.face, link.edge, q.position[0],
                  q.position[1], q.position[2],
                  fmax(fabs(p.position[0] - q.position[0]),
                       fmax(fabs(p.position[1] - q.position[1]), fabs(p.position[2] - q.position[2]))));
        ++*checked;
      }
    }
  }
}

TEST(test_shared_edges_bitwise) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[5] = {shape_icosphere(2), shape_torus(16, 10), shape_seam_sphere(6, 12), shape_open_grid(4),
                     shape_quad_sphere(3)};
  const surf_cfg cfgs[] = {{TLOD_SURFACE_FLAT, 0, false, 0},
                           {TLOD_SURFACE_PHONG, 0.75, false, 0},
                           {TLOD_SURFACE_PHONG, 1.0, false, 0},
                           {TLOD_SURFACE_PN, 0, false, 0}};
  const char* names[] = {"flat", "phong 0.75", "phong 1.0", "pn"};
  for (int si = 0; si < 5; ++si) {
    tlod_mesh_desc md = shape_mesh_desc(&shapes[si]);
    tlod_mesh* mesh = new_mesh(ctx, &md);
    CHECK(mesh);
    uint32_t welded = 0, edges = 0;
    shape_topology(&shapes[si], &welded, &edges);
    for (int c = 0; c < 4; ++c) {
      if (shapes[si].corners == 4 && cfgs[c].type == TLOD_SURFACE_PN) continue;
      tlod_surface* s = new_surface(ctx, mesh, &cfgs[c]);
      CHECK(s);
      char what[96];
      snprintf(what, sizeof what, "%s %s", shapes[si].name, names[c]);
      uint32_t checked = 0, smooth = 0, linked = 0;
      CALL(check_shared_edges(s, mesh, what, &checked, &smooth, &linked));
      tlod_surface_destroy(s);
      if (c == 0)
        printf("  %-12s: %u half-edges linked, %u smooth, %u edge points compared per surface type\n", shapes[si].name,
               linked, smooth, checked);
      /* every interior edge of these smooth shapes is linked and smooth,
       * including the seam sphere's duplicated-vertex edges */
      uint32_t faces = shape_face_count(&shapes[si]);
      uint32_t half_edges = faces * shapes[si].corners;
      uint32_t interior_half_edges = shapes[si].closed ? half_edges : 2 * half_edges - 2 * edges;
      CHECK_MSG(linked == interior_half_edges, "%s: %u linked half-edges, expected %u", what, linked,
                interior_half_edges);
      CHECK_MSG(smooth == linked, "%s: %u of %u linked half-edges smooth", what, smooth, linked);
    }
    tlod_mesh_destroy(mesh);
  }
  for (int k = 0; k < 5; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 8. Rejected requests                                                     */
/* ------------------------------------------------------------------------ */

/* First decimal number after "face" in msg, or -1. */
static long face_number_in(const char* msg) {
  const char* f = strstr(msg, "face");
  if (!f) return -1;
  for (f += 4; *f && (*f < '0' || *f > '9'); ++f) {
  }
  return *f ? strtol(f, NULL, 10) : -1;
}

TEST(test_pn_on_quads_unsupported) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  /* two triangles, then the quad as face 2 */
  const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5f, 1.5f, 0, 2, 0.5f, 0};
  const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const uint32_t idx[] = {3, 2, 4, 1, 5, 2, 0, 1, 2, 3};
  const uint8_t sizes[] = {3, 3, 4};
  tlod_mesh_desc md = {.positions = pos,
                       .normals = nrm,
                       .vertex_count = 6,
                       .indices = idx,
                       .index_count = 10,
                       .face_type = TLOD_FACE_MIXED,
                       .face_sizes = sizes,
                       .face_count = 3,
                       .label = "mixed"};
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  CHECK(tlod_mesh_face_count(mesh) == 3);
  tlod_surface* s = (tlod_surface*)&md; /* must be overwritten with NULL */
  tlod_result r = tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &s);
  const char* msg = tlod_context_last_error(ctx);
  printf("  PN on a mixed mesh: %s: \"%s\"\n", tlod_result_string(r), msg);
  CHECK_MSG(r == TLOD_ERROR_UNSUPPORTED, "%s", tlod_result_string(r));
  CHECK(s == NULL);
  CHECK_MSG(face_number_in(msg) == 2, "message does not name face 2: \"%s\"", msg);
  /* Phong and flat accept the same mesh */
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &s) == TLOD_SUCCESS);
  CHECK(tlod_surface_patch(s, 2).corner_count == 4 && tlod_surface_patch(s, 0).corner_count == 3);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);

  shape qc = shape_quad_cube();
  tlod_mesh_desc qd = shape_mesh_desc(&qc);
  mesh = new_mesh(ctx, &qd);
  CHECK(mesh);
  s = NULL;
  r = tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &s);
  msg = tlod_context_last_error(ctx);
  CHECK_MSG(r == TLOD_ERROR_UNSUPPORTED, "%s", tlod_result_string(r));
  CHECK(s == NULL);
  CHECK_MSG(face_number_in(msg) == 0, "message does not name face 0: \"%s\"", msg);
  tlod_mesh_destroy(mesh);
  shape_free(&qc);
  tlod_context_destroy(ctx);
}

TEST(test_bad_alpha_rejected) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  tlod_mesh_desc md = shape_mesh_desc(&sph);
  tlod_mesh* mesh = new_mesh(ctx, &md);
  CHECK(mesh);
  const float bad[] = {1.5f, -0.25f, 1.0000001f, -1e-7f, NAN, INFINITY};
  for (int k = 0; k < 6; ++k) {
    tlod_surface* s = (tlod_surface*)&md;
    tlod_result r = tlod_surface_create(
        ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = bad[k]},
        &s);
    CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "alpha %g: %s", (double)bad[k], tlod_result_string(r));
    CHECK_MSG(s == NULL, "alpha %g: *out not cleared", (double)bad[k]);
    CHECK_MSG(strlen(tlod_context_last_error(ctx)) > 0, "alpha %g: no message", (double)bad[k]);
  }
  /* the ends of the range are fine */
  const float good[] = {0.0f, 1.0f};
  for (int k = 0; k < 2; ++k) {
    tlod_surface* s = NULL;
    CHECK(tlod_surface_create(
              ctx, mesh,
              &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = good[k]},
              &s) == TLOD_SUCCESS);
    CHECK(tlod_surface_query_desc(s).alpha == good[k]);
    tlod_surface_destroy(s);
  }
  /* a bad surface type */
  tlod_surface* s = NULL;
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_NUM}, &s) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(s == NULL);
  tlod_mesh_destroy(mesh);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 9. Refresh after a mesh update                                           */
/* ------------------------------------------------------------------------ */

/* Every patch of a and b evaluates bitwise equal (positions, normals,
 * tangents) on a grid, and their patch infos are equal. */
static void check_same_surface(const tlod_surface* a, const tlod_surface* b, const bool* only, bool expect_equal,
                               const char* what) {
  uint32_t patches = tlod_surface_patch_count(a);
  CHECK(patches == tlod_surface_patch_count(b));
  const int N = 8;
  for (uint32_t f = 0; f < patches; ++f) {
    if (only && !only[f]) continue;
    tlod_patch_info ia = tlod_surface_patch(a, f), ib = tlod_surface_patch(b, f);
    bool same = memcmp(&ia, &ib, sizeof ia) == 0;
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= N - i; ++j) {
        tlod_surface_point pa, pb;
        tlod_surface_eval(a, f, (float)i / N, (float)j / N, &pa);
        tlod_surface_eval(b, f, (float)i / N, (float)j / N, &pb);
        same = same && memcmp(&pa, &pb, sizeof pa) == 0;
      }
    CHECK_MSG(same == expect_equal, "%s: patch %u %s", what, f, expect_equal ? "differs" : "did not change");
  }
}

TEST(test_refresh_after_update) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  const tlod_surface_type types[] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int ti = 0; ti < 3; ++ti) {
    shape sph = shape_icosphere(1);
    tlod_mesh_desc md = shape_mesh_desc(&sph);
    tlod_mesh* mesh = new_mesh(ctx, &md);
    CHECK(mesh);
    tlod_surface *s = NULL, *before = NULL, *fresh = NULL;
    tlod_surface_desc sd = {.type = types[ti]};
    CHECK(tlod_surface_create(ctx, mesh, &sd, &s) == TLOD_SUCCESS);
    /* patches touching the moved vertex */
    const uint32_t moved = 7;
    uint32_t faces = tlod_mesh_face_count(mesh), touching = 0;
    bool* touches = calloc(faces, 1);
    bool* untouched = calloc(faces, 1);
    for (uint32_t f = 0; f < faces; ++f) {
      uint32_t vid[4], n = tlod_mesh_face_corners(mesh, f, vid);
      for (uint32_t c = 0; c < n; ++c)
        touches[f] |= vid[c] == moved;
      touching += touches[f];
      untouched[f] = !touches[f];
    }
    CHECK(touching == 5 || touching == 6);
    /* a snapshot of the old surface: a surface made before the update
     * would be refreshed too, so keep a second mesh with the old data */
    tlod_mesh* old_mesh = new_mesh(ctx, &md);
    CHECK(old_mesh);
    CHECK(tlod_surface_create(ctx, old_mesh, &sd, &before) == TLOD_SUCCESS);

    for (int c = 0; c < 3; ++c)
      sph.positions[3 * moved + c] *= 1.25f;
    CHECK(tlod_mesh_update(mesh, sph.positions, 0, NULL, 0) == TLOD_SUCCESS);
    uint32_t updated = 12345;
    CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS);
    CHECK_MSG(updated == touching, "type %d: refresh updated %u patches, %u touch vertex %u", (int)types[ti], updated,
              touching, moved);
    /* matches a surface created fresh on the updated mesh, bitwise */
    CHECK(tlod_surface_create(ctx, mesh, &sd, &fresh) == TLOD_SUCCESS);
    CALL(check_same_surface(s, fresh, NULL, true, "refreshed vs fresh"));
    /* untouched patches are as before, touched ones changed */
    CALL(check_same_surface(s, before, untouched, true, "untouched vs before"));
    CALL(check_same_surface(s, before, touches, false, "touched vs before"));
    /* the moved corner is the new input position */
    float p[3], nn[3];
    tlod_mesh_vertex(mesh, moved, p, nn);
    CHECK(memcmp(p, sph.positions + 3 * moved, sizeof p) == 0);
    /* nothing changed since: nothing recomputed */
    updated = 12345;
    CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS);
    CHECK_MSG(updated == 0, "second refresh updated %u", updated);
    CHECK(tlod_surface_refresh(s, NULL) == TLOD_SUCCESS);
    free(touches);
    free(untouched);
    tlod_surface_destroy(s);
    tlod_surface_destroy(before);
    tlod_surface_destroy(fresh);
    tlod_mesh_destroy(mesh);
    tlod_mesh_destroy(old_mesh);
    shape_free(&sph);
  }
  tlod_context_destroy(ctx);
}

static double now_seconds(void) {
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* RUN with the time taken. */
#define TIMED_RUN(name)                                                                                                \
  do {                                                                                                                 \
    double _t0 = now_seconds();                                                                                        \
    RUN(name);                                                                                                         \
    printf("     (%.2f s)\n", now_seconds() - _t0);                                                                    \
  } while (0)

int main(void) {
  TIMED_RUN(test_phong_reference_identities);
  TIMED_RUN(test_phong_triangle_eval);
  TIMED_RUN(test_phong_vertex_alpha);
  TIMED_RUN(test_phong_triangle_frame);
  TIMED_RUN(test_pn_reference_self);
  TIMED_RUN(test_pn_eval);
  TIMED_RUN(test_phong_quad);
  TIMED_RUN(test_flat_eval);
  TIMED_RUN(test_corners_exact);
  TIMED_RUN(test_alpha_zero_is_flat);
  TIMED_RUN(test_equal_normals_are_flat);
  TIMED_RUN(test_sphere_approximation);
  TIMED_RUN(test_error_bound_flat);
  TIMED_RUN(test_error_bound_phong_triangles);
  TIMED_RUN(test_error_bound_phong_quads);
  TIMED_RUN(test_error_bound_phong_vertex_alpha);
  TIMED_RUN(test_error_bound_pn);
  TIMED_RUN(test_shared_edges_bitwise);
  TIMED_RUN(test_pn_on_quads_unsupported);
  TIMED_RUN(test_bad_alpha_rejected);
  TIMED_RUN(test_refresh_after_update);
  TEST_END();
}
