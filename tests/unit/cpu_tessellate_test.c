/*
 * cpu_tessellate_test.c -- independent verification of the CPU reference
 * tessellator (tesslod/cpu.h) over the refinement patterns (tesslod/lod.h).
 * Owned by the verification tests. Reads private state: none (public API only).
 *
 * This work is based on: Schwarz, Staginski, Stamminger 2006 (refinement
 * and connection patterns), docs/design.md invariants 1 and 3.
 *
 * Topological checks are exact: the no_weld output is welded by bitwise
 * equal float positions, never by a distance. Tolerances: output normals
 * are unit to 1e-5 (one float normalisation).
 */
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"
#include "test_fixture.h"
#include "test_lod.h"

#define MAX_LEVEL 6

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

static tlod_cpu_mesh* tessellate(const fixture* fx, uint32_t level, const int8_t* levels, bool no_weld,
                                 bool no_stitch) {
  tlod_cpu_tessellate_desc d = {.level = level, .levels = levels, .no_weld = no_weld, .no_stitch = no_stitch};
  tlod_cpu_mesh* out = NULL;
  tlod_result r = tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &d, &out);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_cpu_tessellate: %s: %s\n", tlod_result_string(r), tlod_context_last_error(fx->ctx));
    return NULL;
  }
  return out;
}

static int8_t* random_levels(uint32_t patches, uint64_t seed, int max_level) {
  shape_rng rng = {seed};
  int8_t* l = malloc(patches + 1);
  for (uint32_t p = 0; p < patches; ++p)
    l[p] = (int8_t)(shape_rng_next(&rng) % (uint64_t)(max_level + 1));
  return l;
}

/* ------------------------------------------------------------------------ */
/* Exact topology of an output mesh                                         */
/* ------------------------------------------------------------------------ */

/* Welds m by bitwise equal positions and checks that the result is a closed,
 * consistently oriented 2-manifold without degenerate triangles: every
 * directed edge occurs once and its reverse occurs once. Returns true if so;
 * otherwise `why` says what is wrong (shapes.h, shared with the scheduler
 * test). */
static bool closed_manifold(const tlod_cpu_mesh* m, char* why, size_t why_size) {
  return shape_closed_manifold(m->positions, m->vertex_count, m->indices, m->triangle_count, m->triangle_patch, why,
                               why_size);
}

/* Output normals are finite unit vectors. */
static void check_unit_normals(const tlod_cpu_mesh* m, const char* what) {
  CHECK_MSG(m->normals != NULL, "%s: no normals", what);
  for (uint32_t v = 0; v < m->vertex_count; ++v) {
    const float* n = m->normals + 3 * (size_t)v;
    double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    CHECK_MSG(fabs(l - 1.0) <= 1e-5, "%s: vertex %u normal length %.9g", what, v, l);
  }
}

/* ------------------------------------------------------------------------ */
/* 1. Counts                                                                */
/* ------------------------------------------------------------------------ */

TEST(test_uniform_counts) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[7] = {shape_icosphere(1), shape_torus(8, 6), shape_cube_shared(), shape_seam_sphere(4, 8),
                     shape_open_grid(3), shape_quad_cube(), shape_quad_sphere(2)};
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 7; ++si) {
    const shape* s = &shapes[si];
    uint64_t V = 0, E = 0, F = shape_face_count(s);
    uint32_t v32, e32;
    shape_topology(s, &v32, &e32);
    V = v32, E = e32;
    for (int ti = 0; ti < 3; ++ti) {
      if (s->corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx;
      CHECK(fixture_make(&fx, ctx, s, types[ti]));
      for (uint32_t l = 0; l <= 4; ++l) {
        uint64_t n = 1u << l;
        uint64_t tris = s->corners == 3 ? F * n * n : 2 * F * n * n;
        uint64_t welded = s->corners == 3 ? V + E * (n - 1) + F * (n - 1) * (n > 1 ? n - 2 : 0) / 2
                                          : V + E * (n - 1) + F * (n - 1) * (n - 1);
        uint64_t separate = s->corners == 3 ? F * (n + 1) * (n + 2) / 2 : F * (n + 1) * (n + 1);
        tlod_cpu_mesh* w = tessellate(&fx, l, NULL, false, false);
        tlod_cpu_mesh* nw = tessellate(&fx, l, NULL, true, false);
        CHECK(w && nw);
        char what[96];
        snprintf(what, sizeof what, "%s %s level %u", s->name, type_name(types[ti]), l);
        bool ok = w->triangle_count == tris && nw->triangle_count == tris && w->vertex_count == welded &&
                  nw->vertex_count == separate && w->pattern_triangles == tris && w->strip_triangles == 0 &&
                  w->strips == 0 && nw->strips == 0 && nw->strip_triangles == 0;
        if (!ok)
          fprintf(stderr,
                  "%s: triangles %u/%u (expected %llu), vertices welded %u (expected %llu), no_weld %u (expected "
                  "%llu), pattern %u, strips %u (%u triangles)\n",
                  what, w->triangle_count, nw->triangle_count, (unsigned long long)tris, w->vertex_count,
                  (unsigned long long)welded, nw->vertex_count, (unsigned long long)separate, w->pattern_triangles,
                  w->strips, w->strip_triangles);
        /* every triangle belongs to a patch, 4^l (quads 2 * 4^l) each */
        uint32_t* per_patch = calloc(F, sizeof *per_patch);
        for (uint32_t t = 0; t < w->triangle_count; ++t)
          if (w->triangle_patch[t] < F) per_patch[w->triangle_patch[t]]++;
        for (uint32_t p = 0; p < F && ok; ++p)
          if (per_patch[p] != tris / F) {
            fprintf(stderr, "%s: patch %u has %u triangles\n", what, p, per_patch[p]);
            ok = false;
          }
        free(per_patch);
        tlod_cpu_mesh_destroy(ctx, w);
        tlod_cpu_mesh_destroy(ctx, nw);
        CHECK_MSG(ok, "%s: counts differ (see above)", what);
      }
      fixture_free(&fx);
    }
  }
  for (int k = 0; k < 7; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 2, 6, 7. Watertight, outward, unit normals                               */
/* ------------------------------------------------------------------------ */

/* Every triangle of the (unit) sphere faces outward.
 *   Pattern triangles: strictly, n . centroid > 0.
 *   Strip triangles fill the gap between two polylines of one boundary
 *   curve (a coarse chord and the finer points on the curve above it), so
 *   they are walls seen edge-on from outside: cos(n, centroid) is ~0 with
 *   either sign. A fold-over faces inward (cos ~ -1); strips must keep
 *   cos >= -0.1. Strip triangles whose points are collinear in exact
 *   arithmetic (a flat patch's finer polyline lies on the coarser chord)
 *   have no defined normal: with |cross| < 1e-5 * (longest edge)^2 they are
 *   counted as slivers and skipped.
 * Returns false and says why on the first violation; *worst_strip gets the
 * smallest cos over the strip triangles checked. */
static bool all_outward(const tlod_cpu_mesh* m, uint32_t* slivers, double* worst_strip, char* why, size_t why_size) {
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const float* p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = m->positions + 3 * (size_t)m->indices[3 * t + c];
    double e1[3], e2[3], e3[3], cen[3];
    for (int c = 0; c < 3; ++c) {
      e1[c] = (double)p[1][c] - p[0][c];
      e2[c] = (double)p[2][c] - p[0][c];
      e3[c] = (double)p[2][c] - p[1][c];
      cen[c] = ((double)p[0][c] + p[1][c] + p[2][c]) / 3.0;
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double d = n[0] * cen[0] + n[1] * cen[1] + n[2] * cen[2];
    double longest =
        fmax(fmax(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2], e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]),
             e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2]);
    double area2 = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double cosang = d / (area2 * sqrt(cen[0] * cen[0] + cen[1] * cen[1] + cen[2] * cen[2]));
    if (m->triangle_patch[t] == UINT32_MAX) {
      if (area2 < 1e-5 * longest) {
        ++*slivers;
        continue;
      }
      *worst_strip = fmin(*worst_strip, cosang);
      if (!(cosang >= -0.1)) {
        snprintf(why, why_size, "strip triangle %u folds over: cos(normal, outward) = %.3g", t, cosang);
        return false;
      }
    } else if (!(d > 0)) {
      snprintf(why, why_size, "triangle %u (patch %u) faces inward (cos %.3g)", t, m->triangle_patch[t], cosang);
      return false;
    }
  }
  return true;
}

TEST(test_watertight) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  shape shapes[8] = {shape_icosphere(1),  shape_torus(8, 6), shape_cube_split(),   shape_cube_soft(),
                     shape_cube_shared(), shape_quad_cube(), shape_quad_sphere(2), shape_seam_sphere(4, 8)};
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t runs = 0, strips_seen = 0, slivers = 0, closed_failures = 0, outward_failures = 0;
  double worst_strip = 1.0;
  for (int si = 0; si < 8; ++si) {
    const shape* s = &shapes[si];
    for (int ti = 0; ti < 3; ++ti) {
      if (s->corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx;
      CHECK(fixture_make(&fx, ctx, s, types[ti]));
      uint32_t patches = tlod_surface_patch_count(fx.surf);
      for (int run = 0; run < 8; ++run) {
        /* runs 0..4: uniform level; 5..7: random levels 0..4 */
        int8_t* levels = run >= 5 ? random_levels(patches, 1000 * (uint64_t)si + 10 * (uint64_t)ti + run, 4) : NULL;
        uint32_t level = run < 5 ? (uint32_t)run : 0;
        char what[128];
        snprintf(what, sizeof what, "%s %s %s %u", s->name, type_name(types[ti]),
                 levels ? "random levels, seed" : "level", run);
        for (int weld = 0; weld < 2; ++weld) {
          tlod_cpu_mesh* m = tessellate(&fx, level, levels, weld == 0, false);
          CHECK_MSG(m, "%s", what);
          char why[160] = "";
          bool closed = closed_manifold(m, why, sizeof why);
          if (!closed)
            fprintf(stderr, "%s%s: not closed: %s (%u strips, %u strip triangles, %u skipped)\n", what,
                    weld ? " (welded)" : " (no_weld)", why, m->strips, m->strip_triangles, m->folds_skipped);
          closed_failures += !closed;
          char why_out[160] = "";
          bool outward = si != 0 || all_outward(m, &slivers, &worst_strip, why_out, sizeof why_out);
          if (!outward) fprintf(stderr, "%s: %s\n", what, why_out);
          outward_failures += !outward;
          if (closed) CALL(check_unit_normals(m, what));
          if (run == 5 && weld == 0) strips_seen += m->strips > 0;
          /* triangle_patch: pattern triangles name their patch, strips UINT32_MAX */
          uint32_t pattern = 0, strip = 0;
          for (uint32_t t = 0; t < m->triangle_count; ++t) {
            if (m->triangle_patch[t] == UINT32_MAX)
              strip++;
            else if (m->triangle_patch[t] < patches)
              pattern++;
          }
          CHECK_MSG(pattern == m->pattern_triangles && strip == m->strip_triangles &&
                        pattern + strip == m->triangle_count,
                    "%s: triangle_patch counts %u + %u vs %u + %u", what, pattern, strip, m->pattern_triangles,
                    m->strip_triangles);
          tlod_cpu_mesh_destroy(ctx, m);
          runs++;
        }
        free(levels);
      }
      fixture_free(&fx);
    }
  }
  printf("  %u tessellations, %u not closed, %u with inward triangles (sphere: smallest strip cos(normal, "
         "outward) %.3g, %u degenerate strip slivers skipped); random levels needed strips in %u runs\n",
         runs, closed_failures, outward_failures, worst_strip, slivers, strips_seen);
  for (int k = 0; k < 8; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
  CHECK(strips_seen > 0);
  CHECK_MSG(closed_failures == 0, "%u tessellations not closed (see above)", closed_failures);
  CHECK_MSG(outward_failures == 0, "%u sphere tessellations with inward triangles (see above)", outward_failures);
}

/* The checker must see the cracks that stitching closes. */
TEST(test_watertight_checker_detects_cracks) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  /* cube_soft, not cube_split: with face normals the Phong and PN edges of a
   * cube are straight on both sides and coincide, so there is no crack */
  shape sph = shape_icosphere(1), cube = shape_cube_soft(), qs = shape_quad_sphere(2);
  struct {
    const shape* s;
    tlod_surface_type type;
    bool mixed;
  } cases[] = {{&sph, TLOD_SURFACE_PHONG, true}, {&sph, TLOD_SURFACE_PN, true},      {&sph, TLOD_SURFACE_FLAT, true},
               {&qs, TLOD_SURFACE_PHONG, true},  {&cube, TLOD_SURFACE_PHONG, false}, {&cube, TLOD_SURFACE_PN, false},
               {&cube, TLOD_SURFACE_PHONG, true}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    fixture fx;
    CHECK(fixture_make(&fx, ctx, cases[k].s, cases[k].type));
    int8_t* levels = cases[k].mixed ? random_levels(tlod_surface_patch_count(fx.surf), 77 + k, 4) : NULL;
    tlod_cpu_mesh* open = tessellate(&fx, 2, levels, true, true);
    tlod_cpu_mesh* stitched = tessellate(&fx, 2, levels, true, false);
    CHECK(open && stitched);
    char why[160] = "", why2[160] = "";
    bool open_closed = closed_manifold(open, why, sizeof why);
    bool stitched_closed = closed_manifold(stitched, why2, sizeof why2);
    if (k == 0) printf("  no_stitch, mixed levels: \"%s\"\n", why);
    if (k == 4) printf("  no_stitch, soft split-normal cube: \"%s\"\n", why);
    CHECK_MSG(!open_closed, "case %zu: no_stitch output passed the watertight check", k);
    CHECK_MSG(stitched_closed, "case %zu: %s", k, why2);
    CHECK_MSG(open->strip_triangles == 0 && open->strips == 0, "case %zu: no_stitch made %u strips", k, open->strips);
    CHECK_MSG(stitched->strips > 0, "case %zu: no strips", k);
    tlod_cpu_mesh_destroy(ctx, open);
    tlod_cpu_mesh_destroy(ctx, stitched);
    free(levels);
    fixture_free(&fx);
  }
  shape_free(&sph);
  shape_free(&cube);
  shape_free(&qs);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 3. Shared edge polylines of no_weld output                               */
/* ------------------------------------------------------------------------ */

static void check_edge_polylines(const fixture* fx, const int8_t* levels, uint32_t level, const char* what,
                                 uint32_t* compared) {
  tlod_cpu_mesh* m = tessellate(fx, level, levels, true, false);
  CHECK(m);
  uint32_t patches = tlod_surface_patch_count(fx->surf);
  uint32_t* base = malloc(sizeof *base * (patches + 1));
  uint32_t* plevel = malloc(sizeof *plevel * (patches + 1));
  base[0] = 0;
  for (uint32_t p = 0; p < patches; ++p) {
    plevel[p] = levels ? (uint32_t)levels[p] : level;
    tlod_pattern_shape sh =
        tlod_surface_patch(fx->surf, p).corner_count == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
    base[p + 1] = base[p] + tlod_pattern_vertex_count(sh, plevel[p]);
  }
  bool ok = m->vertex_count >= base[patches];
  if (!ok) fprintf(stderr, "%s: %u vertices < %u pattern vertices\n", what, m->vertex_count, base[patches]);
  /* blocks: the corners (first pattern vertices) are the input vertices */
  for (uint32_t p = 0; p < patches && ok; ++p) {
    uint32_t vid[4], n = tlod_mesh_face_corners(fx->mesh, p, vid);
    for (uint32_t c = 0; c < n && ok; ++c) {
      float pos[3], nrm[3];
      tlod_mesh_vertex(fx->mesh, vid[c], pos, nrm);
      if (memcmp(pos, m->positions + 3 * (size_t)(base[p] + c), sizeof pos) != 0) {
        fprintf(stderr, "%s: patch %u block vertex %u is not corner %u\n", what, p, base[p] + c, c);
        ok = false;
      }
    }
  }
  /* pattern triangles index their own patch's block */
  for (uint32_t t = 0; t < m->triangle_count && ok; ++t) {
    uint32_t p = m->triangle_patch[t];
    if (p == UINT32_MAX) continue;
    for (int c = 0; c < 3; ++c)
      if (m->indices[3 * t + c] < base[p] || m->indices[3 * t + c] >= base[p + 1]) {
        fprintf(stderr, "%s: triangle %u of patch %u uses vertex %u outside [%u, %u)\n", what, t, p,
                m->indices[3 * t + c], base[p], base[p + 1]);
        ok = false;
        break;
      }
  }
  uint32_t ea[(1 << MAX_LEVEL) + 1], eb[(1 << MAX_LEVEL) + 1];
  for (uint32_t f = 0; f < patches && ok; ++f) {
    uint32_t nf = tlod_surface_patch(fx->surf, f).corner_count;
    tlod_pattern_shape sf = nf == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
    for (uint32_t e = 0; e < nf && ok; ++e) {
      tlod_edge_link link = tlod_mesh_edge_link(fx->mesh, f, e);
      if (link.face == UINT32_MAX || !link.smooth) continue;
      uint32_t g = link.face;
      tlod_pattern_shape sg =
          tlod_surface_patch(fx->surf, g).corner_count == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
      uint32_t la = plevel[f], lb = plevel[g];
      uint32_t na = tlod_patterns_edge(fx->pat, sf, la, e, ea);
      uint32_t nb = tlod_patterns_edge(fx->pat, sg, lb, link.edge, eb);
      if (na != (1u << la) + 1 || nb != (1u << lb) + 1) {
        fprintf(stderr, "%s: tlod_patterns_edge returned %u, %u points\n", what, na, nb);
        ok = false;
        break;
      }
      /* the coarser side's points are every 2^|la - lb|-th point of the finer one */
      for (uint32_t k = 0; k < na && ok; ++k) {
        uint64_t num = (uint64_t)k << lb, den = (uint64_t)1 << la; /* t = k / 2^la in units of 2^-lb */
        if (num % den) continue;
        uint32_t kb = (1u << lb) - (uint32_t)(num / den); /* g runs the other way */
        const float* pa = m->positions + 3 * (size_t)(base[f] + ea[k]);
        const float* pb = m->positions + 3 * (size_t)(base[g] + eb[kb]);
        if (memcmp(pa, pb, 3 * sizeof(float)) != 0) {
          fprintf(stderr,
                  "%s: patch %u edge %u point %u/%u (%.9g %.9g %.9g) != patch %u edge %u point %u/%u (%.9g %.9g "
                  "%.9g)\n",
                  what, f, e, k, 1u << la, pa[0], pa[1], pa[2], g, link.edge, kb, 1u << lb, pb[0], pb[1], pb[2]);
          ok = false;
        }
        ++*compared;
      }
    }
  }
  free(base);
  free(plevel);
  tlod_cpu_mesh_destroy(fx->ctx, m);
  CHECK_MSG(ok, "%s (see above)", what);
}

TEST(test_shared_edge_polylines) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[5] = {shape_icosphere(1), shape_torus(8, 6), shape_seam_sphere(4, 8), shape_quad_sphere(2),
                     shape_open_grid(3)};
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t compared = 0;
  for (int si = 0; si < 5; ++si)
    for (int ti = 0; ti < 3; ++ti) {
      if (shapes[si].corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &shapes[si], types[ti]));
      uint32_t patches = tlod_surface_patch_count(fx.surf);
      for (int run = 0; run < 4; ++run) {
        int8_t* levels = run >= 2 ? random_levels(patches, 500 + 7 * (uint64_t)si + run, 5) : NULL;
        char what[96];
        snprintf(what, sizeof what, "%s %s run %d", shapes[si].name, type_name(types[ti]), run);
        CALL(check_edge_polylines(&fx, levels, run == 0 ? 3 : 5, what, &compared));
        free(levels);
      }
      fixture_free(&fx);
    }
  printf("  %u shared edge points compared bitwise\n", compared);
  CHECK(compared > 10000);
  for (int k = 0; k < 5; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 4. Welded output = no_weld output                                        */
/* ------------------------------------------------------------------------ */

typedef struct tri_key {
  uint32_t bits[9];
} tri_key;

static int cmp_tri_key(const void* a, const void* b) { return memcmp(a, b, sizeof(tri_key)); }

/* Triangles as position triples, each rotated (orientation kept) so its
 * smallest vertex comes first, sorted. */
static tri_key* triangle_keys(const tlod_cpu_mesh* m) {
  tri_key* k = malloc(sizeof *k * (m->triangle_count + 1));
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    uint32_t v[3][3];
    for (int c = 0; c < 3; ++c)
      memcpy(v[c], m->positions + 3 * (size_t)m->indices[3 * t + c], sizeof v[c]);
    int first = 0;
    for (int c = 1; c < 3; ++c)
      if (memcmp(v[c], v[first], sizeof v[c]) < 0) first = c;
    for (int c = 0; c < 3; ++c)
      memcpy(k[t].bits + 3 * c, v[(first + c) % 3], sizeof v[0]);
  }
  qsort(k, m->triangle_count, sizeof *k, cmp_tri_key);
  return k;
}

TEST(test_welded_matches_no_weld) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[5] = {shape_icosphere(1), shape_cube_split(), shape_cube_soft(), shape_quad_sphere(2),
                     shape_seam_sphere(4, 8)};
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 5; ++si)
    for (int ti = 0; ti < 3; ++ti) {
      if (shapes[si].corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &shapes[si], types[ti]));
      for (int run = 0; run < 3; ++run) {
        int8_t* levels = run > 0 ? random_levels(tlod_surface_patch_count(fx.surf), 900 + (uint64_t)run, 4) : NULL;
        tlod_cpu_mesh* w = tessellate(&fx, 3, levels, false, false);
        tlod_cpu_mesh* nw = tessellate(&fx, 3, levels, true, false);
        CHECK(w && nw);
        CHECK_MSG(w->triangle_count == nw->triangle_count, "%s %s run %d: %u vs %u triangles", shapes[si].name,
                  type_name(types[ti]), run, w->triangle_count, nw->triangle_count);
        CHECK(w->vertex_count <= nw->vertex_count);
        tri_key* a = triangle_keys(w);
        tri_key* b = triangle_keys(nw);
        bool same = memcmp(a, b, sizeof *a * w->triangle_count) == 0;
        free(a);
        free(b);
        CHECK_MSG(same, "%s %s run %d: welded and no_weld triangles differ", shapes[si].name, type_name(types[ti]),
                  run);
        /* the welded output has no two vertices with equal position and normal */
        uint32_t* weld = malloc(sizeof *weld * (w->vertex_count + 1));
        uint32_t distinct = shape_weld_ids(w->positions, w->vertex_count, weld);
        free(weld);
        if (!shapes[si].creases && types[ti] != TLOD_SURFACE_FLAT)
          CHECK_MSG(distinct == w->vertex_count, "%s %s run %d: %u vertices, %u distinct positions", shapes[si].name,
                    type_name(types[ti]), run, w->vertex_count, distinct);
        tlod_cpu_mesh_destroy(ctx, w);
        tlod_cpu_mesh_destroy(ctx, nw);
        free(levels);
      }
      fixture_free(&fx);
    }
  for (int k = 0; k < 5; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 5. Thread independence                                                   */
/* ------------------------------------------------------------------------ */

static bool same_output(const tlod_cpu_mesh* a, const tlod_cpu_mesh* b) {
  if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count ||
      a->pattern_triangles != b->pattern_triangles || a->strip_triangles != b->strip_triangles ||
      a->strips != b->strips || a->folds_skipped != b->folds_skipped)
    return false;
  size_t nv = 3 * (size_t)a->vertex_count, nt = (size_t)a->triangle_count;
  if (memcmp(a->positions, b->positions, sizeof(float) * nv) != 0) return false;
  if ((a->normals == NULL) != (b->normals == NULL)) return false;
  if (a->normals && memcmp(a->normals, b->normals, sizeof(float) * nv) != 0) return false;
  if (memcmp(a->indices, b->indices, sizeof(uint32_t) * 3 * nt) != 0) return false;
  return memcmp(a->triangle_patch, b->triangle_patch, sizeof(uint32_t) * nt) == 0;
}

TEST(test_thread_independence) {
  reverse_pool pool = {0};
  tlod_context* ctxs[3] = {new_context(1, NULL, NULL), new_context(2, NULL, NULL), new_context(0, NULL, &pool)};
  CHECK(ctxs[0] && ctxs[1] && ctxs[2]);
  shape shapes[3] = {shape_icosphere(2), shape_cube_soft(), shape_quad_sphere(3)};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      if (shapes[si].corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx[3];
      for (int c = 0; c < 3; ++c)
        CHECK(fixture_make(&fx[c], ctxs[c], &shapes[si], types[ti]));
      int8_t* levels = random_levels(tlod_surface_patch_count(fx[0].surf), 4242 + (uint64_t)si, 5);
      for (int mode = 0; mode < 3; ++mode) {
        tlod_cpu_mesh* out[3];
        for (int c = 0; c < 3; ++c) {
          out[c] = tessellate(&fx[c], 4, mode == 2 ? NULL : levels, mode == 1, false);
          CHECK(out[c]);
        }
        bool same1 = same_output(out[0], out[1]), same2 = same_output(out[0], out[2]);
        for (int c = 0; c < 3; ++c)
          tlod_cpu_mesh_destroy(ctxs[c], out[c]);
        CHECK_MSG(same1, "%s %s mode %d: 1 thread vs 2 threads differ", shapes[si].name, type_name(types[ti]), mode);
        CHECK_MSG(same2, "%s %s mode %d: 1 thread vs reversed custom parallel-for differ", shapes[si].name,
                  type_name(types[ti]), mode);
      }
      free(levels);
      for (int c = 0; c < 3; ++c)
        fixture_free(&fx[c]);
    }
  printf("  custom parallel-for: %ld calls, %ld chunks\n", pool.calls, pool.chunks);
  CHECK_MSG(pool.calls > 0, "the context's parallel-for was never used");
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  for (int c = 0; c < 3; ++c)
    tlod_context_destroy(ctxs[c]);
}

/* ------------------------------------------------------------------------ */
/* 7b. no_normals                                                           */
/* ------------------------------------------------------------------------ */

TEST(test_no_normals) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PN));
  tlod_cpu_mesh* a = NULL;
  tlod_cpu_mesh* b = tessellate(&fx, 3, NULL, true, false);
  CHECK(tlod_cpu_tessellate(ctx, fx.surf, fx.pat,
                            &(tlod_cpu_tessellate_desc){.level = 3, .no_weld = true, .no_normals = true},
                            &a) == TLOD_SUCCESS);
  CHECK(a && b);
  CHECK(a->normals == NULL);
  /* positions do not depend on the normal evaluation */
  CHECK(a->vertex_count == b->vertex_count && a->triangle_count == b->triangle_count);
  CHECK(memcmp(a->positions, b->positions, sizeof(float) * 3 * a->vertex_count) == 0);
  CHECK(memcmp(a->indices, b->indices, sizeof(uint32_t) * 3 * a->triangle_count) == 0);
  tlod_cpu_mesh_destroy(ctx, a);
  tlod_cpu_mesh_destroy(ctx, b);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 8. Bad API use                                                           */
/* ------------------------------------------------------------------------ */

TEST(test_bad_api_use) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  uint32_t patches = tlod_surface_patch_count(fx.surf);
  tlod_cpu_mesh* out = (tlod_cpu_mesh*)&fx; /* must be overwritten with NULL */
  tlod_result r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat, &(tlod_cpu_tessellate_desc){.level = MAX_LEVEL + 1}, &out);
  const char* msg = tlod_context_last_error(ctx);
  printf("  level %d of %d: %s \"%s\"\n", MAX_LEVEL + 1, MAX_LEVEL, tlod_result_string(r), msg);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "%s", tlod_result_string(r));
  CHECK(out == NULL);
  CHECK(strlen(msg) > 0);
  /* a per-patch level too high */
  int8_t* levels = random_levels(patches, 5, 3);
  levels[patches / 2] = MAX_LEVEL + 1;
  out = (tlod_cpu_mesh*)&fx;
  r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat, &(tlod_cpu_tessellate_desc){.levels = levels}, &out);
  msg = tlod_context_last_error(ctx);
  printf("  per-patch level %d: %s \"%s\"\n", MAX_LEVEL + 1, tlod_result_string(r), msg);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "%s", tlod_result_string(r));
  CHECK(out == NULL);
  CHECK(strlen(msg) > 0);
  levels[patches / 2] = -2;
  r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat, &(tlod_cpu_tessellate_desc){.levels = levels}, &out);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "level -2: %s", tlod_result_string(r));
  CHECK(out == NULL);
  /* -1 leaves a patch out: fine */
  levels[patches / 2] = -1;
  r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat, &(tlod_cpu_tessellate_desc){.levels = levels}, &out);
  CHECK(r == TLOD_SUCCESS && out);
  for (uint32_t t = 0; t < out->triangle_count; ++t)
    CHECK(out->triangle_patch[t] != patches / 2);
  tlod_cpu_mesh_destroy(ctx, out);
  free(levels);
  /* patterns that do not reach the level */
  tlod_patterns* small = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 2}, &small) == TLOD_SUCCESS);
  out = (tlod_cpu_mesh*)&fx;
  r = tlod_cpu_tessellate(ctx, fx.surf, small, &(tlod_cpu_tessellate_desc){.level = 3}, &out);
  CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "level 3 with max 2: %s", tlod_result_string(r));
  CHECK(out == NULL);
  tlod_patterns_destroy(small);
  /* NULL arguments */
  tlod_cpu_tessellate_desc d = {.level = 1};
  out = NULL;
  CHECK(tlod_cpu_tessellate(NULL, fx.surf, fx.pat, &d, &out) != TLOD_SUCCESS && out == NULL);
  CHECK(tlod_cpu_tessellate(ctx, NULL, fx.pat, &d, &out) == TLOD_ERROR_INVALID_ARGUMENT && out == NULL);
  CHECK(tlod_cpu_tessellate(ctx, fx.surf, NULL, &d, &out) == TLOD_ERROR_INVALID_ARGUMENT && out == NULL);
  CHECK(tlod_cpu_tessellate(ctx, fx.surf, fx.pat, &d, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  /* a NULL desc: either the defaults (level 0) or an error, never a crash */
  r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat, NULL, &out);
  CHECK(r == TLOD_SUCCESS || r == TLOD_ERROR_INVALID_ARGUMENT);
  if (r == TLOD_SUCCESS) {
    CHECK(out && out->triangle_count == patches);
    tlod_cpu_mesh_destroy(ctx, out);
  }
  tlod_cpu_mesh_destroy(ctx, NULL);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 9. Allocation                                                            */
/* ------------------------------------------------------------------------ */

/* A hand-made draw list is checked like a device's: strips must name edges
 * of drawn patches, arrays must be present where their counts say so. */
static tlod_result tessellate_list(fixture* fx, const tlod_draw_list* dl, bool* out_cleared) {
  tlod_cpu_mesh* out = (tlod_cpu_mesh*)fx; /* must be overwritten with NULL on failure */
  tlod_result r = tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &(tlod_cpu_tessellate_desc){.draw_list = dl}, &out);
  printf("  %s \"%s\"\n", tlod_result_string(r), r ? tlod_context_last_error(fx->ctx) : "");
  *out_cleared = r == TLOD_SUCCESS || out == NULL;
  if (r == TLOD_SUCCESS) tlod_cpu_mesh_destroy(fx->ctx, out);
  return r;
}

/* Refused as an invalid argument, with the output pointer cleared. */
static bool refused(fixture* fx, const tlod_draw_list* dl) {
  bool cleared = false;
  return tessellate_list(fx, dl, &cleared) == TLOD_ERROR_INVALID_ARGUMENT && cleared;
}

TEST(test_bad_draw_list) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shape sph = shape_icosphere(1);
  fixture fx;
  CHECK(ctx && fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  uint32_t patches = tlod_surface_patch_count(fx.surf);
  int8_t* levels = random_levels(patches, 7, 2);
  tlod_draw_strip strip = {.patch_a = 0, .edge_a = 0, .patch_b = 1, .edge_b = 0};
  tlod_draw_list dl = {.patch_count = patches, .levels = levels, .strips = &strip, .strip_count = 1};
  bool cleared = false;
  CHECK(tessellate_list(&fx, &dl, &cleared) == TLOD_SUCCESS);
  strip.edge_b = 3; /* a triangle has edges 0..2 */
  CHECK(refused(&fx, &dl));
  CHECK(strstr(tlod_context_last_error(ctx), "strip 0") != NULL);
  strip.edge_b = 0;
  strip.patch_b = patches; /* past the surface */
  CHECK(refused(&fx, &dl));
  strip.patch_b = 1;
  levels[1] = -1; /* a culled patch has no polyline */
  CHECK(refused(&fx, &dl));
  levels[1] = 0;
  dl.strips = NULL;
  CHECK(refused(&fx, &dl));
  dl.strip_count = 0;
  dl.instance_count = 3; /* instances NULL */
  CHECK(refused(&fx, &dl));
  free(levels);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

TEST(test_allocations_balanced) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  CHECK(ctx);
  shape cube = shape_cube_soft();
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &cube, TLOD_SURFACE_PN));
  int8_t* levels = random_levels(tlod_surface_patch_count(fx.surf), 31, 4);
  for (int mode = 0; mode < 2; ++mode) {
    tlod_cpu_mesh* m = tessellate(&fx, 0, levels, mode == 1, false);
    CHECK(m);
    CHECK(m->strips > 0);
    tlod_cpu_mesh_destroy(ctx, m);
  }
  free(levels);
  fixture_free(&fx);
  shape_free(&cube);
  tlod_context_destroy(ctx);
  printf("  %ld allocations, %ld frees\n", counter.allocs, counter.frees);
  CHECK(counter.allocs > 0);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees", counter.allocs, counter.frees);
}

/* Fails the k-th allocation of one tlod_cpu_tessellate call (and, with
 * fail_all, every one after it) for every k until the call succeeds. */
static void failing_sweep(uint32_t threads, bool fail_all, bool no_weld, const shape* s, tlod_surface_type type,
                          uint32_t* sweep_length) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(threads, &counter, NULL);
  CHECK(ctx);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, s, type));
  int8_t* levels = random_levels(tlod_surface_patch_count(fx.surf), 37, 4);
  bool done = false;
  uint32_t k = 0;
  for (; k < 10000 && !done; ++k) {
    long live_before = counter.allocs - counter.frees;
    counter.fail_at = counter.calls + k;
    counter.fail_all = fail_all;
    counter.failed = 0;
    tlod_cpu_mesh* out = (tlod_cpu_mesh*)&fx;
    tlod_result r = tlod_cpu_tessellate(ctx, fx.surf, fx.pat,
                                        &(tlod_cpu_tessellate_desc){.levels = levels, .no_weld = no_weld}, &out);
    long failed = counter.failed;
    counter.fail_at = -1;
    if (r == TLOD_SUCCESS) {
      CHECK(out && out->triangle_count > 0);
      tlod_cpu_mesh_destroy(ctx, out);
      /* success is only allowed once no allocation failed */
      CHECK_MSG(failed == 0, "k = %u: success although %ld allocations failed", k, failed);
      done = true;
    } else {
      CHECK_MSG(r == TLOD_ERROR_OUT_OF_MEMORY, "k = %u: %s", k, tlod_result_string(r));
      CHECK_MSG(out == NULL, "k = %u: *out not cleared", k);
    }
    CHECK_MSG(counter.allocs - counter.frees == live_before, "k = %u: %ld allocations leaked", k,
              counter.allocs - counter.frees - live_before);
  }
  CHECK(done);
  *sweep_length = k;
  free(levels);
  fixture_free(&fx);
  tlod_context_destroy(ctx);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees", counter.allocs, counter.frees);
}

TEST(test_failing_allocator) {
  shape cube = shape_cube_soft(), sph = shape_icosphere(1);
  uint32_t n1 = 0, n2 = 0, n3 = 0, n4 = 0;
  CALL(failing_sweep(1, false, false, &cube, TLOD_SURFACE_PN, &n1));
  CALL(failing_sweep(1, true, true, &cube, TLOD_SURFACE_PHONG, &n2));
  CALL(failing_sweep(1, false, true, &sph, TLOD_SURFACE_PHONG, &n3));
  CALL(failing_sweep(2, true, false, &sph, TLOD_SURFACE_PN, &n4));
  printf("  failing allocator: %u, %u, %u, %u allocation points swept\n", n1, n2, n3, n4);
  CHECK(n1 > 1 && n2 > 1 && n3 > 1 && n4 > 1);
  shape_free(&cube);
  shape_free(&sph);
}

int main(void) {
  RUN(test_uniform_counts);
  RUN(test_watertight);
  RUN(test_watertight_checker_detects_cracks);
  RUN(test_shared_edge_polylines);
  RUN(test_welded_matches_no_weld);
  RUN(test_thread_independence);
  RUN(test_no_normals);
  RUN(test_bad_api_use);
  RUN(test_bad_draw_list);
  RUN(test_allocations_balanced);
  RUN(test_failing_allocator);
  TEST_END();
}
