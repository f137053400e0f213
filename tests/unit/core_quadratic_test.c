/*
 * core_quadratic_test.c -- second-order faces (issue 14): TLOD_SURFACE_QUADRATIC
 * and tlod_mesh_desc.face_nodes through the public API, against shape
 * functions coded here independently of core:
 *   - the boundary of a 27-node hex (triquadratic Lagrange) and of a 20-node
 *     hex (serendipity) evaluated by the 3D element's shape functions on the
 *     face, at every grid point of levels 0..6: within float rounding, corners
 *     bitwise, shared edges bitwise, the 6 curved faces closed (also through
 *     the scheduler and the CPU tessellator at mixed levels);
 *   - a 6-node triangle pair (a 10-node tet's faces), tangents and the TRUE
 *     normal against finite differences of the shape functions;
 *   - node sharing onto a linear neighbour, the smooth flag of an edge whose
 *     sides carry different node positions;
 *   - a linear mesh under QUADRATIC within float rounding of PHONG;
 *   - the error tables >= the dense true deviation, and their tightness;
 *   - hostile nodes refused naming face and node; refresh after
 *     tlod_mesh_update; tlod_mesh_update_attribute;
 *   - computed corner normals of curved faces (6 quads around a cylinder)
 *     against the shape functions' Q_u x Q_v, with creases and after an
 *     update.
 */
#include <float.h>
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "tesslod/core.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"

#define MAX_LEVEL 6
/* The dense error-table check up to level 6 costs 20 s under ASan (1 s in
 * release): there it stops at level 4, which still runs every table entry
 * and the tail. */
#if defined(__SANITIZE_ADDRESS__)
#define TABLE_MAX_LEVEL 4
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TABLE_MAX_LEVEL 4
#endif
#endif
#ifndef TABLE_MAX_LEVEL
#define TABLE_MAX_LEVEL MAX_LEVEL
#endif
#define ULP 0x1p-24

/* ------------------------------------------------------------------------ */
/* The hex element: nodes (a, b, c) in {0, 1, 2}^3 at reference (a-1, b-1, c-1) */
/* ------------------------------------------------------------------------ */

typedef struct hex {
  float pos[27][3]; /* vertex 9a + 3b + c */
  bool serendipity; /* 20 nodes: no face or body centre */
} hex;

static uint32_t hex_id(int a, int b, int c) { return (uint32_t)(9 * a + 3 * b + c); }

/* A curved element: a smooth map of the reference cube, moved off the
 * origin, plus a per-node perturbation, so every face is a general
 * (bi)quadratic and nothing is symmetric by accident. */
static void hex_make(hex* h, bool serendipity, uint64_t seed) {
  shape_rng rng = {seed};
  h->serendipity = serendipity;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) {
        double x = a - 1, y = b - 1, z = c - 1;
        double p[3] = {x + 0.22 * y * y - 0.15 * z * x, y + 0.18 * x * z + 0.1 * x * x, z + 0.25 * x * x - 0.12 * y};
        for (int k = 0; k < 3; k++) {
          p[k] = 1.7 * p[k] + (k == 0 ? 4.0 : k == 1 ? -2.5 : 1.25);
          h->pos[hex_id(a, b, c)][k] = (float)(p[k] + shape_rng_range(&rng, -0.06, 0.06));
        }
      }
}

/* 1D quadratic Lagrange on {-1, 0, 1}. */
static double lag(int node, double x) {
  return node == 0 ? 0.5 * x * (x - 1.0) : node == 1 ? 1.0 - x * x : 0.5 * x * (x + 1.0);
}

/* Serendipity (20-node) shape function of node (a, b, c) with at most one 1. */
static double seren(int a, int b, int c, double x, double y, double z) {
  double xi = a - 1, yi = b - 1, zi = c - 1;
  if (a == 1) return 0.25 * (1 - x * x) * (1 + y * yi) * (1 + z * zi);
  if (b == 1) return 0.25 * (1 - y * y) * (1 + x * xi) * (1 + z * zi);
  if (c == 1) return 0.25 * (1 - z * z) * (1 + x * xi) * (1 + y * yi);
  return 0.125 * (1 + x * xi) * (1 + y * yi) * (1 + z * zi) * (x * xi + y * yi + z * zi - 2);
}

/* The element's map at reference point r, by its 27 or 20 shape functions. */
static void hex_eval(const hex* h, const double r[3], double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) {
        int mids = (a == 1) + (b == 1) + (c == 1);
        if (h->serendipity && mids > 1) continue;
        double n = h->serendipity ? seren(a, b, c, r[0], r[1], r[2]) : lag(a, r[0]) * lag(b, r[1]) * lag(c, r[2]);
        for (int k = 0; k < 3; k++)
          out[k] += n * h->pos[hex_id(a, b, c)][k];
      }
}

/* The six faces, outward and counter-clockwise: corners as (a, b, c) in {0, 2}. */
static const int k_faces[6][4][3] = {
    {{0, 0, 0}, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}}, {{0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}},
    {{0, 0, 0}, {0, 0, 2}, {0, 2, 2}, {0, 2, 0}}, {{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}},
    {{0, 0, 0}, {2, 0, 0}, {2, 0, 2}, {0, 0, 2}}, {{0, 2, 0}, {0, 2, 2}, {2, 2, 2}, {2, 2, 0}},
};

/* Reference point of face f at (u, v): bilinear in the corners (the face is a square there). */
static void face_ref(int f, double u, double v, double r[3]) {
  double w[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
  for (int k = 0; k < 3; k++) {
    r[k] = 0.0;
    for (int i = 0; i < 4; i++)
      r[k] += w[i] * (k_faces[f][i][k] - 1);
  }
}

static uint32_t face_corner(int f, int i) { return hex_id(k_faces[f][i][0], k_faces[f][i][1], k_faces[f][i][2]); }

/* Node of slot s: edge s between corners s, s+1; 4 the centre (27 nodes only). */
static uint32_t face_node(const hex* h, int f, int s) {
  int x[3] = {0, 0, 0};
  if (s == 4) {
    if (h->serendipity) return TLOD_NO_NODE;
    for (int i = 0; i < 4; i++)
      for (int k = 0; k < 3; k++)
        x[k] += k_faces[f][i][k];
    return hex_id(x[0] / 4, x[1] / 4, x[2] / 4);
  }
  for (int k = 0; k < 3; k++)
    x[k] = (k_faces[f][s][k] + k_faces[f][(s + 1) % 4][k]) / 2;
  return hex_id(x[0], x[1], x[2]);
}

typedef struct hex_mesh {
  tlod_context* ctx;
  hex h;
  uint32_t indices[24], nodes[30];
  tlod_mesh* mesh;
  tlod_surface* surf;
} hex_mesh;

static void hex_mesh_free(hex_mesh* m) {
  tlod_surface_destroy(m->surf);
  tlod_mesh_destroy(m->mesh);
  tlod_context_destroy(m->ctx);
}

static tlod_mesh_desc hex_desc(hex_mesh* m) {
  for (int f = 0; f < 6; f++) {
    for (int i = 0; i < 4; i++)
      m->indices[4 * f + i] = face_corner(f, i);
    for (int s = 0; s < 5; s++)
      m->nodes[5 * f + s] = face_node(&m->h, f, s);
  }
  return (tlod_mesh_desc){.positions = &m->h.pos[0][0],
                          .vertex_count = 27,
                          .indices = m->indices,
                          .index_count = 24,
                          .face_type = TLOD_FACE_QUADS,
                          .face_nodes = m->nodes,
                          .label = m->h.serendipity ? "hex20" : "hex27"};
}

static bool hex_mesh_make(hex_mesh* m, bool serendipity, uint64_t seed, tlod_surface_desc sd) {
  memset(m, 0, sizeof *m);
  hex_make(&m->h, serendipity, seed);
  m->ctx = new_context(1, NULL, NULL);
  tlod_mesh_desc d = hex_desc(m);
  sd.type = TLOD_SURFACE_QUADRATIC;
  tlod_result r = m->ctx ? tlod_mesh_create(m->ctx, &d, &m->mesh) : TLOD_ERROR_OUT_OF_MEMORY;
  if (r == TLOD_SUCCESS) r = tlod_surface_create(m->ctx, m->mesh, &sd, &m->surf);
  if (r != TLOD_SUCCESS) fprintf(stderr, "hex mesh: %s: %s\n", tlod_result_string(r), tlod_context_last_error(m->ctx));
  return r == TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Grid helpers                                                             */
/* ------------------------------------------------------------------------ */

/* All grid points of a patch at level l: quads (2^l + 1)^2, triangles i + j <= 2^l. */
static uint32_t grid_points(uint32_t corners, uint32_t l, uint16_t (*ij)[2]) {
  uint32_t n = 1u << l, count = 0;
  for (uint32_t i = 0; i <= n; i++)
    for (uint32_t j = 0; j <= (corners == 4 ? n : n - i); j++)
      ij[count][0] = (uint16_t)i, ij[count][1] = (uint16_t)j, count++;
  return count;
}

#define GRID_MAX ((64 + 1) * (64 + 1))
static uint16_t g_ij[GRID_MAX][2];
static float g_pos[GRID_MAX][3], g_nrm[GRID_MAX][3];

static double dist3(const double a[3], const float b[3]) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Largest |p - q| over the mesh's positions: the extent tolerances scale with. */
static double mesh_extent(const tlod_mesh* m) {
  tlod_mesh_info i = tlod_mesh_query_info(m);
  double d[3] = {i.bbox_max[0] - i.bbox_min[0], i.bbox_max[1] - i.bbox_min[1], i.bbox_max[2] - i.bbox_min[2]};
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + fmax(fabs(i.bbox_max[0]), fabs(i.bbox_min[0]));
}

/* Point k of edge e of patch f on the level-MAX_LEVEL grid (k = the end corner's weight times 2^l). */
static void edge_ij(uint32_t corners, uint32_t e, uint32_t k, uint16_t ij[2]) {
  uint32_t n = 1u << MAX_LEVEL;
  uint32_t tri[3][2] = {{n - k, k}, {0, n - k}, {k, 0}};
  uint32_t quad[4][2] = {{k, 0}, {n, k}, {n - k, n}, {0, n - k}};
  ij[0] = (uint16_t)(corners == 3 ? tri[e][0] : quad[e][0]);
  ij[1] = (uint16_t)(corners == 3 ? tri[e][1] : quad[e][1]);
}

/* Every linked edge's points from both sides, bitwise; returns the mismatches. */
static uint32_t edge_mismatches(const tlod_surface* s) {
  const tlod_mesh* m = tlod_surface_mesh(s);
  uint32_t bad = 0, n = 1u << MAX_LEVEL;
  for (uint32_t f = 0; f < tlod_mesh_face_count(m); f++) {
    uint32_t corners = tlod_mesh_face_corners(m, f, NULL);
    for (uint32_t e = 0; e < corners; e++) {
      tlod_edge_link l = tlod_mesh_edge_link(m, f, e);
      if (l.face == UINT32_MAX) continue;
      uint32_t gc = tlod_mesh_face_corners(m, l.face, NULL);
      for (uint32_t k = 0; k <= n; k++) {
        uint16_t a[2], b[2];
        float pa[3], pb[3];
        edge_ij(corners, e, k, a), edge_ij(gc, l.edge, n - k, b);
        tlod_surface_eval_grid(s, f, MAX_LEVEL, a, 0, 1, pa, NULL);
        tlod_surface_eval_grid(s, l.face, MAX_LEVEL, b, 0, 1, pb, NULL);
        bad += memcmp(pa, pb, sizeof pa) != 0;
      }
    }
  }
  return bad;
}

/* ------------------------------------------------------------------------ */
/* Hex faces: exact at every level, corners and shared edges bitwise        */
/* ------------------------------------------------------------------------ */

/* Largest |surface - shape functions| over every grid point of levels 0..6, in units of extent * 2^-24. */
static double hex_face_error(const hex_mesh* m, uint32_t* corner_mismatches) {
  double worst = 0.0, extent = mesh_extent(m->mesh);
  for (uint32_t l = 0; l <= MAX_LEVEL; l++) {
    uint32_t count = grid_points(4, l, g_ij), n = 1u << l;
    for (int f = 0; f < 6; f++) {
      if (tlod_surface_eval_grid(m->surf, (uint32_t)f, l, &g_ij[0][0], sizeof g_ij[0], count, &g_pos[0][0],
                                 &g_nrm[0][0]) != TLOD_SUCCESS)
        return INFINITY;
      for (uint32_t k = 0; k < count; k++) {
        double r[3], want[3];
        face_ref(f, (double)g_ij[k][0] / n, (double)g_ij[k][1] / n, r);
        hex_eval(&m->h, r, want);
        worst = fmax(worst, dist3(want, g_pos[k]) / (extent * ULP));
        bool corner = (g_ij[k][0] == 0 || g_ij[k][0] == n) && (g_ij[k][1] == 0 || g_ij[k][1] == n);
        if (!corner) continue;
        int c = g_ij[k][0] == 0 ? (g_ij[k][1] == 0 ? 0 : 3) : (g_ij[k][1] == 0 ? 1 : 2);
        *corner_mismatches += memcmp(g_pos[k], m->h.pos[face_corner(f, c)], sizeof g_pos[k]) != 0;
      }
    }
  }
  return worst;
}

static void check_hex(bool serendipity) {
  hex_mesh m;
  bool made = hex_mesh_make(&m, serendipity, serendipity ? 20 : 27, (tlod_surface_desc){0});
  if (!made) hex_mesh_free(&m);
  CHECK(made);
  tlod_mesh_info info = tlod_mesh_query_info(m.mesh);
  uint32_t corner_bad = 0;
  double err = hex_face_error(&m, &corner_bad);
  uint32_t edge_bad = edge_mismatches(m.surf);
  printf("  %s: max |surface - shape functions| = %.2f ulps of the extent (levels 0..%d), %u corner and %u edge "
         "mismatches\n",
         serendipity ? "hex20" : "hex27", err, MAX_LEVEL, corner_bad, edge_bad);
  bool closed = info.closed && info.curved_faces == 6 && info.nodes_shared == 0 && info.crease_edges == 0;
  /* Node-only vertices are neither unused nor given computed normals: the
   * body centre (and the 20-node hex's face centres) are unused. */
  uint32_t unused = serendipity ? 7 : 1, node_only = serendipity ? 12 : 18;
  bool counts = info.unused_vertices == unused && info.normals_computed == 27 - node_only;
  hex_mesh_free(&m);
  CHECK_MSG(err <= 16.0, "%.2f ulps", err);
  CHECK(corner_bad == 0 && edge_bad == 0);
  CHECK_MSG(closed, "closed %d curved %u shared %u creases %u", info.closed, info.curved_faces, info.nodes_shared,
            info.crease_edges);
  CHECK_MSG(counts, "unused %u (want %u), normals computed %u (want %u)", info.unused_vertices, unused,
            info.normals_computed, 27 - node_only);
}

TEST(test_hex27_faces_exact) { check_hex(false); }
TEST(test_hex20_faces_exact) { check_hex(true); }

/* The records carry the resolved nodes: given ones bitwise, the 20-node
 * centre by the serendipity rule. */
TEST(test_hex_records) {
  hex_mesh m;
  bool made = hex_mesh_make(&m, true, 5, (tlod_surface_desc){0});
  tlod_patch_record rec[6];
  if (made) made = tlod_surface_patch_records(m.surf, 0, 6, rec) == TLOD_SUCCESS;
  uint32_t bad = 0;
  double centre_err = 0.0;
  for (int f = 0; made && f < 6; f++) {
    bad += rec[f].info[0] != 4 || rec[f].info[1] != 1;
    for (int e = 0; e < 4; e++)
      bad += memcmp(rec[f].pn_control[e], m.h.pos[face_node(&m.h, f, e)], 12) != 0 || rec[f].pn_control[e][3] != 0;
    double r[3], want[3];
    face_ref(f, 0.5, 0.5, r);
    hex_eval(&m.h, r, want);
    /* The biquadratic's value at the centre is its centre node. */
    centre_err = fmax(centre_err, dist3(want, rec[f].pn_control[4]));
  }
  double extent = made ? mesh_extent(m.mesh) : 0.0;
  hex_mesh_free(&m);
  CHECK(made);
  CHECK(bad == 0);
  CHECK_MSG(centre_err <= 8.0 * ULP * extent, "serendipity centre off by %g", centre_err);
}

/* tlod_mesh_update moves an edge node: the two faces sharing it are
 * recomputed and follow the shape functions of the moved element. The
 * computed normals at the edge's two corners follow the curved edge, so the
 * two other faces at those corners are rebuilt too: 4 patches. */
TEST(test_hex_refresh) {
  hex_mesh m;
  bool made = hex_mesh_make(&m, false, 9, (tlod_surface_desc){0});
  uint32_t updated = 0, corner_bad = 0;
  double err = INFINITY;
  if (made) {
    uint32_t v = face_node(&m.h, 1, 0); /* top face, edge 0: shared with face 4 */
    m.h.pos[v][2] += 0.4f, m.h.pos[v][0] -= 0.1f;
    m.h.pos[hex_id(1, 1, 2)][2] -= 0.3f; /* top face's centre */
    made = tlod_mesh_update(m.mesh, &m.h.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS &&
           tlod_surface_refresh(m.surf, &updated) == TLOD_SUCCESS;
    err = hex_face_error(&m, &corner_bad);
  }
  hex_mesh_free(&m);
  CHECK(made);
  CHECK_MSG(updated == 4, "%u patches refreshed (want 4)", updated);
  CHECK_MSG(err <= 16.0 && corner_bad == 0, "%.2f ulps after the update", err);
}

/* The scheduler and the CPU tessellator take the new type unchanged: random
 * per-patch levels and a camera's draw list give closed output. */
TEST(test_hex_cpu_closed) {
  hex_mesh m;
  bool made = hex_mesh_make(&m, false, 3, (tlod_surface_desc){0});
  tlod_patterns* pat = NULL;
  if (made) made = tlod_patterns_create(m.ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &pat) == TLOD_SUCCESS;
  uint32_t open = 0, runs = 0;
  char why[256] = "";
  shape_rng rng = {77};
  for (int run = 0; made && run < 24; run++) {
    int8_t levels[6];
    for (int f = 0; f < 6; f++)
      levels[f] = (int8_t)(shape_rng_next(&rng) % (MAX_LEVEL + 1));
    tlod_cpu_mesh* out = NULL;
    tlod_cpu_tessellate_desc d = {.levels = levels, .no_weld = true};
    if (tlod_cpu_tessellate(m.ctx, m.surf, pat, &d, &out) != TLOD_SUCCESS) {
      made = false;
      break;
    }
    open += !shape_closed_manifold(out->positions, out->vertex_count, out->indices, out->triangle_count,
                                   out->triangle_patch, why, sizeof why);
    runs++;
    tlod_cpu_mesh_destroy(m.ctx, out);
  }
  tlod_scheduler* sched = NULL;
  if (made) made = tlod_scheduler_create(m.ctx, m.surf, pat, &(tlod_scheduler_desc){0}, &sched) == TLOD_SUCCESS;
  if (made) {
    camera cam = {{9.0, 3.0, 6.0}, {4.0, -2.5, 1.25}, {0, 0, 1}, 0.8, 0, 1.0, 0.1, 100.0, false, 800, 800};
    tlod_view_desc view = make_view(&cam);
    tlod_frame_desc fr = {.views = &view, .view_count = 1, .dt_ms = 16.0f};
    tlod_cpu_mesh* out = NULL;
    made = tlod_scheduler_update(sched, &fr) == TLOD_SUCCESS;
    tlod_cpu_tessellate_desc d = {.draw_list = made ? tlod_scheduler_draw_list(sched, 0) : NULL, .no_weld = true};
    made = made && tlod_cpu_tessellate(m.ctx, m.surf, pat, &d, &out) == TLOD_SUCCESS;
    if (made)
      open += !shape_closed_manifold(out->positions, out->vertex_count, out->indices, out->triangle_count,
                                     out->triangle_patch, why, sizeof why);
    tlod_cpu_mesh_destroy(m.ctx, out);
  }
  if (!made) fprintf(stderr, "  %s\n", tlod_context_last_error(m.ctx));
  tlod_scheduler_destroy(sched);
  tlod_patterns_destroy(pat);
  hex_mesh_free(&m);
  CHECK(made && runs == 24);
  CHECK_MSG(open == 0, "%u tessellations not closed: %s", open, why);
}

/* ------------------------------------------------------------------------ */
/* 6-node triangles (a 10-node tet's faces), tangents, TRUE normal          */
/* ------------------------------------------------------------------------ */

/* Two triangles 0-1-2 and 0-2-3 sharing edge 0-2 (node 6), nodes 4, 5 | 7, 8. */
static const float k_tri_pos[9][3] = {{0, 0, 0},     {2, 0, 0.3f},        {2, 2, 0},
                                      {0, 2, -0.2f}, {1, -0.2f, 0.5f},    {2.3f, 1, 0.1f},
                                      {1, 1, 0.6f},  {0.9f, 2.25f, 0.2f}, {-0.3f, 1, 0.35f}};
static const uint32_t k_tri_idx[6] = {0, 1, 2, 0, 2, 3};
static const uint32_t k_tri_nodes[10] = {4, 5, 6, 4321, 99, 6, 7, 8, TLOD_NO_NODE, TLOD_NO_NODE};

static void tri_shape(int f, double u, double v, double out[3]) {
  const uint32_t* c = k_tri_idx + 3 * f;
  const uint32_t* nd = k_tri_nodes + 5 * f;
  double l[3] = {u, v, 1.0 - u - v};
  double w[6] = {l[0] * (2 * l[0] - 1), l[1] * (2 * l[1] - 1), l[2] * (2 * l[2] - 1),
                 4 * l[0] * l[1],       4 * l[1] * l[2],       4 * l[2] * l[0]};
  uint32_t id[6] = {c[0], c[1], c[2], nd[0], nd[1], nd[2]};
  for (int k = 0; k < 3; k++) {
    out[k] = 0.0;
    for (int i = 0; i < 6; i++)
      out[k] += w[i] * k_tri_pos[id[i]][k];
  }
}

static tlod_mesh* tri_mesh(tlod_context* ctx) {
  tlod_mesh_desc d = {.positions = &k_tri_pos[0][0],
                      .vertex_count = 9,
                      .indices = k_tri_idx,
                      .index_count = 6,
                      .face_nodes = k_tri_nodes, /* the unused slots 3 and 4 of triangles are ignored */
                      .label = "tet10 faces"};
  tlod_mesh* m = NULL;
  return tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS ? m : NULL;
}

TEST(test_triangles_exact) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* mesh = tri_mesh(ctx);
  tlod_surface* s = NULL;
  if (mesh) tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &s);
  double worst = 0.0;
  uint32_t edge_bad = s ? edge_mismatches(s) : 1;
  for (uint32_t l = 0; s && l <= MAX_LEVEL; l++) {
    uint32_t count = grid_points(3, l, g_ij), n = 1u << l;
    for (uint32_t f = 0; f < 2; f++) {
      tlod_surface_eval_grid(s, f, l, &g_ij[0][0], sizeof g_ij[0], count, &g_pos[0][0], NULL);
      for (uint32_t k = 0; k < count; k++) {
        double want[3];
        tri_shape((int)f, (double)g_ij[k][0] / n, (double)g_ij[k][1] / n, want);
        worst = fmax(worst, dist3(want, g_pos[k]));
      }
    }
  }
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  tlod_edge_link link = tlod_mesh_edge_link(mesh, 0, 2);
  double extent = mesh ? mesh_extent(mesh) : 0.0;
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  CHECK(s != NULL);
  printf("  6-node triangles: max |surface - shape functions| = %.2f ulps of the extent\n", worst / (extent * ULP));
  CHECK_MSG(worst <= 16.0 * ULP * extent, "%g", worst);
  CHECK(edge_bad == 0);
  CHECK(info.curved_faces == 2 && info.nodes_shared == 0 && info.unused_vertices == 0);
  CHECK(link.face == 1 && link.edge == 0 && link.smooth);
}

/* Tangents dP/du, dP/dv and the TRUE normal against central differences of the shape functions. */
TEST(test_triangle_derivatives) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* mesh = tri_mesh(ctx);
  tlod_surface* s = NULL;
  tlod_surface_desc sd = {.type = TLOD_SURFACE_QUADRATIC, .shading_normal = TLOD_SHADING_NORMAL_TRUE};
  if (mesh) tlod_surface_create(ctx, mesh, &sd, &s);
  double worst_t = 0.0, worst_n = 0.0;
  const double h = 1e-5, at[4][2] = {{0.2, 0.3}, {0.6, 0.1}, {0.05, 0.9}, {0.33, 0.33}};
  for (int f = 0; s && f < 2; f++)
    for (int k = 0; k < 4; k++) {
      double u = at[k][0], v = at[k][1], a[3], b[3], c[3], d[3], tu[3], tv[3];
      tlod_surface_point pt;
      tlod_surface_eval(s, (uint32_t)f, (float)u, (float)v, &pt);
      tri_shape(f, u + h, v, a), tri_shape(f, u - h, v, b), tri_shape(f, u, v + h, c), tri_shape(f, u, v - h, d);
      for (int x = 0; x < 3; x++)
        tu[x] = (a[x] - b[x]) / (2 * h), tv[x] = (c[x] - d[x]) / (2 * h);
      double n[3];
      cross3(tu, tv, n);
      double len = len3(n);
      for (int x = 0; x < 3; x++)
        n[x] /= len;
      worst_t = fmax(worst_t, fmax(dist3(tu, pt.tangent), dist3(tv, pt.bitangent)));
      worst_n = fmax(worst_n, dist3(n, pt.normal));
    }
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  CHECK(s != NULL);
  CHECK_MSG(worst_t <= 1e-4 && worst_n <= 1e-5, "tangent error %g, normal error %g", worst_t, worst_n);
}

/* ------------------------------------------------------------------------ */
/* Node sharing and the smooth flag                                         */
/* ------------------------------------------------------------------------ */

/* Quad A (0 1 2 3, 9 nodes) and linear quad B (1 4 5 2) share edge 1-2 (A's
 * edge 1, B's edge 3); vertex 6 is A's node there, vertex 13 a copy of it. */
static float g_pair_pos[14][3] = {{0, 0, 0},           {1, 0, 0.1f},        {1, 1, -0.1f},      {0, 1, 0},
                                  {2, 0, 0},           {2, 1, 0.05f},       {1.2f, 0.5f, 0.3f}, {0.5f, -0.1f, 0.2f},
                                  {0.5f, 1.1f, 0.15f}, {-0.1f, 0.5f, 0.1f}, {0.5f, 0.5f, 0.4f}, {9, 9, 9},
                                  {9, 9, 9},           {1.2f, 0.5f, 0.3f}};
static const uint32_t k_pair_idx[8] = {0, 1, 2, 3, 1, 4, 5, 2};

static tlod_mesh* pair_mesh(tlod_context* ctx, uint32_t b_node) {
  static uint32_t nodes[10];
  const uint32_t a[5] = {7, 6, 8, 9, 10};
  memcpy(nodes, a, sizeof a);
  for (int s = 0; s < 5; s++)
    nodes[5 + s] = s == 3 ? b_node : TLOD_NO_NODE;
  tlod_mesh_desc d = {.positions = &g_pair_pos[0][0],
                      .vertex_count = 14,
                      .indices = k_pair_idx,
                      .index_count = 8,
                      .face_type = TLOD_FACE_QUADS,
                      .face_nodes = nodes,
                      .label = "pair"};
  tlod_mesh* m = NULL;
  if (tlod_mesh_create(ctx, &d, &m) != TLOD_SUCCESS) fprintf(stderr, "  %s\n", tlod_context_last_error(ctx));
  return m;
}

TEST(test_node_sharing) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* mesh = pair_mesh(ctx, TLOD_NO_NODE);
  tlod_surface* s = NULL;
  if (mesh) tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &s);
  tlod_patch_record rec[2] = {0};
  if (s) tlod_surface_patch_records(s, 0, 2, rec);
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  tlod_mesh_view view = tlod_mesh_query_view(mesh);
  tlod_edge_link link = tlod_mesh_edge_link(mesh, 1, 3);
  uint32_t edge_bad = s ? edge_mismatches(s) : 1;
  bool view_ok = view.face_nodes && view.face_nodes[1][3] == 6 && view.face_nodes[1][0] == TLOD_NO_NODE &&
                 view.face_nodes[0][4] == 10;
  /* B (no given node) takes A's node; its centre is the serendipity one of its resolved nodes. */
  double worst = 0.0;
  for (int k = 0; k < 3; k++) {
    double c = 0.0;
    for (int i = 0; i < 4; i++)
      c += 0.5 * rec[1].pn_control[i][k] - 0.25 * rec[1].corner[i][k];
    worst = fmax(worst, fabs(c - rec[1].pn_control[4][k]));
  }
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  CHECK(s != NULL);
  CHECK_MSG(info.curved_faces == 1 && info.nodes_shared == 1, "curved %u shared %u", info.curved_faces,
            info.nodes_shared);
  CHECK(view_ok);
  CHECK(rec[0].info[1] == 1 && rec[1].info[1] == 0);
  CHECK(memcmp(rec[1].pn_control[3], g_pair_pos[6], 12) == 0);
  CHECK_MSG(worst <= 1e-6, "%g", worst);
  CHECK(link.face == 0 && link.edge == 1 && link.smooth);
  CHECK(edge_bad == 0);
}

/* Both sides give a node: another vertex at the bitwise same position keeps
 * the edge smooth (and closed); a different position makes it a crease. */
TEST(test_node_smooth_flag) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* same = pair_mesh(ctx, 13);
  tlod_edge_link l_same = tlod_mesh_edge_link(same, 0, 1);
  tlod_mesh_info i_same = tlod_mesh_query_info(same);
  tlod_mesh_destroy(same);
  g_pair_pos[13][2] += 0.25f;
  tlod_mesh* moved = pair_mesh(ctx, 13);
  tlod_edge_link l_moved = tlod_mesh_edge_link(moved, 0, 1);
  tlod_mesh_info i_moved = tlod_mesh_query_info(moved);
  /* an update moving the node back makes the edge smooth again */
  g_pair_pos[13][2] -= 0.25f;
  tlod_result r = tlod_mesh_update(moved, &g_pair_pos[0][0], 0, NULL, 0);
  tlod_edge_link l_back = tlod_mesh_edge_link(moved, 0, 1);
  tlod_mesh_info i_back = tlod_mesh_query_info(moved);
  tlod_mesh_destroy(moved);
  tlod_context_destroy(ctx);
  CHECK(l_same.face == 1 && l_same.smooth && i_same.crease_edges == 0 && i_same.nodes_shared == 0);
  CHECK(l_moved.face == 1 && !l_moved.smooth && i_moved.crease_edges == 1);
  CHECK(r == TLOD_SUCCESS && l_back.smooth && i_back.crease_edges == 0);
}

/* ------------------------------------------------------------------------ */
/* A linear mesh under QUADRATIC is its Phong surface                       */
/* ------------------------------------------------------------------------ */

static double compare_phong(tlod_context* ctx, shape sh, double* normal_err) {
  tlod_mesh_desc md = shape_mesh_desc(&sh);
  tlod_mesh* mesh = NULL;
  tlod_surface *q = NULL, *p = NULL;
  double worst = INFINITY;
  *normal_err = INFINITY;
  if (tlod_mesh_create(ctx, &md, &mesh) == TLOD_SUCCESS &&
      tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &q) == TLOD_SUCCESS &&
      tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &p) == TLOD_SUCCESS) {
    worst = *normal_err = 0.0;
    static float pp[GRID_MAX][3], pn[GRID_MAX][3];
    for (uint32_t f = 0; f < tlod_mesh_face_count(mesh); f++) {
      uint32_t corners = tlod_mesh_face_corners(mesh, f, NULL), count = grid_points(corners, 4, g_ij);
      tlod_surface_eval_grid(q, f, 4, &g_ij[0][0], sizeof g_ij[0], count, &g_pos[0][0], &g_nrm[0][0]);
      tlod_surface_eval_grid(p, f, 4, &g_ij[0][0], sizeof g_ij[0], count, &pp[0][0], &pn[0][0]);
      for (uint32_t k = 0; k < count; k++)
        for (int x = 0; x < 3; x++) {
          worst = fmax(worst, fabs((double)g_pos[k][x] - pp[k][x]));
          *normal_err = fmax(*normal_err, fabs((double)g_nrm[k][x] - pn[k][x]));
        }
    }
  }
  tlod_surface_destroy(q);
  tlod_surface_destroy(p);
  tlod_mesh_destroy(mesh);
  shape_free(&sh);
  return worst;
}

TEST(test_linear_is_phong) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  double nq, nt, dq = compare_phong(ctx, shape_quad_sphere(3), &nq), dt = compare_phong(ctx, shape_icosphere(2), &nt);
  tlod_context_destroy(ctx);
  printf("  linear meshes: |QUADRATIC - PHONG| <= %.3g (quads), %.3g (triangles) on unit spheres; normals %.3g, %.3g\n",
         dq, dt, nq, nt);
  CHECK_MSG(dq <= 16 * ULP && dt <= 16 * ULP, "quads %g triangles %g", dq, dt);
  CHECK_MSG(nq <= 4 * ULP && nt <= 4 * ULP, "normals: quads %g triangles %g", nq, nt);
}

/* ------------------------------------------------------------------------ */
/* Error tables against the dense true deviation                           */
/* ------------------------------------------------------------------------ */

static void eval_d(const tlod_surface* s, uint32_t f, double u, double v, double out[3]) {
  tlod_surface_point pt;
  tlod_surface_eval(s, f, (float)u, (float)v, &pt);
  for (int c = 0; c < 3; c++)
    out[c] = pt.position[c];
}

/* max |S - linear interpolant| over a (u, v) triangle, on d segments; also the farthest point from centre. */
static double tri_dev(const tlod_surface* s, uint32_t f, const double c[3][2], int d, const float centre[3],
                      double* far) {
  double p[3][3], worst = 0;
  for (int x = 0; x < 3; x++)
    eval_d(s, f, c[x][0], c[x][1], p[x]);
  for (int i = 0; i <= d; i++)
    for (int j = 0; i + j <= d; j++) {
      double b1 = (double)i / d, b2 = (double)j / d, b0 = 1.0 - b1 - b2, q[3], e2 = 0;
      eval_d(s, f, b0 * c[0][0] + b1 * c[1][0] + b2 * c[2][0], b0 * c[0][1] + b1 * c[1][1] + b2 * c[2][1], q);
      for (int k = 0; k < 3; k++) {
        double e = q[k] - (b0 * p[0][k] + b1 * p[1][k] + b2 * p[2][k]);
        e2 += e * e;
      }
      worst = fmax(worst, sqrt(e2));
      float qf[3] = {(float)q[0], (float)q[1], (float)q[2]};
      double cd[3] = {centre[0], centre[1], centre[2]};
      *far = fmax(*far, dist3(cd, qf));
    }
  return worst;
}

/* The level-l pattern's triangles (quads: diagonal (a,b)-(a+1,b+1), lod/src/pattern_refine.c). */
static double dense_dev(const tlod_surface* s, uint32_t f, uint32_t corners, uint32_t level, const float centre[3],
                        double* far) {
  int n = 1 << level, d = level <= 2 ? 16 : level == 3 ? 8 : 4;
  double h = 1.0 / n, worst = 0;
  for (int b = 0; b < n; b++)
    for (int a = 0; a < (corners == 3 ? n - b : n); a++) {
      double A = a * h, B = b * h, A1 = (a + 1) * h, B1 = (b + 1) * h;
      if (corners == 3) {
        double lo[3][2] = {{A, B}, {A1, B}, {A, B1}}, up[3][2] = {{A1, B}, {A1, B1}, {A, B1}};
        worst = fmax(worst, tri_dev(s, f, lo, d, centre, far));
        if (a + b + 2 <= n) worst = fmax(worst, tri_dev(s, f, up, d, centre, far));
      } else {
        double t1[3][2] = {{A, B}, {A1, B}, {A1, B1}}, t2[3][2] = {{A, B}, {A1, B1}, {A, B1}};
        worst = fmax(worst, fmax(tri_dev(s, f, t1, d, centre, far), tri_dev(s, f, t2, d, centre, far)));
      }
    }
  return worst;
}

typedef struct table_stats {
  double ratio[512];
  uint32_t n, below, outside_sphere, closed_below;
  double worst_ratio;
} table_stats;

static void check_tables(const tlod_surface* s, const tlod_surface* closed, table_stats* st) {
  const tlod_mesh* m = tlod_surface_mesh(s);
  for (uint32_t f = 0; f < tlod_mesh_face_count(m); f++) {
    tlod_patch_info info = tlod_surface_patch(s, f), ci = tlod_surface_patch(closed, f);
    for (uint32_t l = 0; l <= TABLE_MAX_LEVEL; l++) {
      double far = 0.0, dense = dense_dev(s, f, info.corner_count, l, info.center, &far);
      double bound = tlod_patch_error_bound(&info, l), cb = tlod_patch_error_bound(&ci, l);
      st->below += bound < dense;
      st->closed_below += cb < bound;
      st->outside_sphere += far > info.radius;
      if (dense > 4.0 * info.error_slack && st->n < 512) {
        st->ratio[st->n++] = bound / dense;
        st->worst_ratio = fmax(st->worst_ratio, bound / dense);
      }
    }
  }
}

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* Curved triangles and quads: random nodes around random flat faces (half
 * the quads with a centre node, half 8-node). */
static void random_curved(tlod_context* ctx, uint32_t corners, table_stats* st) {
  enum { FACES = 6 };
  float pos[FACES * 9][3] = {{0}};
  uint32_t idx[FACES * 4], nodes[FACES * 5];
  shape_rng rng = {corners * 1000u + 7u};
  static const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tri[3][2] = {{0, 0}, {1, 0}, {0.3, 0.9}};
  for (uint32_t f = 0; f < FACES; f++) {
    float(*p)[3] = pos + f * 9;
    double centre[3] = {0, 0, 0};
    for (uint32_t i = 0; i < corners; i++) {
      const double* c = corners == 4 ? sq[i] : tri[i];
      p[i][0] = (float)(c[0] * 2 + 5 * f), p[i][1] = (float)(c[1] * 2 + shape_rng_range(&rng, -0.3, 0.3));
      p[i][2] = (float)shape_rng_range(&rng, -0.3, 0.3);
      idx[f * corners + i] = f * 9 + i;
      for (int k = 0; k < 3; k++)
        centre[k] += p[i][k] / corners;
    }
    for (uint32_t s = 0; s < 5; s++) {
      bool used = s < corners || (corners == 4 && s == 4 && f % 2 == 0);
      for (int k = 0; k < 3; k++) {
        double base = s < corners ? 0.5 * (p[s][k] + p[(s + 1) % corners][k]) : centre[k];
        p[4 + s][k] = (float)(base + shape_rng_range(&rng, -0.4, 0.4));
      }
      nodes[f * 5 + s] = used ? f * 9 + 4 + s : TLOD_NO_NODE;
    }
  }
  tlod_mesh_desc d = {.positions = &pos[0][0],
                      .vertex_count = FACES * 9,
                      .indices = idx,
                      .index_count = FACES * corners,
                      .face_type = corners == 4 ? TLOD_FACE_QUADS : TLOD_FACE_TRIANGLES,
                      .face_nodes = nodes};
  tlod_mesh* mesh = NULL;
  tlod_surface *s = NULL, *c = NULL;
  tlod_mesh_create(ctx, &d, &mesh);
  tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &s);
  tlod_surface_create(
      ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC, .error_tables = TLOD_ERROR_TABLES_CLOSED_FORM},
      &c);
  if (s && c)
    check_tables(s, c, st);
  else
    st->below++, fprintf(stderr, "  random %u-corner faces: %s\n", corners, tlod_context_last_error(ctx));
  tlod_surface_destroy(s);
  tlod_surface_destroy(c);
  tlod_mesh_destroy(mesh);
}

TEST(test_error_tables) {
  table_stats st = {0};
  for (int kind = 0; kind < 2; kind++) {
    hex_mesh m, mc;
    bool ok = hex_mesh_make(&m, kind == 1, 11, (tlod_surface_desc){0}) &&
              hex_mesh_make(&mc, kind == 1, 11, (tlod_surface_desc){.error_tables = TLOD_ERROR_TABLES_CLOSED_FORM});
    if (ok) check_tables(m.surf, mc.surf, &st);
    hex_mesh_free(&m);
    hex_mesh_free(&mc);
    CHECK(ok);
  }
  tlod_context* ctx = new_context(1, NULL, NULL);
  random_curved(ctx, 3, &st);
  random_curved(ctx, 4, &st);
  tlod_context_destroy(ctx);
  qsort(st.ratio, st.n, sizeof st.ratio[0], cmp_double);
  double median = st.n ? st.ratio[st.n / 2] : 0.0;
  printf("  error tables: bound / dense true deviation over %u (patch, level): min %.3f median %.3f max %.3f\n", st.n,
         st.n ? st.ratio[0] : 0.0, median, st.worst_ratio);
  CHECK_MSG(st.below == 0, "%u bounds below the dense deviation", st.below);
  CHECK_MSG(st.closed_below == 0, "%u closed-form entries below the measured ones", st.closed_below);
  CHECK_MSG(st.outside_sphere == 0, "%u samples outside the bounding sphere", st.outside_sphere);
  CHECK_MSG(st.n > 80 && median <= 1.5 && st.worst_ratio <= 2.0, "median %.3f worst %.3f", median, st.worst_ratio);
}

/* ------------------------------------------------------------------------ */
/* Hostile nodes                                                            */
/* ------------------------------------------------------------------------ */

static void expect_refused(tlod_context* ctx, uint32_t slot, uint32_t value, const char* want) {
  uint32_t nodes[10] = {4, 5, 6, TLOD_NO_NODE, TLOD_NO_NODE, TLOD_NO_NODE, 7, 8, TLOD_NO_NODE, TLOD_NO_NODE};
  nodes[slot] = value;
  tlod_mesh_desc d = {.positions = &k_tri_pos[0][0],
                      .vertex_count = 9,
                      .indices = k_tri_idx,
                      .index_count = 6,
                      .face_nodes = nodes,
                      .label = "hostile"};
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  const char* msg = tlod_context_last_error(ctx);
  tlod_mesh_destroy(m);
  CHECK_MSG(r == TLOD_ERROR_INVALID_MESH && m == NULL, "slot %u = %u: %s", slot, value, tlod_result_string(r));
  CHECK_MSG(strstr(msg, want) != NULL, "'%s' lacks '%s'", msg, want);
}

TEST(test_hostile_nodes) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CALL(expect_refused(ctx, 7, 9, "face 1: node 2: index 9 out of range (9 vertices)"));
  CALL(expect_refused(ctx, 1, UINT32_MAX - 1, "face 0: node 1: index 4294967294 out of range"));
  CALL(expect_refused(ctx, 5, 3, "face 1: node 0: vertex 3 is corner 2 of the face"));
  CALL(expect_refused(ctx, 2, 4, "face 0: node 2: vertex 4 is also node 0"));
  /* a node-only vertex with a NaN position is refused like any vertex */
  float pos[9][3];
  memcpy(pos, k_tri_pos, sizeof pos);
  pos[8][1] = NAN;
  tlod_mesh_desc d = {
      .positions = &pos[0][0], .vertex_count = 9, .indices = k_tri_idx, .index_count = 6, .face_nodes = k_tri_nodes};
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  bool named = strstr(tlod_context_last_error(ctx), "vertex 8") != NULL;
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  CHECK(r == TLOD_ERROR_INVALID_MESH && named);
}

/* Random node arrays (out of range, corners, repeats, far-away nodes at the
 * position limit) on a mixed mesh: refused with a message, or accepted with
 * finite points, tables and spheres everywhere. */
static bool finite_surface(const tlod_surface* s) {
  const tlod_mesh* m = tlod_surface_mesh(s);
  for (uint32_t f = 0; f < tlod_mesh_face_count(m); f++) {
    tlod_patch_info info = tlod_surface_patch(s, f);
    uint32_t count = grid_points(info.corner_count, 3, g_ij);
    tlod_patch_record rec;
    if (tlod_surface_eval_grid(s, f, 3, &g_ij[0][0], sizeof g_ij[0], count, &g_pos[0][0], &g_nrm[0][0]) ||
        tlod_surface_patch_records(s, f, 1, &rec))
      return false;
    bool ok = isfinite(info.radius) && isfinite(tlod_patch_error_bound(&info, 0)) && isfinite(info.error_tail);
    for (uint32_t k = 0; k < count; k++)
      for (int x = 0; x < 3; x++)
        ok = ok && isfinite(g_pos[k][x]) && isfinite(g_nrm[k][x]);
    if (!ok) return false;
  }
  return true;
}

TEST(test_random_nodes) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[12][3];
  shape_rng rng = {1234};
  const uint32_t idx[11] = {0, 1, 2, 3, 1, 4, 5, 2, 2, 5, 6};
  const uint8_t sizes[3] = {4, 4, 3};
  uint32_t accepted = 0, refused = 0, silent = 0, broken = 0;
  for (int run = 0; run < 300; run++) {
    for (int v = 0; v < 12; v++)
      for (int k = 0; k < 3; k++)
        pos[v][k] = (float)shape_rng_range(&rng, -1.0, 1.0) + (float)(v % 7);
    pos[11][run % 3] = run % 2 ? 1e18f : -1e18f; /* a node at the position limit */
    uint32_t nodes[15];
    for (int s = 0; s < 15; s++) {
      uint64_t r = shape_rng_next(&rng) % 16;
      nodes[s] = r < 9 ? TLOD_NO_NODE : r < 15 ? 7 + (uint32_t)(shape_rng_next(&rng) % 5) : 12u + (uint32_t)(run % 2);
    }
    tlod_mesh_desc d = {.positions = &pos[0][0],
                        .vertex_count = 12,
                        .indices = idx,
                        .index_count = 11,
                        .face_type = TLOD_FACE_MIXED,
                        .face_sizes = sizes,
                        .face_count = 3,
                        .face_nodes = nodes};
    tlod_mesh* m = NULL;
    tlod_surface* s = NULL;
    if (tlod_mesh_create(ctx, &d, &m) != TLOD_SUCCESS) {
      refused++;
      silent += tlod_context_last_error(ctx)[0] == 0;
      continue;
    }
    accepted++;
    tlod_surface_desc sd = {.type = TLOD_SURFACE_QUADRATIC, .shading_normal = TLOD_SHADING_NORMAL_TRUE};
    broken += tlod_surface_create(ctx, m, &sd, &s) != TLOD_SUCCESS || !finite_surface(s);
    tlod_surface_destroy(s);
    tlod_mesh_destroy(m);
  }
  tlod_context_destroy(ctx);
  printf("  random nodes: %u meshes accepted, %u refused\n", accepted, refused);
  CHECK(accepted > 20 && refused > 20);
  CHECK_MSG(silent == 0 && broken == 0, "%u refusals without a message, %u surfaces not finite", silent, broken);
}

/* Every allocation of a quadratic mesh and surface failing in turn: a clean
 * refusal each time, nothing leaked (frees == allocations). */
TEST(test_out_of_memory) {
  uint32_t failures = 0, leaks = 0, silent = 0;
  long calls = -1;
  for (long k = 0; calls < 0 || k < calls; k++) {
    counting_allocator ca = {.fail_at = -1};
    tlod_context* ctx = new_context(1, &ca, NULL);
    long before = ca.calls;
    ca.fail_at = calls < 0 ? -1 : before + k;
    hex_mesh m = {.ctx = ctx};
    hex_make(&m.h, k % 2 == 1, 4);
    tlod_mesh_desc d = hex_desc(&m);
    tlod_result r = tlod_mesh_create(ctx, &d, &m.mesh);
    if (r == TLOD_SUCCESS)
      r = tlod_surface_create(ctx, m.mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &m.surf);
    if (r != TLOD_SUCCESS) failures++, silent += r != TLOD_ERROR_OUT_OF_MEMORY;
    tlod_surface_destroy(m.surf);
    tlod_mesh_destroy(m.mesh);
    ca.fail_at = -1;
    long made = ca.calls - before;
    tlod_context_destroy(ctx);
    leaks += ca.allocs != ca.frees;
    if (calls < 0) calls = made, k = -1; /* the first pass counts the allocations */
  }
  printf("  out of memory: %ld allocations each failed in turn\n", calls);
  CHECK(calls > 5);
  CHECK_MSG(failures == (uint32_t)calls && silent == 0 && leaks == 0, "%u failures, %u not OOM, %u leaks", failures,
            silent, leaks);
}

/* ------------------------------------------------------------------------ */
/* tlod_mesh_update_attribute                                               */
/* ------------------------------------------------------------------------ */

TEST(test_update_attribute) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float field[9][2] = {{0}}, next[9][2], bad[9][2];
  for (int v = 0; v < 9; v++)
    field[v][0] = (float)v, field[v][1] = 1.0f, next[v][0] = (float)(10 * v), next[v][1] = -2.0f;
  memcpy(bad, next, sizeof bad);
  bad[5][1] = INFINITY;
  tlod_attribute_desc a = {.data = &field[0][0], .components = 2, .name = "temperature"};
  tlod_mesh_desc d = {.positions = &k_tri_pos[0][0],
                      .vertex_count = 9,
                      .indices = k_tri_idx,
                      .index_count = 6,
                      .attributes = &a,
                      .attribute_count = 1};
  tlod_mesh* m = NULL;
  tlod_mesh_create(ctx, &d, &m);
  tlod_result r_bad = tlod_mesh_update_attribute(m, 0, &bad[0][0], 0);
  bool named = strstr(tlod_context_last_error(ctx), "vertex 5") && strstr(tlod_context_last_error(ctx), "temperature");
  tlod_result r_index = tlod_mesh_update_attribute(m, 1, &next[0][0], 0);
  tlod_result r_null = tlod_mesh_update_attribute(m, 0, NULL, 0);
  tlod_result r_stride = tlod_mesh_update_attribute(m, 0, &next[0][0], 4);
  uint16_t ij[3][2] = {{4, 0}, {0, 4}, {1, 1}};
  float before[3][4], after[3][4];
  tlod_mesh_eval_attributes_grid(m, 1, 2, &ij[0][0], sizeof ij[0], 3, before);
  tlod_result r_ok = tlod_mesh_update_attribute(m, 0, &next[0][0], 8);
  tlod_mesh_eval_attributes_grid(m, 1, 2, &ij[0][0], sizeof ij[0], 3, after);
  tlod_result r_nullmesh = tlod_mesh_update_attribute(NULL, 0, &next[0][0], 0);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  CHECK(r_bad == TLOD_ERROR_INVALID_MESH && named);
  CHECK(r_index == TLOD_ERROR_INVALID_ARGUMENT && r_null == TLOD_ERROR_INVALID_ARGUMENT &&
        r_stride == TLOD_ERROR_INVALID_ARGUMENT && r_nullmesh == TLOD_ERROR_INVALID_ARGUMENT);
  /* face 1 = (0, 2, 3): grid (4, 0) is corner 0, (0, 4) corner 2 (vertex 2); failures wrote nothing */
  CHECK(before[0][0] == 0.0f && before[1][0] == 2.0f && before[1][1] == 1.0f);
  CHECK(r_ok == TLOD_SUCCESS);
  CHECK(after[0][0] == 0.0f && after[1][0] == 20.0f && after[1][1] == -2.0f && after[0][2] == 0.0f &&
        after[0][3] == 1.0f);
  /* interior: u = v = 1/4 of (0, 20, 30): 0.25 * 0 + 0.25 * 20 + 0.5 * 30 */
  CHECK_NEAR(after[2][0], 20.0, 1e-5);
}

/* ------------------------------------------------------------------------ */
/* Computed corner normals of curved faces                                  */
/* ------------------------------------------------------------------------ */

/* 6 biquadratic quads around the unit cylinder, z in [0, h], spans of 40 to
 * 80 degrees so the flat normals are off the radial direction; every node
 * on the cylinder. Vertices: bottom corners 0..5, top 6..11, side mids
 * 12..17, per quad bottom mid 18 + q, top mid 24 + q, centre 30 + q. */
#define CYL_Q 6
#define CYL_V 36
static const double k_cyl_deg[CYL_Q + 1] = {0, 40, 120, 180, 240, 280, 360};
static float g_cyl_pos[CYL_V][3];
static uint32_t g_cyl_idx[CYL_Q * 4], g_cyl_nodes[CYL_Q * 5];

static void cyl_point(double deg, double z, float out[3]) {
  double a = deg * (3.14159265358979323846 / 180.0);
  out[0] = (float)cos(a);
  out[1] = (float)sin(a);
  out[2] = (float)z;
}

static void cyl_make(double h) {
  for (int q = 0; q < CYL_Q; q++) {
    double a = k_cyl_deg[q], mid = 0.5 * (a + k_cyl_deg[q + 1]);
    cyl_point(a, 0, g_cyl_pos[q]);
    cyl_point(a, h, g_cyl_pos[6 + q]);
    cyl_point(a, 0.5 * h, g_cyl_pos[12 + q]);
    cyl_point(mid, 0, g_cyl_pos[18 + q]);
    cyl_point(mid, h, g_cyl_pos[24 + q]);
    cyl_point(mid, 0.5 * h, g_cyl_pos[30 + q]);
    uint32_t n = (uint32_t)(q + 1) % CYL_Q, c[4] = {(uint32_t)q, n, 6 + n, 6 + (uint32_t)q};
    uint32_t nodes[5] = {18 + (uint32_t)q, 12 + n, 24 + (uint32_t)q, 12 + (uint32_t)q, 30 + (uint32_t)q};
    memcpy(g_cyl_idx + 4 * q, c, sizeof c);
    memcpy(g_cyl_nodes + 5 * q, nodes, sizeof nodes);
  }
}

static tlod_mesh* cyl_mesh(tlod_context* ctx, bool nodes, float crease) {
  tlod_mesh_desc d = {.positions = &g_cyl_pos[0][0],
                      .vertex_count = CYL_V,
                      .indices = g_cyl_idx,
                      .index_count = CYL_Q * 4,
                      .face_type = TLOD_FACE_QUADS,
                      .face_nodes = nodes ? g_cyl_nodes : NULL,
                      .normal_mode = TLOD_NORMALS_ANGLE,
                      .crease_angle_deg = crease,
                      .label = "cylinder"};
  tlod_mesh* m = NULL;
  if (tlod_mesh_create(ctx, &d, &m) != TLOD_SUCCESS) fprintf(stderr, "  %s\n", tlod_context_last_error(ctx));
  return m;
}

/* Lagrange basis on nodes 0, 1/2, 1 (index 0, 1 = mid, 2) and derivatives. */
static double lag3(int a, double t) {
  return a == 0 ? (1 - t) * (1 - 2 * t) : a == 1 ? 4 * t * (1 - t) : t * (2 * t - 1);
}
static double lag3_d(int a, double t) { return a == 0 ? 4 * t - 3 : a == 1 ? 4 - 8 * t : 4 * t - 1; }

/* The vertex at grid (a, b) of quad q (a, b in 0, 1 = mid, 2). */
static uint32_t cyl_node(int q, int a, int b) {
  static const int8_t slot[3][3] = {{-1, 3, -4}, {0, 4, 2}, {-2, 1, -3}}; /* corner -(i+1) or node slot */
  int s = slot[a][b];
  return s < 0 ? g_cyl_idx[4 * q - s - 1] : g_cyl_nodes[5 * q + s];
}

/* Corner (ca, cb) of quad q, from the shape functions: the unit normal
 * Q_u x Q_v and the interior angle between the edge tangents there. */
static double cyl_corner(int q, int ca, int cb, double n[3]) {
  double du[3] = {0, 0, 0}, dv[3] = {0, 0, 0}, u = ca / 2.0, v = cb / 2.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      for (int c = 0; c < 3; c++) {
        double x = g_cyl_pos[cyl_node(q, a, b)][c];
        du[c] += lag3_d(a, u) * lag3(b, v) * x;
        dv[c] += lag3(a, u) * lag3_d(b, v) * x;
      }
  double x[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
  double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), dot = 0;
  for (int c = 0; c < 3; c++) {
    n[c] = x[c] / len;
    dot += (ca ? -du[c] : du[c]) * (cb ? -dv[c] : dv[c]);
  }
  return atan2(len, dot);
}

/* Angle-weighted mean of the corner normals at bottom/top corner j. */
static void cyl_expected(int j, bool top, double out[3]) {
  double n0[3], n1[3];
  int p = (j + CYL_Q - 1) % CYL_Q, cb = top ? 2 : 0;
  double w0 = cyl_corner(j, 0, cb, n0), w1 = cyl_corner(p, 2, cb, n1), len = 0;
  for (int c = 0; c < 3; c++) {
    out[c] = w0 * n0[c] + w1 * n1[c];
    len += out[c] * out[c];
  }
  for (int c = 0; c < 3; c++)
    out[c] /= sqrt(len);
}

static double angle_deg(const double a[3], const float b[3]) {
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
  return atan2(sqrt(x * x + y * y + z * z), d) * (180.0 / 3.14159265358979323846);
}

typedef struct cyl_err {
  double expected; /* largest |n - expected| (curved faces only) */
  double curved;   /* largest angle to the cylinder normal, degrees */
} cyl_err;

static cyl_err cyl_check(const tlod_mesh* m) {
  tlod_mesh_view v = tlod_mesh_query_view(m);
  cyl_err e = {0, 0};
  for (int i = 0; i < 12; i++) {
    float r[3];
    cyl_point(k_cyl_deg[i % 6], 0, r);
    double x[3], radial[3] = {r[0], r[1], 0};
    cyl_expected(i % 6, i >= 6, x);
    e.expected = fmax(e.expected, dist3(x, v.normals[i]));
    e.curved = fmax(e.curved, angle_deg(radial, v.normals[i]));
  }
  return e;
}

/* Normals of the curved and the flat cylinder, created and after an update
 * stretching it along z (the update recomputes them the same way). */
typedef struct cyl_run {
  bool made, updated;
  cyl_err e, e_creased, e_updated, e_creased_updated;
  double flat_deg;
  uint32_t creased_vertices, flat_creased_vertices;
} cyl_run;

static uint32_t cyl_vertices(const tlod_mesh* m) { return m ? tlod_mesh_query_view(m).vertex_count : 0; }

static void cyl_run_all(tlod_context* ctx, cyl_run* out) {
  cyl_make(1.0);
  tlod_mesh* curved = cyl_mesh(ctx, true, 0.0f);
  tlod_mesh* flat = cyl_mesh(ctx, false, 0.0f);
  /* Flat faces meet at 60 degrees at every vertex: a 30 degree crease
   * splits them all, the curved corner normals agree within it. */
  tlod_mesh* creased = cyl_mesh(ctx, true, 30.0f);
  tlod_mesh* flat_creased = cyl_mesh(ctx, false, 30.0f);
  out->made = curved && flat && creased && flat_creased;
  if (out->made) {
    out->e = cyl_check(curved);
    out->e_creased = cyl_check(creased);
    out->flat_deg = cyl_check(flat).curved;
    out->creased_vertices = cyl_vertices(creased);
    out->flat_creased_vertices = cyl_vertices(flat_creased);
    cyl_make(3.0);
    out->updated = tlod_mesh_update(curved, &g_cyl_pos[0][0], 0, NULL, 0) == TLOD_SUCCESS &&
                   tlod_mesh_update(creased, &g_cyl_pos[0][0], 0, NULL, 0) == TLOD_SUCCESS;
    out->e_updated = cyl_check(curved);
    out->e_creased_updated = cyl_check(creased);
  }
  tlod_mesh_destroy(curved);
  tlod_mesh_destroy(flat);
  tlod_mesh_destroy(creased);
  tlod_mesh_destroy(flat_creased);
}

TEST(test_curved_corner_normals) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  cyl_run r = {0};
  cyl_run_all(ctx, &r);
  tlod_context_destroy(ctx);
  CHECK(r.made && r.updated);
  printf("  corner normals: %.3g from the shape functions; to the cylinder %.3f deg curved, %.3f deg flat\n",
         r.e.expected, r.e.curved, r.flat_deg);
  CHECK(r.e.expected < 1e-6 && r.e_creased.expected < 1e-6);
  CHECK(r.e.curved < 0.25 * r.flat_deg);
  CHECK(r.creased_vertices == CYL_V && r.flat_creased_vertices > CYL_V);
  CHECK(r.e_updated.expected < 1e-6 && r.e_creased_updated.expected < 1e-6);
}

int main(void) {
  RUN(test_hex27_faces_exact);
  RUN(test_hex20_faces_exact);
  RUN(test_hex_records);
  RUN(test_hex_refresh);
  RUN(test_hex_cpu_closed);
  RUN(test_triangles_exact);
  RUN(test_triangle_derivatives);
  RUN(test_node_sharing);
  RUN(test_node_smooth_flag);
  RUN(test_linear_is_phong);
  RUN(test_error_tables);
  RUN(test_hostile_nodes);
  RUN(test_random_nodes);
  RUN(test_out_of_memory);
  RUN(test_update_attribute);
  RUN(test_curved_corner_normals);
  TEST_END();
}
