/* tesslod::core -- per-patch, per-level error tables (issue #9): an upper
 * bound e_l of max |S - P_l| over the patch, P_l the piecewise-linear
 * interpolant of S on the level-l pattern's triangles, for l = 0..K
 * (K = TLOD_ERROR_TABLE_LEVELS - 1), and a rigorous tail c 4^-l above K.
 * Maths, with the proofs: docs/design.md "Error tables". In short:
 *
 *  - flat triangle: 0. Flat (bilinear) quad: exactly |p0 - p1 + p2 - p3| / 4 * 4^-l.
 *  - global-alpha Phong triangle: S - flat = alpha Q, Q quadratic, so the
 *    level-l error is exactly 4^-l max|alpha Q| (every cell sees the same
 *    constant Hessian); max|Q| from a grid with the exact factor 1/(1 - 1/N^2).
 *  - cubic triangles (PN, per-vertex-alpha Phong): on a cell with Taylor
 *    vertex y0, size h, orientation s = +-1 the error is
 *        E(m) = h^2 q_{H(y0)}(m) + s h^3 c(m),
 *    q linear in the Hessian H (affine in y0), c fixed: |E| is convex in y0,
 *    so its max over all cells is reached on the <= 6 cells at the hull of
 *    the lattice (the corner cells of each orientation). Those are sampled on
 *    a sub-grid; between samples the sub-cell error is h_s^2 q + s h_s^3 c,
 *    at most h_s^2 Qbar + h_s^3 Cbar. Level 0's finer grid is read off
 *    level 1's four cells (level01_m2); every entry and the tail are also
 *    capped by the second-derivative bound error_bound 4^-l.
 *  - quads (Phong): a shared sample grid of the patch, all cells, and the
 *    remainder (1/2) M R^2 with M from the tensor net (phong.c); the
 *    samples are float, with a bound of their rounding added.
 *  - every entry adds a slack for the float rounding of the evaluation.
 *  - TLOD_ERROR_TABLES_CLOSED_FORM: error_bound 4^-l plus the same slack,
 *    nothing measured (_tlod_error_table_closed); never below the above.
 * Cost (BENCHMARKS.md "Surface build cost"): the sample loops are laid out
 * so they vectorise (samples by weight, components side by side, one pass
 * over the samples for all cells of a level, maxima as trees), which took
 * the cubic tables from 4.5x to about 2.8x the build without tables. */
#include <math.h>
#include <string.h>

#include "error_table_lanes.h"

#define K (TLOD_ERROR_TABLE_LEVELS - 1)
/* Grid of the quadratic maximum (1/(1 - 1/N^2) = 36/35) and of the cubic cells. */
#define QUAD_N 6
#define CELL_N 3
/* Quads: samples per edge of the shared grid (2^K cells times 2). */
#define QUAD_G (2 << K)

typedef double d3[3];
typedef float fl3[3];

/* Plain maxima (fmax handles NaN, and is a library call at -O2). */
static inline double dmax(double a, double b) { return a > b ? a : b; }
static inline double dmin(double a, double b) { return a < b ? a : b; }
/* 4^-l, exact. */
static const double k_pow4[] = {1.0, 0x1p-2, 0x1p-4, 0x1p-6, 0x1p-8, 0x1p-10};

static double d3_len2(const double* a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; }
/* The largest of a[0..7], as a tree of maxima (depth 3, not a chain of 8). */
static inline double max8(const double* a) {
  return dmax(dmax(dmax(a[0], a[1]), dmax(a[2], a[3])), dmax(dmax(a[4], a[5]), dmax(a[6], a[7])));
}

/* The smallest float >= x (x >= 0): x rounded, and the next float up (the
 * bit pattern + 1, as floats >= 0 are ordered like their bits) if that fell
 * below x. Branch-free: the comparison is data-dependent, and a mispredicted
 * branch per entry cost as much as the rest of a flat patch's table. */
static float float_up(double x) {
  float f = (float)x;
  uint32_t bits;
  memcpy(&bits, &f, sizeof bits);
  bits += (uint32_t)((double)f < x);
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* Float rounding of the evaluation: every evaluated position is a short
 * sum of products of O(scale) coordinates (weights in [0, 1], projections
 * whose offsets are O(extent)); a forward error analysis gives < 8 ulps of
 * scale per point, and a measured deviation compares a point with an
 * interpolant of points: 16 ulps (2^-24 each) of scale + extent. */
static double eval_slack(const _tlod_corners* c, const double (*extra)[3], int extra_n) {
  /* Six independent maxima (per axis, even and odd points), not one chain of
   * dependent ones; one square root (sqrt is monotonic). */
  double s[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, extent2 = 0.0;
  for (uint32_t x = 0; x < c->n; x++) {
    s[0] = dmax(s[0], fabs((double)c->p[x].x)), s[1] = dmax(s[1], fabs((double)c->p[x].y));
    s[2] = dmax(s[2], fabs((double)c->p[x].z));
    double e[3] = {c->p[x].x - c->p[0].x, c->p[x].y - c->p[0].y, c->p[x].z - c->p[0].z};
    extent2 = dmax(extent2, d3_len2(e));
  }
  for (int x = 0; x < extra_n; x += 2) {
    const double* odd = extra[x + 1 < extra_n ? x + 1 : x];
    for (int k = 0; k < 3; k++)
      s[k] = dmax(s[k], fabs(extra[x][k])), s[3 + k] = dmax(s[3 + k], fabs(odd[k]));
  }
  double scale = dmax(dmax(dmax(s[0], s[1]), dmax(s[2], s[3])), dmax(s[4], s[5]));
  return 16.0 * 0x1p-24 * (scale + sqrt(extent2));
}

/* Stores the table: e[l] (exact-arithmetic bounds) plus slack, made
 * non-increasing (suffix maximum, tail included), rounded up to float. */
static void finish(tlod_patch_info* info, const double e[K + 1], double tail, double slack) {
  slack *= 1.0 + 0x1p-20; /* covers the float add in tlod_patch_error_bound */
  info->error_slack = float_up(slack);
  info->error_tail = float_up(tail);
  double next = tail * k_pow4[K + 1] + slack;
  for (int l = K; l >= 0; l--) {
    next = dmax(next, e[l] + slack);
    info->error_table[l] = float_up(next);
  }
}

/* The previous bound (docs/design.md 3.5), set before the table:
 * error_bound, a float rounded to nearest, times 1 + 2^-23 so it is at
 * least the double it was rounded from. */
static double closed_form_bound(const tlod_patch_info* info) { return (double)info->error_bound * (1.0 + 0x1p-23); }

float tlod_patch_error_bound(const tlod_patch_info* info, uint32_t level) {
  if (level < TLOD_ERROR_TABLE_LEVELS) return info->error_table[level];
  if (level > 126) level = 126;
  return ldexpf(info->error_tail, -2 * (int)level) + info->error_slack;
}

/* ------------------------------------------------------------------------ */
/* Quadratic shape on the unit right triangle                               */
/* ------------------------------------------------------------------------ */

/* q(m1, m2) = (m1^2 - m1)/2 A + m1 m2 B + (m2^2 - m2)/2 C: the linear
 * interpolation error, at barycentrics (1 - m1 - m2, m1, m2) of (0,0), (1,0),
 * (0,1), of the quadratic with Hessian (A, B; B, C). An upper bound of
 * max |q|: on the edges exactly (|A|/8, |C|/8, |B - (A+C)/2|/4 at the
 * midpoints), inside on the N-grid, over (1 - 1/N^2): q minus its linear
 * interpolant on a grid sub-triangle is q itself scaled by 1/N^2. */
/* The points: the interior (i, j) / QUAD_N, i, j >= 1, i + j < QUAD_N (10),
 * then the edge midpoints (1/2, 0), (0, 1/2), (1/2, 1/2) and the first again
 * (14: an even count, for the vector loop). |q|^2 = w^T G w with w = (qa, qb,
 * qc) the point's weights and G the Gram matrix of (A, B, C): per point six
 * products of constant weights, not three components of three terms. */
#define QN 14
#define QP(W, i, j) W((double)(i) / QUAD_N, (double)(j) / QUAD_N)
#define QROW(W)                                                                                                        \
  {                                                                                                                    \
    QP(W, 1, 1), QP(W, 1, 2), QP(W, 1, 3), QP(W, 1, 4), QP(W, 2, 1), QP(W, 2, 2), QP(W, 2, 3), QP(W, 3, 1),            \
        QP(W, 3, 2), QP(W, 4, 1), W(0.5, 0.0), W(0.0, 0.5), W(0.5, 0.5), QP(W, 1, 1)                                   \
  }
#define QWA(a, b) (0.5 * ((a) * (a) - (a)))
#define QWB(a, b) ((a) * (b))
#define QWC(a, b) (0.5 * ((b) * (b) - (b)))
#define QAA(a, b) (QWA(a, b) * QWA(a, b))
#define QBB(a, b) (QWB(a, b) * QWB(a, b))
#define QCC(a, b) (QWC(a, b) * QWC(a, b))
#define QAB(a, b) (2.0 * QWA(a, b) * QWB(a, b))
#define QAC(a, b) (2.0 * QWA(a, b) * QWC(a, b))
#define QBC(a, b) (2.0 * QWB(a, b) * QWC(a, b))
static const double k_quad_p[6][QN] = {QROW(QAA), QROW(QBB), QROW(QCC), QROW(QAB), QROW(QAC), QROW(QBC)};

static double d3_dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The squared maximum of |q| on the edges (exact) and at the interior grid points. */
static double quad_shape_m2(const double* A, const double* B, const double* C) {
  const double g[6] = {d3_dot(A, A), d3_dot(B, B), d3_dot(C, C), d3_dot(A, B), d3_dot(A, C), d3_dot(B, C)};
  const double(*p)[QN] = k_quad_p;
  double l2[QN];
  for (int k = 0; k < QN; k++)
    l2[k] = p[0][k] * g[0] + p[1][k] * g[1] + p[2][k] * g[2] + p[3][k] * g[3] + p[4][k] * g[4] + p[5][k] * g[5];
  return dmax(max8(l2), max8(l2 + QN - 8));
}

static double quad_shape_finish(double m2) { return sqrt(m2) / (1.0 - 1.0 / (QUAD_N * QUAD_N)); }

static double quad_shape_max(const double* A, const double* B, const double* C) {
  return quad_shape_finish(quad_shape_m2(A, B, C));
}

/* ------------------------------------------------------------------------ */
/* Cubic triangles                                                          */
/* ------------------------------------------------------------------------ */

typedef struct cubic {
  d3 h[3][3]; /* [corner i, j, k][f_uu, f_uv, f_vv] */
  d3 t[4];    /* f_uuu, f_uuv, f_uvv, f_vvv */
} cubic;

/* 6 (b_p - 2 b_q + b_r) and 6 (b_p - b_q - b_r + b_s): second differences of
 * the net (indices constant at every call, so they fold). */
static inline void diff2(const double (*b)[3], int p, int q, int r, double* out) {
  for (int c = 0; c < 3; c++)
    out[c] = 6.0 * (b[p][c] - 2.0 * b[q][c] + b[r][c]);
}
static inline void twist2(const double (*b)[3], int p, int q, int r, int s, double* out) {
  for (int c = 0; c < 3; c++)
    out[c] = 6.0 * (b[p][c] - b[q][c] - b[r][c] + b[s][c]);
}

/* Net order (_tlod_tri_net): 0 b300, 1 b030, 2 b003, 3 b210, 4 b120, 5 b021,
 * 6 b012, 7 b102, 8 b201, 9 b111 (i: u, j: v, k: w). At corner e_x the
 * Hessian's net is f_uu = 6 (b_{x+200} - 2 b_{x+101} + b_{x+002}), f_uv =
 * 6 (b_{x+110} - b_{x+101} - b_{x+011} + b_{x+002}), f_vv = 6 (b_{x+020} -
 * 2 b_{x+011} + b_{x+002}). */
static void cubic_from_net(const double (*b)[3], cubic* out) {
  diff2(b, 0, 8, 7, out->h[0][0]), twist2(b, 3, 8, 9, 7, out->h[0][1]), diff2(b, 4, 9, 7, out->h[0][2]);
  diff2(b, 3, 9, 6, out->h[1][0]), twist2(b, 4, 9, 5, 6, out->h[1][1]), diff2(b, 1, 5, 6, out->h[1][2]);
  diff2(b, 8, 7, 2, out->h[2][0]), twist2(b, 9, 7, 6, 2, out->h[2][1]), diff2(b, 5, 6, 2, out->h[2][2]);
  for (int c = 0; c < 3; c++) {
    double b300 = b[0][c], b030 = b[1][c], b003 = b[2][c], b210 = b[3][c], b120 = b[4][c];
    double b021 = b[5][c], b012 = b[6][c], b102 = b[7][c], b201 = b[8][c], b111 = b[9][c];
    out->t[0][c] = 6.0 * (b300 - 3.0 * b201 + 3.0 * b102 - b003);
    out->t[1][c] = 6.0 * (b210 - b201 - 2.0 * b111 + 2.0 * b102 + b012 - b003);
    out->t[2][c] = 6.0 * (b120 - 2.0 * b111 + b102 - b021 + 2.0 * b012 - b003);
    out->t[3][c] = 6.0 * (b030 - 3.0 * b021 + 3.0 * b012 - b003);
  }
}

/* Qbar = the largest quad_shape_max of the corner Hessians h[x] = (f_uu, f_uv, f_vv). */
static double quad_shape_max3(const d3 (*h)[3]) {
  double m2 = 0.0;
  for (int x = 0; x < 3; x++)
    m2 = dmax(m2, quad_shape_m2(h[x][0], h[x][1], h[x][2]));
  return quad_shape_finish(m2);
}

/* Weights of one cell sample (m1, m2): quadratic part (of f_uu, f_uv, f_vv)
 * and cubic part (of f_uuu, f_uuv, f_uvv, f_vvv), see cubic_table. Stored
 * by weight (structure of arrays, samples padded to an even count with a
 * repeated sample) so the sample loops vectorise. */
#define WQA(a, b) (0.5 * ((a) * (a) - (a)))
#define WQB(a, b) ((a) * (b))
#define WQC(a, b) (0.5 * ((b) * (b) - (b)))
#define WCA(a, b) (((a) * (a) * (a) - (a)) / 6.0)
#define WCB(a, b) (0.5 * (a) * (a) * (b))
#define WCC(a, b) (0.5 * (a) * (b) * (b))
#define WCD(a, b) (((b) * (b) * (b) - (b)) / 6.0)
/* The CELL_N = 3 grid without the three corners (7 samples, the first repeated). */
#define NS 8 /* max8() reads NS values */
#define G3(W, i, j) W((double)(i) / CELL_N, (double)(j) / CELL_N)
#define ROW3(W)                                                                                                        \
  { G3(W, 1, 0), G3(W, 2, 0), G3(W, 0, 1), G3(W, 1, 1), G3(W, 2, 1), G3(W, 0, 2), G3(W, 1, 2), G3(W, 1, 0) }
static const double k_cell_w[7][NS] = {ROW3(WQA), ROW3(WQB), ROW3(WQC), ROW3(WCA), ROW3(WCB), ROW3(WCC), ROW3(WCD)};
/* Level 0 is one cell, sampled on the CELL0_N = 6 grid (from level 1's cells, level01_m2). */
#define CELL0_N 6

/* On a cell with Taylor vertex y0 = (u0, v0), size h, orientation s, the
 * samples' error E(m_k) = (cell point y0 + s h m_k) - (linear interpolant of
 * the cell's corners) = h^2 (qa f_uu + qb f_uv + qc f_vv)(y0) + s h^3 (ca f_uuu
 * + cb f_uuv + cc f_uvv + cd f_vvv) (Taylor at y0, exact for a cubic). The
 * Hessian at y0 is u0 H_0 + v0 H_1 + w0 H_2 (corner Hessians), so with
 * a2 = q_{H_2}(m_k), d0 = q_{H_0} - a2, d1 = q_{H_1} - a2, t = c(m_k)
 *     E(m_k) = h^2 a2 + s h^3 t + h^2 u0 d0 + h^2 v0 d1:
 * per level two base vectors, then two terms per cell. [component][sample]. */
typedef struct cell_basis {
  double a2[3][NS], d0[3][NS], d1[3][NS], t[3][NS];
} cell_basis;

static void cell_basis_init(const cubic* restrict p, cell_basis* restrict b) {
  const double(*w)[NS] = k_cell_w;
  for (int c = 0; c < 3; c++) {
    /* q is linear in the Hessian: d_x = q_{H_x - H_2} */
    const double h2a = p->h[2][0][c], h2b = p->h[2][1][c], h2c = p->h[2][2][c];
    const double h0a = p->h[0][0][c] - h2a, h0b = p->h[0][1][c] - h2b, h0c = p->h[0][2][c] - h2c;
    const double h1a = p->h[1][0][c] - h2a, h1b = p->h[1][1][c] - h2b, h1c = p->h[1][2][c] - h2c;
    const double ta = p->t[0][c], tb = p->t[1][c], tc = p->t[2][c], td = p->t[3][c];
    for (int k = 0; k < NS; k++) {
      b->a2[c][k] = w[0][k] * h2a + w[1][k] * h2b + w[2][k] * h2c;
      b->d0[c][k] = w[0][k] * h0a + w[1][k] * h0b + w[2][k] * h0c;
      b->d1[c][k] = w[0][k] * h1a + w[1][k] * h1b + w[2][k] * h1c;
      b->t[c][k] = w[3][k] * ta + w[4][k] * tb + w[5][k] * tc + w[6][k] * td;
    }
  }
}

/* Level l >= 2: max |E|^2 over the samples of the six hull cells, lower at
 * y0 = (0,0), (1-h,0), (0,1-h), upper at (h,h), (1-h,h), (h,1-h), i.e. with
 * lo = h^2 a2 + h^3 t, up = h^2 a2 - h^3 t, g = h^2 (1 - h):
 *   lo, lo + g d0, lo + g d1, up + h^3 (d0 + d1), up + g d0 + h^3 d1, up + h^3 d0 + g d1.
 * All six in one pass over the samples, so each basis value is loaded once. */
static inline void hull_add(const cell_basis* restrict b, int c, int k, const double w[3], double s[6]) {
  double lo = w[0] * b->a2[c][k] + w[1] * b->t[c][k], up = w[0] * b->a2[c][k] - w[1] * b->t[c][k];
  double gd0 = w[2] * b->d0[c][k], gd1 = w[2] * b->d1[c][k], hd0 = w[1] * b->d0[c][k], hd1 = w[1] * b->d1[c][k];
  double e1 = lo + gd0, e2 = lo + gd1, e3 = up + hd0 + hd1, e4 = up + gd0 + hd1, e5 = up + hd0 + gd1;
  s[0] += lo * lo, s[1] += e1 * e1, s[2] += e2 * e2, s[3] += e3 * e3, s[4] += e4 * e4, s[5] += e5 * e5;
}

static double hull_cells_m2(const cell_basis* restrict b, double h2, double h3, double g) {
  const double w[3] = {h2, h3, g};
  double acc[NS];
  for (int k = 0; k < NS; k++) {
    double s[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    hull_add(b, 0, k, w, s), hull_add(b, 1, k, w, s), hull_add(b, 2, k, w, s);
    acc[k] = dmax(dmax(dmax(s[0], s[1]), dmax(s[2], s[3])), dmax(s[4], s[5]));
  }
  return max8(acc);
}

/* Level 0 (one cell, y0 = (0, 0), h = 1) on the 6-grid, from level 1's
 * four cells: their 3-grid samples and the three edge midpoints are the
 * 6-grid, and on a level-1 cell S - P_0 = (S - P_1) + (P_1 - P_0), the last
 * term linear, equal to E_0 = S - P_0 at the cell's corners (0 at the
 * patch's corners, E_0 at the midpoints: the one-cell formula). */
#define BARY(a, b) (1.0 - (a) - (b))
#define M1(a, b) (a)
#define M2(a, b) (b)
static const double k_cell_b[3][NS] = {ROW3(BARY), ROW3(M1), ROW3(M2)};
/* E_0 at the edge midpoints (1/2, 0), (0, 1/2), (1/2, 1/2), mid[point][component],
 * from the net: a cubic edge's midpoint is (b_i + 3 b_ij + 3 b_ji + b_j) / 8,
 * so S - P_0 there is 3/8 (b_ij + b_ji - b_i - b_j). */
static double cubic_midpoints(const double (*b)[3], d3 mid[3]) {
  static const int edge[3][4] = {{8, 7, 0, 2}, {5, 6, 1, 2}, {3, 4, 0, 1}}; /* b201 b102 b300 b003, ... */
  double m2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const int* e = edge[k];
    for (int c = 0; c < 3; c++)
      mid[k][c] = 0.375 * ((b[e[0]][c] + b[e[1]][c]) - (b[e[2]][c] + b[e[3]][c]));
    m2 = dmax(m2, d3_len2(mid[k]));
  }
  return m2;
}

/* Levels 1 and 0 from level 1's four cells (h = 1/2, so g = h^2 (1 - h) =
 * h^3 = 1/8): E_1 of lower (0,0), (1/2,0), (0,1/2): lo, lo + g d0, lo + g d1,
 * and upper (1/2,1/2): up + g (d0 + d1), into m[0]; E_1 plus the interpolant
 * of the cell's corner values of E_0 (B0 at y0, B1 at the m1 corner, B2 at
 * the m2 corner: 0 at the patch's corners, mid[] at the edge midpoints; the
 * upper cell's m1 corner is (0, 1/2), its m2 corner (1/2, 0)) into m[1]:
 * max |.|^2 over the samples, one pass. */
static inline void level01_add(const cell_basis* restrict b, int c, int k, const d3 mid[3], double s[8]) {
  const double *B0 = k_cell_b[0], *B1 = k_cell_b[1], *B2 = k_cell_b[2], g = 0.125;
  double lo = 0.25 * b->a2[c][k] + 0.125 * b->t[c][k], up = 0.25 * b->a2[c][k] - 0.125 * b->t[c][k];
  double gd0 = g * b->d0[c][k], gd1 = g * b->d1[c][k];
  double e2 = lo + gd0, e3 = lo + gd1, e4 = up + gd0 + gd1;
  double f1 = lo + B1[k] * mid[0][c] + B2[k] * mid[1][c], f2 = e2 + B0[k] * mid[0][c] + B2[k] * mid[2][c];
  double f3 = e3 + B0[k] * mid[1][c] + B1[k] * mid[2][c];
  double f4 = e4 + B0[k] * mid[2][c] + B1[k] * mid[1][c] + B2[k] * mid[0][c];
  s[0] += lo * lo, s[1] += e2 * e2, s[2] += e3 * e3, s[3] += e4 * e4;
  s[4] += f1 * f1, s[5] += f2 * f2, s[6] += f3 * f3, s[7] += f4 * f4;
}

static void level01_m2(const cell_basis* restrict b, const d3 mid[3], double m[2]) {
  double acc1[NS], acc0[NS];
  for (int k = 0; k < NS; k++) {
    double s[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    level01_add(b, 0, k, mid, s), level01_add(b, 1, k, mid, s), level01_add(b, 2, k, mid, s);
    acc1[k] = dmax(dmax(s[0], s[1]), dmax(s[2], s[3]));
    acc0[k] = dmax(dmax(s[4], s[5]), dmax(s[6], s[7]));
  }
  m[0] = dmax(m[0], max8(acc1)), m[1] = dmax(m[1], max8(acc0));
}

static void cubic_table(const double (*net)[3], const _tlod_corners* c, const double (*extra)[3], int extra_n,
                        tlod_patch_info* info) {
  cubic p;
  cubic_from_net(net, &p);
  /* Qbar: max over the patch of the quadratic shape's max (convex in the
   * Hessian, which is affine: the corners); Cbar: the cubic shape's max,
   * |m1^3 - m1|/6 <= 0.06416, m1^2 m2 / 2 <= 2/27 < 0.07408. */
  double qbar = quad_shape_max3(p.h);
  double cbar = 0.06416 * (sqrt(d3_len2(p.t[0])) + sqrt(d3_len2(p.t[3]))) +
                0.07408 * (sqrt(d3_len2(p.t[1])) + sqrt(d3_len2(p.t[2])));
  double e[K + 1];
  cell_basis b;
  cell_basis_init(&p, &b);
  {
    /* Levels 0 and 1: h = 1/2, the four cells (0,0), (1/2,0), (0,1/2) lower, (1/2,1/2) upper. */
    const double h2 = 0.25, h3 = 0.125, hs0 = 1.0 / CELL0_N, hs1 = 0.5 / CELL_N;
    d3 mid[3]; /* E_0 at (1/2,0), (0,1/2), (1/2,1/2) */
    double m[2] = {0.0, cubic_midpoints(net, mid)};
    level01_m2(&b, (const d3*)mid, m);
    e[0] = dmin(sqrt(m[1]) + hs0 * hs0 * qbar + hs0 * hs0 * hs0 * cbar, qbar + cbar);
    e[1] = dmin(sqrt(m[0]) + hs1 * hs1 * qbar + hs1 * hs1 * hs1 * cbar, h2 * qbar + h3 * cbar);
  }
  for (int l = 2; l <= K; l++) {
    double h = 1.0 / (double)(1 << l), hs = h / CELL_N, h2 = h * h, h3 = h2 * h;
    double sampled = sqrt(hull_cells_m2(&b, h2, h3, h2 * (1.0 - h))) + hs * hs * qbar + hs * hs * hs * cbar;
    e[l] = dmin(sampled, h2 * qbar + h3 * cbar);
  }
  /* l > K: h^2 Qbar + h^3 Cbar <= 4^-l (Qbar + 2^-(K+1) Cbar). The
   * second-derivative bound (error_bound, with its exact 4^-l law) is also a
   * bound at every level, and is the smaller of the two on some patches
   * (Qbar's 36/35, the h^3 term): every entry takes the smaller, so the
   * measured table is never above the closed-form one. */
  double eb = closed_form_bound(info), tail = dmin(qbar + cbar / (double)(1 << (K + 1)), eb);
  for (int l = 0; l <= K; l++)
    e[l] = dmin(e[l], eb * k_pow4[l]);
  finish(info, e, tail, eval_slack(c, extra, extra_n));
}

/* ------------------------------------------------------------------------ */
/* Quadratic triangles, quads                                               */
/* ------------------------------------------------------------------------ */

/* A quadratic deviation from the flat triangle with constant Hessian (A, B;
 * B, C) in (u, v): every level-l cell errs by exactly 4^-l times level 0. */
static void hessian_tri_table(const double* A, const double* B, const double* C, double cap, double slack,
                              tlod_patch_info* info) {
  double e0 = dmin(quad_shape_max(A, B, C), cap), e[K + 1];
  for (int l = 0; l <= K; l++)
    e[l] = e0 * k_pow4[l];
  finish(info, e, e0, slack);
}

/* S - flat = alpha Q, Q = 2 (uv d_ij + vw d_jk + wu d_ki): Hessian in (u, v)
 * Q_uu = -4 d_ki, Q_uv = 2 (d_ij - d_jk - d_ki), Q_vv = -4 d_jk. */
static void phong_tri_table(const _tlod_corners* c, tlod_patch_info* info) {
  d3 d[3];
  for (uint32_t x = 0; x < 3; x++) {
    uint32_t i = x, j = (x + 1) % 3;
    v3 b = v3_scale(v3_add(v3_project(c->p[j], c->p[i], c->nrm[i]), v3_project(c->p[i], c->p[j], c->nrm[j])), 0.5f);
    v3 dv = v3_sub(b, v3_scale(v3_add(c->p[i], c->p[j]), 0.5f));
    d[x][0] = dv.x, d[x][1] = dv.y, d[x][2] = dv.z;
  }
  double a = c->alpha[0], A[3], B[3], C[3];
  for (int k = 0; k < 3; k++) {
    A[k] = -4.0 * a * d[2][k];
    B[k] = 2.0 * a * (d[0][k] - d[1][k] - d[2][k]);
    C[k] = -4.0 * a * d[1][k];
  }
  hessian_tri_table(A, B, C, INFINITY, eval_slack(c, NULL, 0), info);
}

/* A quadratic triangle: S - flat = 2 (uv dev_ij + vw dev_jk + wu dev_ki),
 * dev = 2 (M - mid), the Phong form above with alpha d -> dev; capped by
 * the closed form (2/3) max |dev| (error_bound), so the measured table is
 * never above the closed-form one. */
static void quadratic_tri_table(const double (*dev)[3], double slack, tlod_patch_info* info) {
  double A[3], B[3], C[3];
  for (int k = 0; k < 3; k++) {
    A[k] = -4.0 * dev[2][k];
    B[k] = 2.0 * (dev[0][k] - dev[1][k] - dev[2][k]);
    C[k] = -4.0 * dev[1][k];
  }
  hessian_tri_table(A, B, C, closed_form_bound(info), slack, info);
}

/* Power form of a bicubic tensor net: a[p][q] of u^p v^q. */
static void quad_power(const double (*net)[4][3], d3 a[4][4]) {
  for (int c = 0; c < 3; c++) {
    double t[4][4];
    for (int i = 0; i < 4; i++) { /* along v for each i */
      const double b0 = net[i][0][c], b1 = net[i][1][c], b2 = net[i][2][c], b3 = net[i][3][c];
      t[i][0] = b0, t[i][1] = 3.0 * (b1 - b0), t[i][2] = 3.0 * (b2 - 2.0 * b1 + b0),
      t[i][3] = b3 - 3.0 * b2 + 3.0 * b1 - b0;
    }
    for (int q = 0; q < 4; q++) {
      const double b0 = t[0][q], b1 = t[1][q], b2 = t[2][q], b3 = t[3][q];
      a[0][q][c] = b0, a[1][q][c] = 3.0 * (b1 - b0), a[2][q][c] = 3.0 * (b2 - 2.0 * b1 + b0);
      a[3][q][c] = b3 - 3.0 * b2 + 3.0 * b1 - b0;
    }
  }
}

/* A biquadratic (a quadratic face, degree-elevated to the bicubic net)
 * S = sum c_pq u^p v^q, p, q <= 2. On a cell of size h at (a, b), in cell
 * coordinates (x, y), S minus its linear interpolant on either of the
 * cell's triangles is E[S] = h^2 E[A x^2 + B xy + C y^2] + h^3 E[(c21 + 2 c22 b)
 * x^2 y + (c12 + 2 c22 a) x y^2] + h^4 E[c22 x^2 y^2], with A = c20 + c21 b +
 * c22 b^2, B = c11 + 2 c21 a + 2 c12 b + 4 c22 a b, C = c02 + c12 a + c22 a^2
 * (Taylor at (a, b), exact). So e(h) <= h^2 Q + h^3 Cb + h^4 D:
 *  - Q: max |E| of the quadratic part over all (a, b). (A, B, C) is a
 *    polynomial of bidegree (2, 2) in (a, b), so it lies in the convex hull
 *    of its 3 x 3 Bezier net, and |E| is convex in it (E is linear): the
 *    max over the net points of quad_shape_max, each triangle mapped to
 *    the unit one (t1 = (0,0) (1,0) (1,1): Hessian (2A, 2A + B, 2(A + B +
 *    C)); t2 = (0,0) (1,1) (0,1): (2(A + B + C), B + 2C, 2C)).
 *  - max |E[x^2 y]| = max |E[x y^2]| = 2 / (3 sqrt 3) < 0.385 on both
 *    triangles (x (1 - x^2) on the diagonal), max |E[x^2 y^2]| < 0.4726
 *    (y (1 - y^3) at y^3 = 1/4); the cubic coefficients are affine in b (a),
 *    so their norms peak at 0 or 1.
 *  - the net's bicubic remainder (a_pq with p or q = 3, rounding only): each
 *    such monomial errs by at most M/4 h^2 <= 3.75 h^2; counted 16 times. */
typedef struct biquad_law {
  double q, c, d; /* e(h) <= h^2 (q + h (c + h d)) */
} biquad_law;

static double biquad_at(const biquad_law* b, double h) { return h * h * (b->q + h * (b->c + h * b->d)); }

static double d3_norm(const double* a) { return sqrt(d3_len2(a)); }

/* The net point (i, j) of (A, B, C), in the two triangles' Hessians h[2][3]. */
static void biquad_hessians(const d3 (*a)[4], int i, int j, d3 h[2][3]) {
  double bi = 0.5 * i, bj = 0.5 * j; /* B is bilinear: its net is its values at (i/2, j/2) */
  for (int k = 0; k < 3; k++) {
    const double A = a[2][0][k] + (j > 0 ? 0.5 * a[2][1][k] : 0.0) + (j > 1 ? 0.5 * a[2][1][k] + a[2][2][k] : 0.0);
    const double C = a[0][2][k] + (i > 0 ? 0.5 * a[1][2][k] : 0.0) + (i > 1 ? 0.5 * a[1][2][k] + a[2][2][k] : 0.0);
    const double B = a[1][1][k] + 2.0 * a[2][1][k] * bi + 2.0 * a[1][2][k] * bj + 4.0 * a[2][2][k] * bi * bj;
    h[0][0][k] = 2.0 * A, h[0][1][k] = 2.0 * A + B, h[0][2][k] = 2.0 * (A + B + C);
    h[1][0][k] = 2.0 * (A + B + C), h[1][1][k] = B + 2.0 * C, h[1][2][k] = 2.0 * C;
  }
}

static biquad_law biquad_bound(const d3 (*a)[4]) {
  double m2 = 0.0, rest = 0.0, c21[3], c12[3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      d3 h[2][3];
      biquad_hessians(a, i, j, h);
      m2 = dmax(m2, dmax(quad_shape_m2(h[0][0], h[0][1], h[0][2]), quad_shape_m2(h[1][0], h[1][1], h[1][2])));
    }
  for (int p = 0; p < 4; p++)
    for (int q = 0; q < 4; q++)
      rest += (p == 3 || q == 3) ? d3_norm(a[p][q]) : 0.0;
  for (int k = 0; k < 3; k++)
    c21[k] = a[2][1][k] + 2.0 * a[2][2][k], c12[k] = a[1][2][k] + 2.0 * a[2][2][k];
  double cub = 0.385 * (dmax(d3_norm(a[2][1]), d3_norm(c21)) + dmax(d3_norm(a[1][2]), d3_norm(c12)));
  return (biquad_law){quad_shape_finish(m2) + 16.0 * 3.75 * rest, cub, 0.4726 * d3_norm(a[2][2])};
}

/* The largest squared deviation of the grid samples f of one cell (corner
 * (i0, j0), `step` grid steps a side) from the cell's two linear triangles,
 * (i0, j0) (i0+s, j0) (i0+s, j0+s) below the diagonal (j <= i) and (i0, j0)
 * (i0+s, j0+s) (i0, j0+s) above it. A sample's interpolant is
 * f00 + si gu + tj gv, evaluated left to right: the row part f00 + si gu is
 * the same for a whole row, so it is formed once a row (the same roundings
 * as per sample) and the components are kept in registers: this loop was
 * 55% of a Phong quad's surface build. In float (the grid is relative to
 * the patch's corner, quad_grid_floats; quad_table_from adds the roundings'
 * allowance), and without the four corners, whose deviation is rounding
 * alone: a quarter of the samples. */
static double quad_cell_m2(const fl3 (*f)[QUAD_G + 1], int i0, int j0, int step) {
  const float *f00 = f[i0][j0], *f10 = f[i0 + step][j0], *f11 = f[i0 + step][j0 + step], *f01 = f[i0][j0 + step];
  float du1[3], dv1[3], du2[3], dv2[3], inv = 1.0f / (float)step, worst = 0.0f;
  for (int k = 0; k < 3; k++)
    du1[k] = f10[k] - f00[k], dv1[k] = f11[k] - f10[k], du2[k] = f11[k] - f01[k], dv2[k] = f01[k] - f00[k];
  for (int i = 0; i <= step; i++) {
    float si = (float)i * inv, r1[3], r2[3];
    for (int k = 0; k < 3; k++)
      r1[k] = f00[k] + si * du1[k], r2[k] = f00[k] + si * du2[k];
    const float* row = f[i0 + i][j0];
    int corner = i == 0 || i == step; /* the first and last row start and end at a corner */
    for (int j = corner; j <= step - corner; j++) {
      float tj = (float)j * inv;
      const float *r = j <= i ? r1 : r2, *gv = j <= i ? dv1 : dv2, *p = row + 3 * j;
      float dx = p[0] - (r[0] + tj * gv[0]), dy = p[1] - (r[1] + tj * gv[1]), dz = p[2] - (r[2] + tj * gv[2]);
      float x = dx * dx + dy * dy + dz * dz;
      worst = worst > x ? worst : x;
    }
  }
  return worst;
}

/* The shared grid g[i][j] = S(i/G, j/G) - S(0, 0) in float, returning its
 * largest component E (which scales the float samples' rounding allowance,
 * quad_table_from). In double: the power form without its constant, each
 * row's cubic in v by Horner's rule in u, then forward differences along
 * the row (3 additions a value instead of 6 operations), each value rounded
 * once to float; the double roundings, below 2^-40 E, are inside the
 * allowance's room. */
static double quad_grid_floats(const d3 (*a)[4], fl3 (*g)[QUAD_G + 1]) {
  const double h = 1.0 / QUAD_G, h2 = h * h, h3 = h2 * h;
  float e = 0.0f;
  for (int i = 0; i <= QUAD_G; i++) {
    double u = (double)i / QUAD_G, fd[4][3];
    for (int k = 0; k < 3; k++) {
      double c[4];
      for (int q = 0; q < 4; q++)
        c[q] = ((a[3][q][k] * u + a[2][q][k]) * u + a[1][q][k]) * u + (q ? a[0][q][k] : 0.0);
      fd[0][k] = c[0], fd[1][k] = (c[1] * h + c[2] * h2) + c[3] * h3;
      fd[2][k] = 2.0 * c[2] * h2 + 6.0 * c[3] * h3, fd[3][k] = 6.0 * c[3] * h3;
    }
    for (int j = 0; j <= QUAD_G; j++)
      for (int k = 0; k < 3; k++) {
        g[i][j][k] = (float)fd[0][k];
        float x = fabsf(g[i][j][k]);
        e = e > x ? e : x;
        fd[0][k] = fd[0][k] + fd[1][k], fd[1][k] = fd[1][k] + fd[2][k], fd[2][k] = fd[2][k] + fd[3][k];
      }
  }
  return e;
}

/* The table of a quad (Phong or biquadratic) from its net's m and the
 * squared maxima worst2[l] of the shared grid's level-l cells: between grid
 * points (sub-triangles with legs 1/G, R^2 = 1/(2 G^2)) at most M/(4 G^2).
 * The samples are float, relative to the patch's corner 0, E the grid's
 * largest component: a sample's roundings (the grid values', the
 * interpolant's, the difference) are at most 14 u E per component, u = 2^-24
 * (docs/design.md 3.5b), so 32 u E bounds their norm, with room; the float
 * sum of squares and its square root err by a few u relatively (1 + 2^-21),
 * and squares below 2^-126 by at most 2^-61 absolutely. A biquadratic (law
 * finite) also takes the h^2 law above, for the remainder, every level and
 * the tail. */
static void quad_table_from(double m, const double* worst2, double grid_max, const biquad_law* law, double slack,
                            tlod_patch_info* info) {
  enum { G = QUAD_G };
  double e[K + 1], allowance = 32.0 * 0x1p-24 * grid_max + 0x1p-61;
  for (int l = 0; l <= K; l++) {
    double sampled = sqrt(worst2[l]) * (1.0 + 0x1p-21) + allowance + dmin(m / (4.0 * G * G), biquad_at(law, 1.0 / G));
    e[l] = dmin(dmin(sampled, m / 4.0 * k_pow4[l]), biquad_at(law, k_pow4[l] * (1 << l)));
  }
  /* l > K: h <= 2^-(K+1), so e(h) <= 4^-l (q + 2^-(K+1) (c + 2^-(K+1) d)). */
  finish(info, e, dmin(m / 4.0, biquad_at(law, 1.0 / (1 << (K + 1))) * (double)(1 << (2 * (K + 1)))), slack);
}

/* All cells of levels 0..K on the shared (QUAD_G + 1)^2 grid (the same
 * loops, in lanes of patches: error_table_lanes.inc). */
static void phong_quad_table(const double (*net)[4][3], bool biquadratic, double slack, tlod_patch_info* info) {
  enum { G = QUAD_G, S = G + 1 };
  d3 a[4][4];
  quad_power(net, a);
  fl3 g[S][S];
  double grid_max = quad_grid_floats((const d3(*)[4])a, g), worst2[K + 1];
  for (int l = 0; l <= K; l++) {
    int step = G >> l, cells = 1 << l;
    double worst = 0.0;
    for (int ca = 0; ca < cells; ca++)
      for (int cb = 0; cb < cells; cb++)
        worst = dmax(worst, quad_cell_m2((const fl3(*)[S])g, ca * step, cb * step, step));
    worst2[l] = worst;
  }
  biquad_law law = biquadratic ? biquad_bound((const d3(*)[4])a) : (biquad_law){INFINITY, 0.0, 0.0};
  quad_table_from(_tlod_quad_net_m(net), worst2, grid_max, &law, slack, info);
}

/* Bilinear: S = ... + u v (p0 - p1 + p2 - p3); on a cell's triangle the
 * u v term errs by h^2 t (1 - s) (t <= s), at most h^2 / 4. */
static void flat_quad_table(const _tlod_corners* c, tlod_patch_info* info) {
  double twist[3] = {(double)c->p[0].x - c->p[1].x + c->p[2].x - c->p[3].x,
                     (double)c->p[0].y - c->p[1].y + c->p[2].y - c->p[3].y,
                     (double)c->p[0].z - c->p[1].z + c->p[2].z - c->p[3].z};
  double e0 = _tlod_norm3(twist) / 4.0, e[K + 1];
  for (int l = 0; l <= K; l++)
    e[l] = e0 * k_pow4[l];
  finish(info, e, e0, eval_slack(c, NULL, 0));
}

/* Closed-form mode: error_bound is a rigorous bound of the level-0
 * deviation with the 4^-l law (docs/design.md 3.5); the slack is the
 * measured tables' own, so the two modes differ only in e_l. */
void _tlod_error_table_closed(const _tlod_corners* c, const double (*extra)[3], int extra_n, tlod_patch_info* info) {
  _tlod_error_table_closed_slack(eval_slack(c, extra, extra_n), info);
}

void _tlod_error_table_closed_slack(double slack, tlod_patch_info* info) {
  double e[K + 1], e0 = closed_form_bound(info);
  for (int l = 0; l <= K; l++)
    e[l] = e0 * k_pow4[l];
  finish(info, e, e0, slack);
}

/* A quadratic face's evaluation is a sum of up to 9 products with Lagrange
 * weights in [-1/8, 1] (sum of |weights| <= 25/16 on quads, 5/3 on
 * triangles), each weight a few roundings: three times the Phong slack. */
static double quadratic_slack(const _tlod_corners* c, const double (*nodes)[3], int node_n) {
  return 3.0 * eval_slack(c, nodes, node_n);
}

void _tlod_error_table_quadratic_closed(const _tlod_corners* c, const double (*nodes)[3], int node_n,
                                        tlod_patch_info* info) {
  double e[K + 1], e0 = closed_form_bound(info);
  for (int l = 0; l <= K; l++)
    e[l] = e0 * k_pow4[l];
  finish(info, e, e0, quadratic_slack(c, nodes, node_n));
}

void _tlod_error_table_quadratic(const _tlod_corners* c, const double (*dev)[3], const double (*quad_net)[4][3],
                                 const double (*nodes)[3], int node_n, tlod_patch_info* info) {
  if (c->n == 4)
    phong_quad_table(quad_net, true, quadratic_slack(c, nodes, node_n), info);
  else
    quadratic_tri_table(dev, quadratic_slack(c, nodes, node_n), info);
}

void _tlod_error_table(tlod_surface_type type, const _tlod_corners* c, const double (*net)[3],
                       const double (*quad_net)[4][3], tlod_patch_info* info) {
  static const double zero[K + 1] = {0};
  if (c->n == 4) {
    if (quad_net)
      phong_quad_table(quad_net, false, eval_slack(c, NULL, 0), info);
    else
      flat_quad_table(c, info);
  } else if (type == TLOD_SURFACE_PN) {
    cubic_table(net, c, net, 10, info);
  } else if (net) {
    cubic_table(net, c, NULL, 0, info);
  } else if (type == TLOD_SURFACE_PHONG) {
    phong_tri_table(c, info);
  } else {
    finish(info, zero, 0.0, eval_slack(c, NULL, 0));
  }
}
