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
 *    level 1's four cells (see cell_acc01).
 *  - quads (Phong): a shared sample grid of the patch, all cells, and the
 *    remainder (1/2) M R^2 with M from the tensor net (phong.c).
 *  - every entry adds a slack for the float rounding of the evaluation. */
#include <float.h>
#include <math.h>

#include "surface_eval.h"

#define K (TLOD_ERROR_TABLE_LEVELS - 1)
/* Grid of the quadratic maximum (1/(1 - 1/N^2) = 36/35) and of the cubic cells. */
#define QUAD_N 6
#define CELL_N 3
/* Quads: samples per edge of the shared grid (2^K cells times 2). */
#define QUAD_G (2 << K)

typedef double d3[3];

/* Plain maxima (fmax handles NaN, and is a library call at -O2). */
static inline double dmax(double a, double b) { return a > b ? a : b; }
static inline double dmin(double a, double b) { return a < b ? a : b; }
/* 4^-l, exact. */
static const double k_pow4[] = {1.0, 0x1p-2, 0x1p-4, 0x1p-6, 0x1p-8, 0x1p-10};

static double d3_len2(const double* a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; }

/* The smallest float >= x (x >= 0). */
static float float_up(double x) {
  float f = (float)x;
  return (double)f < x ? f * (1.0f + FLT_EPSILON) : f;
}

/* Float rounding of the evaluation: every evaluated position is a short
 * sum of products of O(scale) coordinates (weights in [0, 1], projections
 * whose offsets are O(extent)); a forward error analysis gives < 8 ulps of
 * scale per point, and a measured deviation compares a point with an
 * interpolant of points: 16 ulps (2^-24 each) of scale + extent. */
static double eval_slack(const _tlod_corners* c, const double (*extra)[3], int extra_n) {
  double scale = 0.0, extent = 0.0;
  for (uint32_t x = 0; x < c->n; x++) {
    scale = dmax(scale, dmax(fabs((double)c->p[x].x), dmax(fabs((double)c->p[x].y), fabs((double)c->p[x].z))));
    double e[3] = {c->p[x].x - c->p[0].x, c->p[x].y - c->p[0].y, c->p[x].z - c->p[0].z};
    extent = dmax(extent, _tlod_norm3(e));
  }
  for (int x = 0; x < extra_n; x++)
    for (int k = 0; k < 3; k++)
      scale = dmax(scale, fabs(extra[x][k]));
  return 16.0 * 0x1p-24 * (scale + extent);
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
/* The interior points (i, j) / QUAD_N, i, j >= 1, i + j < QUAD_N (10). */
#define QN 10
#define QP(W, i, j) W((double)(i) / QUAD_N, (double)(j) / QUAD_N)
#define QROW(W)                                                                                                        \
  {                                                                                                                    \
    QP(W, 1, 1), QP(W, 1, 2), QP(W, 1, 3), QP(W, 1, 4), QP(W, 2, 1), QP(W, 2, 2), QP(W, 2, 3), QP(W, 3, 1),            \
        QP(W, 3, 2), QP(W, 4, 1)                                                                                       \
  }
#define QWA(a, b) (0.5 * ((a) * (a) - (a)))
#define QWB(a, b) ((a) * (b))
#define QWC(a, b) (0.5 * ((b) * (b) - (b)))
static const double k_quad_w[3][QN] = {QROW(QWA), QROW(QWB), QROW(QWC)};

/* The squared maximum of |q| on the edges (exact) and at the interior grid
 * points, the latter into acc[k] (an elementwise maximum). */
static double quad_shape_m2(const double* A, const double* B, const double* C, double* restrict acc) {
  double hyp[3] = {B[0] - 0.5 * (A[0] + C[0]), B[1] - 0.5 * (A[1] + C[1]), B[2] - 0.5 * (A[2] + C[2])};
  double l2[QN] = {0};
  for (int c = 0; c < 3; c++)
    for (int k = 0; k < QN; k++) {
      double q = k_quad_w[0][k] * A[c] + k_quad_w[1][k] * B[c] + k_quad_w[2][k] * C[c];
      l2[k] += q * q;
    }
  for (int k = 0; k < QN; k++)
    acc[k] = acc[k] > l2[k] ? acc[k] : l2[k];
  return dmax(d3_len2(A) / 64.0, dmax(d3_len2(C) / 64.0, d3_len2(hyp) / 16.0));
}

static double quad_shape_finish(double m2, const double* acc) {
  for (int k = 0; k < QN; k++)
    m2 = dmax(m2, acc[k]);
  return sqrt(m2) / (1.0 - 1.0 / (QUAD_N * QUAD_N));
}

static double quad_shape_max(const double* A, const double* B, const double* C) {
  double acc[QN] = {0};
  return quad_shape_finish(quad_shape_m2(A, B, C, acc), acc);
}

/* ------------------------------------------------------------------------ */
/* Cubic triangles                                                          */
/* ------------------------------------------------------------------------ */

/* Net index of b_{ijk} (i: u, j: v, k: w), _tlod_tri_net order. */
static int at(int i, int j, int k) {
  static const int idx[4][4] = {{2, 6, 5, 1}, {7, 9, 4, -1}, {8, 3, -1, -1}, {0, -1, -1, -1}}; /* [i][j] */
  (void)k;
  return idx[i][j];
}

typedef struct cubic {
  d3 h[3][3]; /* [corner i, j, k][f_uu, f_uv, f_vv] */
  d3 t[4];    /* f_uuu, f_uuv, f_uvv, f_vvv */
} cubic;

static void cubic_from_net(const double (*b)[3], cubic* out) {
  static const int base[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int x = 0; x < 3; x++) {
    int i = base[x][0], j = base[x][1], k = base[x][2];
    for (int c = 0; c < 3; c++) {
      out->h[x][0][c] = 6.0 * (b[at(i + 2, j, k)][c] - 2.0 * b[at(i + 1, j, k + 1)][c] + b[at(i, j, k + 2)][c]);
      out->h[x][1][c] = 6.0 * (b[at(i + 1, j + 1, k)][c] - b[at(i + 1, j, k + 1)][c] - b[at(i, j + 1, k + 1)][c] +
                               b[at(i, j, k + 2)][c]);
      out->h[x][2][c] = 6.0 * (b[at(i, j + 2, k)][c] - 2.0 * b[at(i, j + 1, k + 1)][c] + b[at(i, j, k + 2)][c]);
    }
  }
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
  double acc[QN] = {0}, m2 = 0.0;
  for (int x = 0; x < 3; x++)
    m2 = dmax(m2, quad_shape_m2(h[x][0], h[x][1], h[x][2], acc));
  return quad_shape_finish(m2, acc);
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
#define NS 8
#define G3(W, i, j) W((double)(i) / CELL_N, (double)(j) / CELL_N)
#define ROW3(W)                                                                                                        \
  { G3(W, 1, 0), G3(W, 2, 0), G3(W, 0, 1), G3(W, 1, 1), G3(W, 2, 1), G3(W, 0, 2), G3(W, 1, 2), G3(W, 1, 0) }
static const double k_cell_w[7][NS] = {ROW3(WQA), ROW3(WQB), ROW3(WQC), ROW3(WCA), ROW3(WCB), ROW3(WCC), ROW3(WCD)};
/* Level 0 is one cell, sampled on the CELL0_N = 6 grid (from level 1's cells, cell_acc01). */
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
    const double h0a = p->h[0][0][c], h0b = p->h[0][1][c], h0c = p->h[0][2][c];
    const double h1a = p->h[1][0][c], h1b = p->h[1][1][c], h1c = p->h[1][2][c];
    const double h2a = p->h[2][0][c], h2b = p->h[2][1][c], h2c = p->h[2][2][c];
    const double ta = p->t[0][c], tb = p->t[1][c], tc = p->t[2][c], td = p->t[3][c];
    for (int k = 0; k < NS; k++) {
      double a2 = w[0][k] * h2a + w[1][k] * h2b + w[2][k] * h2c;
      b->a2[c][k] = a2;
      b->d0[c][k] = w[0][k] * h0a + w[1][k] * h0b + w[2][k] * h0c - a2;
      b->d1[c][k] = w[0][k] * h1a + w[1][k] * h1b + w[2][k] * h1c - a2;
      b->t[c][k] = w[3][k] * ta + w[4][k] * tb + w[5][k] * tc + w[6][k] * td;
    }
  }
}

/* A level's base vectors: lo = h^2 a2 + h^3 t (s = 1), up = h^2 a2 - h^3 t. */
static void cell_bases(const cell_basis* restrict b, double h2, double h3, double (*restrict lo)[NS],
                       double (*restrict up)[NS]) {
  for (int c = 0; c < 3; c++)
    for (int k = 0; k < NS; k++) {
      lo[c][k] = h2 * b->a2[c][k] + h3 * b->t[c][k];
      up[c][k] = h2 * b->a2[c][k] - h3 * b->t[c][k];
    }
}

/* acc[k] = max(acc[k], |base_k + x0 d0_k + x1 d1_k|^2), x0 = h^2 u0, x1 = h^2 v0. */
static void cell_acc(const double (*restrict base)[NS], const cell_basis* restrict b, double x0, double x1,
                     double* restrict acc) {
  for (int k = 0; k < NS; k++) {
    double e0 = base[0][k] + x0 * b->d0[0][k] + x1 * b->d1[0][k];
    double e1 = base[1][k] + x0 * b->d0[1][k] + x1 * b->d1[1][k];
    double e2 = base[2][k] + x0 * b->d0[2][k] + x1 * b->d1[2][k];
    double l2 = e0 * e0 + e1 * e1 + e2 * e2;
    acc[k] = acc[k] > l2 ? acc[k] : l2;
  }
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
#define MID(W)                                                                                                         \
  { W(0.5, 0.0), W(0.0, 0.5), W(0.5, 0.5) }
static const double k_mid_w[7][3] = {MID(WQA), MID(WQB), MID(WQC), MID(WCA), MID(WCB), MID(WCC), MID(WCD)};

/* E_0 at the midpoints (1/2, 0), (0, 1/2), (1/2, 1/2): mid[point][component]. */
static double cubic_midpoints(const cubic* restrict p, d3 mid[3]) {
  double m2 = 0.0;
  for (int k = 0; k < 3; k++) {
    for (int c = 0; c < 3; c++)
      mid[k][c] = k_mid_w[0][k] * p->h[2][0][c] + k_mid_w[1][k] * p->h[2][1][c] + k_mid_w[2][k] * p->h[2][2][c] +
                  k_mid_w[3][k] * p->t[0][c] + k_mid_w[4][k] * p->t[1][c] + k_mid_w[5][k] * p->t[2][c] +
                  k_mid_w[6][k] * p->t[3][c];
    m2 = dmax(m2, d3_len2(mid[k]));
  }
  return m2;
}

/* A level-1 cell: cell_acc into acc1, and E_1 + the interpolant of the
 * corner values c0 (at y0), c1, c2 (the cell's m1, m2 corners) into acc0. */
static void cell_acc01(const double (*restrict base)[NS], const cell_basis* restrict b, double x0, double x1,
                       const double* c0, const double* c1, const double* c2, double* restrict acc1,
                       double* restrict acc0) {
  const double *B0 = k_cell_b[0], *B1 = k_cell_b[1], *B2 = k_cell_b[2];
  for (int k = 0; k < NS; k++) {
    double e0 = base[0][k] + x0 * b->d0[0][k] + x1 * b->d1[0][k];
    double e1 = base[1][k] + x0 * b->d0[1][k] + x1 * b->d1[1][k];
    double e2 = base[2][k] + x0 * b->d0[2][k] + x1 * b->d1[2][k];
    double f0 = e0 + B0[k] * c0[0] + B1[k] * c1[0] + B2[k] * c2[0];
    double f1 = e1 + B0[k] * c0[1] + B1[k] * c1[1] + B2[k] * c2[1];
    double f2 = e2 + B0[k] * c0[2] + B1[k] * c1[2] + B2[k] * c2[2];
    double l1 = e0 * e0 + e1 * e1 + e2 * e2, l0 = f0 * f0 + f1 * f1 + f2 * f2;
    acc1[k] = acc1[k] > l1 ? acc1[k] : l1;
    acc0[k] = acc0[k] > l0 ? acc0[k] : l0;
  }
}

static double acc_max(const double* acc, double m2) {
  for (int k = 0; k < NS; k++)
    m2 = dmax(m2, acc[k]);
  return m2;
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
    static const double zero[3] = {0.0, 0.0, 0.0};
    const double h2 = 0.25, h3 = 0.125, g = h2 * 0.5, hs0 = 1.0 / CELL0_N, hs1 = 0.5 / CELL_N;
    d3 mid[3]; /* E_0 at (1/2,0), (0,1/2), (1/2,1/2) */
    double m0 = cubic_midpoints(&p, mid), lo[3][NS], up[3][NS], acc1[NS] = {0}, acc0[NS] = {0};
    cell_bases(&b, h2, h3, lo, up);
    cell_acc01(lo, &b, 0.0, 0.0, zero, mid[0], mid[1], acc1, acc0);
    cell_acc01(lo, &b, g, 0.0, mid[0], zero, mid[2], acc1, acc0);
    cell_acc01(lo, &b, 0.0, g, mid[1], mid[2], zero, acc1, acc0);
    /* upper: y0 - h m, its m1 corner (0, 1/2), its m2 corner (1/2, 0) */
    cell_acc01(up, &b, h3, h3, mid[2], mid[1], mid[0], acc1, acc0);
    e[0] = dmin(sqrt(acc_max(acc0, m0)) + hs0 * hs0 * qbar + hs0 * hs0 * hs0 * cbar, qbar + cbar);
    e[1] = dmin(sqrt(acc_max(acc1, 0.0)) + hs1 * hs1 * qbar + hs1 * hs1 * hs1 * cbar, h2 * qbar + h3 * cbar);
  }
  for (int l = 2; l <= K; l++) {
    double h = 1.0 / (double)(1 << l), hs = h / CELL_N, h2 = h * h, h3 = h2 * h;
    double lo[3][NS], up[3][NS], acc[NS] = {0}; /* h^2 a2 + h^3 t, h^2 a2 - h^3 t */
    cell_bases(&b, h2, h3, lo, up);
    /* Hull cells: lower at the three corners (y0 = (0,0), (1-h,0), (0,1-h)),
     * upper next to them ((h,h), (1-h,h), (h,1-h)). */
    double g = h2 * (1.0 - h);
    cell_acc(lo, &b, 0.0, 0.0, acc);
    cell_acc(lo, &b, g, 0.0, acc);
    cell_acc(lo, &b, 0.0, g, acc);
    cell_acc(up, &b, h3, h3, acc);
    cell_acc(up, &b, g, h3, acc);
    cell_acc(up, &b, h3, g, acc);
    double m2 = 0.0;
    for (int k = 0; k < NS; k++)
      m2 = dmax(m2, acc[k]);
    double sampled = sqrt(m2) + hs * hs * qbar + hs * hs * hs * cbar;
    e[l] = dmin(sampled, h2 * qbar + h3 * cbar);
  }
  /* l > K: h^2 Qbar + h^3 Cbar <= 4^-l (Qbar + 2^-(K+1) Cbar). */
  finish(info, e, qbar + cbar / (double)(1 << (K + 1)), eval_slack(c, extra, extra_n));
}

/* ------------------------------------------------------------------------ */
/* Quadratic triangles, quads                                               */
/* ------------------------------------------------------------------------ */

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
  double e0 = quad_shape_max(A, B, C), e[K + 1];
  for (int l = 0; l <= K; l++)
    e[l] = e0 * k_pow4[l];
  finish(info, e, e0, eval_slack(c, NULL, 0));
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

/* All cells of levels 0..K on the shared (QUAD_G + 1)^2 grid; between grid
 * points (sub-triangles with legs 1/G, R^2 = 1/(2 G^2)) at most M/(4 G^2). */
static void phong_quad_table(const double (*net)[4][3], const _tlod_corners* c, tlod_patch_info* info) {
  enum { G = QUAD_G, S = G + 1 };
  d3 a[4][4];
  quad_power(net, a);
  d3 f[S][S];
  for (int i = 0; i < S; i++) {
    double u = (double)i / G;
    d3 col[4];
    for (int q = 0; q < 4; q++)
      for (int k = 0; k < 3; k++)
        col[q][k] = ((a[3][q][k] * u + a[2][q][k]) * u + a[1][q][k]) * u + a[0][q][k];
    for (int j = 0; j < S; j++) {
      double v = (double)j / G;
      for (int k = 0; k < 3; k++)
        f[i][j][k] = ((col[3][k] * v + col[2][k]) * v + col[1][k]) * v + col[0][k];
    }
  }
  double m = _tlod_quad_net_m(net), e[K + 1];
  for (int l = 0; l <= K; l++) {
    int step = G >> l, cells = 1 << l;
    double inv = 1.0 / step, worst = 0.0;
    for (int ca = 0; ca < cells; ca++) {
      for (int cb = 0; cb < cells; cb++) {
        int i0 = ca * step, j0 = cb * step;
        const double *f00 = f[i0][j0], *f10 = f[i0 + step][j0], *f11 = f[i0 + step][j0 + step];
        const double* f01 = f[i0][j0 + step];
        double du1[3], dv1[3], du2[3], dv2[3]; /* the two triangles' gradients */
        for (int k = 0; k < 3; k++)
          du1[k] = f10[k] - f00[k], dv1[k] = f11[k] - f10[k], du2[k] = f11[k] - f01[k], dv2[k] = f01[k] - f00[k];
        for (int i = 0; i <= step; i++) {
          for (int j = 0; j <= step; j++) {
            double si = i * inv, tj = j * inv, d[3];
            const double *gu = j <= i ? du1 : du2, *gv = j <= i ? dv1 : dv2;
            for (int k = 0; k < 3; k++)
              d[k] = f[i0 + i][j0 + j][k] - (f00[k] + si * gu[k] + tj * gv[k]);
            worst = dmax(worst, d3_len2(d));
          }
        }
      }
    }
    double sampled = sqrt(worst) + m / (4.0 * G * G);
    e[l] = dmin(sampled, m / 4.0 * k_pow4[l]);
  }
  finish(info, e, m / 4.0, eval_slack(c, NULL, 0));
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

void _tlod_error_table(tlod_surface_type type, const _tlod_corners* c, const double (*net)[3],
                       const double (*quad_net)[4][3], tlod_patch_info* info) {
  static const double zero[K + 1] = {0};
  if (c->n == 4) {
    if (quad_net)
      phong_quad_table(quad_net, c, info);
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
