/*
 * lod_scheduler_test.c -- independent verification of the view-dependent LOD
 * scheduler (tesslod/lod.h: tlod_scheduler_*, tlod_draw_list) and of the CPU
 * realisation of its draw lists (tesslod/cpu.h, desc.draw_list).
 * Owned by the verification tests. Reads private state: none (public API only).
 *
 * This work is based on: M. Schwarz, M. Staginski, M. Stamminger, GPU-based
 * rendering of PN triangle meshes with adaptive tessellation, VMV 2006
 * (sec. 3 screen-space metric, sec. 4 stitching, sec. 5 geomorphs);
 * T. Boubekeur, M. Alexa, Phong tessellation, SIGGRAPH Asia 2008 (silhouette
 * depth); docs/design.md (maths, invariants 3 and 4).
 *
 * References. Every expected value is computed here, in double precision,
 * from the public inputs only: the camera matrices built by test_camera.h
 * (column-major GL look-at, perspective and orthographic, stored as float),
 * tlod_surface_patch() (error bound, bounding sphere), the mesh's vertices
 * and tlod_surface_eval(). The library's own helpers (tlod_level_for_error,
 * tlod_projection_scale) are checked against the same references, never used
 * as one; the exception is tlod_patch_projection_scale(), the one projection
 * bound of lod.h, which the references use after test_projection_scale has
 * checked it against finite differences of the projection.
 *
 * Tolerances. e_max: relative 1e-5. A level may differ by one only when the
 * reference e_max lies within 1e-5 (relative) of a level threshold. Topology
 * is exact: no_weld output welded by bitwise equal positions. Geomorph
 * midpoints are compared bitwise. Screen error: see test_screen_error.
 */
#define TEST_POOL_CHUNK 5 /* the reverse parallel-for's chunks (test_context.h) */

#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"
#include "test_lod.h"

#define PAT_MAX 5 /* patterns built to this level */
#define DEG (SHAPES_PI / 180.0)

static double now_seconds(void) {
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ------------------------------------------------------------------------ */
/* Fixture: mesh, surface, patterns and a copy of the per-patch data        */
/* ------------------------------------------------------------------------ */

typedef struct fixture {
  tlod_context* ctx;
  const shape* s;
  tlod_surface_type type;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
  uint32_t patches, vertices;
  tlod_patch_info* info;     /* per patch */
  uint32_t (*corner)[4];     /* per patch */
  uint8_t* ncorner;          /* per patch: 3 or 4 */
  tlod_edge_link (*link)[4]; /* per patch edge */
  double (*vpos)[3];         /* per mesh vertex (validated) */
  double (*vnrm)[3];         /* per mesh vertex (unit) */
  tlod_cpu_mesh* out;        /* realisation, reused */
  uint32_t* base;            /* no_weld block of each patch in `out` */
} fixture;

static tlod_pattern_shape shape_of(const fixture* fx, uint32_t p) {
  return fx->ncorner[p] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
}

/* Re-reads what the references use (after tlod_mesh_update / refresh). */
static void fixture_read(fixture* fx) {
  for (uint32_t p = 0; p < fx->patches; ++p) {
    fx->info[p] = tlod_surface_patch(fx->surf, p);
    fx->ncorner[p] = (uint8_t)tlod_mesh_face_corners(fx->mesh, p, fx->corner[p]);
    for (uint32_t e = 0; e < fx->ncorner[p]; ++e)
      fx->link[p][e] = tlod_mesh_edge_link(fx->mesh, p, e);
  }
  for (uint32_t v = 0; v < fx->vertices; ++v) {
    float pos[3], nrm[3];
    tlod_mesh_vertex(fx->mesh, v, pos, nrm);
    for (int c = 0; c < 3; ++c)
      fx->vpos[v][c] = pos[c], fx->vnrm[v][c] = nrm[c];
  }
}

static void fixture_free(fixture* fx) {
  if (fx->out) tlod_cpu_mesh_destroy(fx->ctx, fx->out);
  tlod_surface_destroy(fx->surf);
  tlod_mesh_destroy(fx->mesh);
  tlod_patterns_destroy(fx->pat);
  free(fx->info);
  free(fx->corner);
  free(fx->ncorner);
  free(fx->link);
  free(fx->vpos);
  free(fx->vnrm);
  free(fx->base);
  memset(fx, 0, sizeof *fx);
}

/* tables: the surface desc's error_tables (DEFAULT: the measured tables). */
static bool fixture_make_tables(fixture* fx, tlod_context* ctx, const shape* s, tlod_surface_type type,
                                tlod_error_tables tables) {
  memset(fx, 0, sizeof *fx);
  fx->ctx = ctx;
  fx->s = s;
  fx->type = type;
  tlod_mesh_desc md = shape_mesh_desc(s);
  tlod_result r = tlod_mesh_create(ctx, &md, &fx->mesh);
  if (r == TLOD_SUCCESS)
    r = tlod_surface_create(ctx, fx->mesh, &(tlod_surface_desc){.type = type, .error_tables = tables}, &fx->surf);
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = PAT_MAX}, &fx->pat);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "fixture %s %s: %s: %s\n", s->name, type_name(type), tlod_result_string(r),
            tlod_context_last_error(ctx));
    fixture_free(fx);
    return false;
  }
  fx->patches = tlod_surface_patch_count(fx->surf);
  fx->vertices = tlod_mesh_vertex_count(fx->mesh);
  fx->info = calloc(fx->patches + 1, sizeof *fx->info);
  fx->corner = calloc(fx->patches + 1, sizeof *fx->corner);
  fx->ncorner = calloc(fx->patches + 1, 1);
  fx->link = calloc(fx->patches + 1, sizeof *fx->link);
  fx->vpos = calloc(fx->vertices + 1, sizeof *fx->vpos);
  fx->vnrm = calloc(fx->vertices + 1, sizeof *fx->vnrm);
  fx->base = calloc(fx->patches + 1, sizeof *fx->base);
  fixture_read(fx);
  return true;
}

static bool fixture_make(fixture* fx, tlod_context* ctx, const shape* s, tlod_surface_type type) {
  return fixture_make_tables(fx, ctx, s, type, TLOD_ERROR_TABLES_DEFAULT);
}

static tlod_scheduler* new_scheduler(const fixture* fx, tlod_scheduler_desc d) {
  return scheduler_create(fx->ctx, fx->surf, fx->pat, d);
}

/* One frame; NULL on failure (reported). */
static const tlod_draw_list* plan(const fixture* fx, tlod_scheduler* s, const tlod_view_desc* views, uint32_t count,
                                  float dt_ms, float measured_ms) {
  tlod_frame_desc f = {.views = views, .view_count = count, .dt_ms = dt_ms, .measured_frame_ms = measured_ms};
  return scheduler_plan(fx->ctx, s, &f);
}

/* Realises a draw list with no_weld (every patch its own pattern vertices,
 * as a GPU draws them) into fx->out, and fx->base[p] = the first output
 * vertex of patch p's block. */
static bool realise(fixture* fx, const tlod_draw_list* dl, bool no_stitch) {
  tlod_cpu_tessellate_desc d = {.draw_list = dl, .no_weld = true, .no_stitch = no_stitch, .no_normals = true};
  tlod_result r = fx->out ? tlod_cpu_tessellate_into(fx->ctx, fx->surf, fx->pat, &d, fx->out)
                          : tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &d, &fx->out);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_cpu_tessellate(draw_list): %s: %s\n", tlod_result_string(r),
            tlod_context_last_error(fx->ctx));
    return false;
  }
  uint32_t b = 0;
  for (uint32_t p = 0; p < fx->patches; ++p) {
    fx->base[p] = b;
    if (dl->levels[p] >= 0) b += tlod_pattern_vertex_count(shape_of(fx, p), (uint32_t)dl->levels[p]);
  }
  fx->base[fx->patches] = b;
  if (fx->out->vertex_count != b) {
    fprintf(stderr, "no_weld output has %u vertices, the draw list's patterns %u\n", fx->out->vertex_count, b);
    return false;
  }
  /* the block layout: each block starts with the patch's corners */
  for (uint32_t p = 0; p < fx->patches; ++p) {
    if (dl->levels[p] < 0) continue;
    for (uint32_t c = 0; c < fx->ncorner[p]; ++c) {
      const float* q = fx->out->positions + 3 * (size_t)(fx->base[p] + c);
      const double* v = fx->vpos[fx->corner[p][c]];
      if (q[0] != (float)v[0] || q[1] != (float)v[1] || q[2] != (float)v[2]) {
        fprintf(stderr, "no_weld block of patch %u does not start with its corners\n", p);
        return false;
      }
    }
  }
  return true;
}

/* ------------------------------------------------------------------------ */
/* Cameras (test_camera.h: double precision, stored as float)               */
/* ------------------------------------------------------------------------ */

static camera look_from(double ex, double ey, double ez, double tx, double ty, double tz) {
  camera c = {.eye = {ex, ey, ez},
              .target = {tx, ty, tz},
              .up = {0, 1, 0},
              .fovy = 60 * DEG,
              .aspect = 4.0 / 3.0,
              .znear = 0.05,
              .zfar = 200,
              .width = 800,
              .height = 600};
  double f[3] = {tx - ex, ty - ey, tz - ez}, s[3];
  cross3(f, c.up, s);
  if (len3(s) < 1e-6 * len3(f)) c.up[0] = 1, c.up[1] = 0;
  return c;
}

/* Kinds: 0 near, 1 far, 2 grazing, 3 inside the bounding box, 4 medium.
 * R: the shape's bounding radius about the origin. */
static camera random_camera(shape_rng* r, double R, int kind, bool ortho) {
  camera c;
  memset(&c, 0, sizeof c);
  double dir[3], off[3];
  shape_rng_direction(r, dir);
  shape_rng_direction(r, off);
  double dist = 0;
  switch (kind) {
  case 0: /* near: just off the surface, looking at a point of it */
    dist = R * shape_rng_range(r, 1.05, 2.0);
    for (int k = 0; k < 3; ++k)
      c.eye[k] = dir[k] * dist, c.target[k] = off[k] * 0.6 * R;
    break;
  case 1: /* far */
    dist = R * shape_rng_range(r, 6.0, 40.0);
    for (int k = 0; k < 3; ++k)
      c.eye[k] = dir[k] * dist, c.target[k] = off[k] * 0.3 * R;
    break;
  case 2: { /* grazing: looking at a point near the silhouette rim */
    dist = R * shape_rng_range(r, 1.1, 3.0);
    double t[3];
    cross3(dir, off, t);
    shape_normalize3(t);
    double a = shape_rng_range(r, 0.8, 1.05), b = shape_rng_range(r, -0.3, 0.3);
    for (int k = 0; k < 3; ++k)
      c.eye[k] = dir[k] * dist, c.target[k] = t[k] * a * R + dir[k] * b * R;
    break;
  }
  case 3: /* inside the bounding box, any direction */
    dist = R;
    for (int k = 0; k < 3; ++k) {
      c.eye[k] = shape_rng_range(r, -R, R);
      c.target[k] = c.eye[k] + off[k];
    }
    break;
  default: /* medium */
    dist = R * shape_rng_range(r, 2.0, 6.0);
    for (int k = 0; k < 3; ++k)
      c.eye[k] = dir[k] * dist, c.target[k] = off[k] * 0.3 * R;
    break;
  }
  for (;;) {
    shape_rng_direction(r, c.up);
    double f[3] = {c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]}, s[3];
    cross3(f, c.up, s);
    if (len3(s) > 0.2 * len3(f)) break;
  }
  c.ortho = ortho;
  c.fovy = shape_rng_range(r, 25, 100) * DEG;
  c.aspect = shape_rng_range(r, 0.6, 2.0);
  c.half_h = R * shape_rng_range(r, 0.3, 1.5);
  c.znear = R * shape_rng_range(r, 0.01, 0.2);
  c.zfar = dist + R * shape_rng_range(r, 3.0, 50.0);
  c.width = 320 + (uint32_t)(shape_rng_next(r) % 1600);
  c.height = (uint32_t)fmax(64.0, floor(c.width / c.aspect));
  return c;
}

/* ------------------------------------------------------------------------ */
/* References                                                               */
/* ------------------------------------------------------------------------ */

typedef struct view_ref {
  double V[16], P[16], M[16]; /* from the float matrices; M = P V */
  double planes[6][4];        /* unit normals, inside >= 0 */
  double eye[3];
  double pix; /* viewport_height / 2 * proj[5]: f (perspective) or pixels per unit (ortho) */
  double znear;
  bool ortho;
  double width, height;
} view_ref;

static view_ref make_ref(const tlod_view_desc* v, const camera* c) {
  view_ref r;
  memset(&r, 0, sizeof r);
  for (int k = 0; k < 16; ++k)
    r.V[k] = v->view[k], r.P[k] = v->proj[k];
  mat4_mul(r.P, r.V, r.M);
  /* Gribb & Hartmann: row3 +- row0 / row1 / row2 */
  for (int pl = 0; pl < 6; ++pl) {
    int axis = pl / 2;
    double sign = pl % 2 ? -1.0 : 1.0, l = 0;
    for (int k = 0; k < 4; ++k)
      r.planes[pl][k] = r.M[4 * k + 3] + sign * r.M[4 * k + axis];
    l = sqrt(r.planes[pl][0] * r.planes[pl][0] + r.planes[pl][1] * r.planes[pl][1] + r.planes[pl][2] * r.planes[pl][2]);
    for (int k = 0; k < 4; ++k)
      r.planes[pl][k] /= l;
  }
  for (int k = 0; k < 3; ++k)
    r.eye[k] = -(r.V[4 * k + 0] * r.V[12] + r.V[4 * k + 1] * r.V[13] + r.V[4 * k + 2] * r.V[14]);
  r.pix = v->viewport_height / 2.0 * r.P[5];
  r.znear = c->znear;
  r.ortho = c->ortho;
  r.width = v->viewport_width;
  r.height = v->viewport_height;
  return r;
}

/* View depth (distance in front of the camera along -z). */
static double ref_depth(const view_ref* r, const float c[3]) {
  return -(r->V[2] * c[0] + r->V[6] * c[1] + r->V[10] * c[2] + r->V[14]);
}

/* Pixels per world unit over the patch's sphere: the library's
 * tlod_patch_projection_scale() (checked against finite differences of the
 * projection in test_projection_scale), on the float matrices r holds. */
static double ref_scale(const view_ref* r, const tlod_patch_info* in) {
  tlod_view_desc v = {.viewport_width = (uint32_t)r->width, .viewport_height = (uint32_t)r->height};
  for (int k = 0; k < 16; ++k)
    v.view[k] = (float)r->V[k], v.proj[k] = (float)r->P[k];
  return tlod_patch_projection_scale(&v, in->center, in->radius);
}

/* e_max = the level-0 table bound times the projection scale. */
static double ref_emax(const view_ref* r, const tlod_patch_info* in) {
  return (double)tlod_patch_error_bound(in, 0) * ref_scale(r, in);
}

/* 1: the sphere is fully outside a frustum plane (must be culled);
 * 0: a point of the sphere lies inside the frustum (must be kept);
 * -1: neither shown (outside near a frustum edge or corner: either is fine). */
static int ref_cull(const view_ref* r, const float cf[3], double radius) {
  double c[3] = {cf[0], cf[1], cf[2]};
  double scale = 1e-6 * (1.0 + len3(c) + radius);
  bool inside = true;
  for (int pl = 0; pl < 6; ++pl) {
    double d = dot3(r->planes[pl], c) + r->planes[pl][3];
    if (d < -radius - scale) return 1;
    if (d < 0) inside = false;
  }
  if (inside) return 0;
  /* Dykstra's alternating projections onto the six half-spaces: the point
   * of the frustum nearest to c; a witness inside the sphere means kept. */
  double x[3] = {c[0], c[1], c[2]}, q[6][3] = {{0}};
  for (int it = 0; it < 400; ++it)
    for (int pl = 0; pl < 6; ++pl) {
      double y[3] = {x[0] + q[pl][0], x[1] + q[pl][1], x[2] + q[pl][2]};
      double d = dot3(r->planes[pl], y) + r->planes[pl][3];
      for (int k = 0; k < 3; ++k) {
        double yp = d < 0 ? y[k] - d * r->planes[pl][k] : y[k];
        q[pl][k] = y[k] - yp;
        x[k] = yp;
      }
    }
  for (int pl = 0; pl < 6; ++pl)
    if (dot3(r->planes[pl], x) + r->planes[pl][3] < -scale) return -1;
  double dx[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  return len3(dx) < radius * (1 - 1e-4) - scale ? 0 : -1;
}

/* The level rule: 0 when e <= eps, else the smallest l with 4^-l e <= eps,
 * at most lmax. *ambiguous: e lies within 1e-5 (relative) of a threshold. */
static int ref_level(double e, double eps, int lmax, bool* ambiguous) {
  *ambiguous = false;
  for (int k = 0; k <= lmax; ++k) {
    double thr = ldexp(eps, 2 * k);
    if (fabs(e - thr) <= 1e-5 * thr) *ambiguous = true;
  }
  if (!(e > eps)) return 0;
  int l = 1;
  while (ldexp(e, -2 * l) > eps && l < lmax)
    l++;
  return l < lmax ? l : lmax;
}

/* d_i = (1 - |n_i . (c - p_i) / |c - p_i||) m (Boubekeur & Alexa). */
static double ref_vertex_depth(const fixture* fx, const view_ref* r, uint32_t v, double m) {
  double d[3] = {r->eye[0] - fx->vpos[v][0], r->eye[1] - fx->vpos[v][1], r->eye[2] - fx->vpos[v][2]};
  double l = len3(d);
  if (l == 0) return m;
  return (1.0 - fabs(dot3(fx->vnrm[v], d) / l)) * m;
}

/* Largest corner silhouette depth of a patch, in units of m (s in lod.h). */
static double ref_patch_s(const fixture* fx, const view_ref* r, uint32_t p) {
  double s = 0;
  for (uint32_t c = 0; c < fx->ncorner[p]; ++c)
    s = fmax(s, ref_vertex_depth(fx, r, fx->corner[p][c], 1.0));
  return s;
}

/* ------------------------------------------------------------------------ */
/* Draw-list consistency (structure, counts, strips)                        */
/* ------------------------------------------------------------------------ */

/* Whether (a, b) comes strictly after (c, d) in lexicographic order. */
static bool pair_after(uint32_t a, uint32_t b, uint32_t c, uint32_t d) { return a > c || (a == c && b > d); }

/* Levels in range, one instance per visible patch, buckets covering them,
 * statistics that add up, and strips exactly where two visible sides of an
 * edge would otherwise not meet: smooth edges with different levels, and
 * crease edges (split normals); a smooth edge with equal levels and no
 * strip must have equal edge morph values on both sides. */
static bool check_draw_list(const fixture* fx, const tlod_draw_list* dl, uint32_t lmax, char* why, size_t n) {
  bool ok = false;
  uint32_t* seen = calloc(fx->patches + 1, sizeof *seen);
  uint32_t* strips_at = calloc(4 * (size_t)fx->patches + 1, sizeof *strips_at);
  const tlod_draw_instance** inst = calloc(fx->patches + 1, sizeof *inst);
#define FAILF(...)                                                                                                     \
  do {                                                                                                                 \
    snprintf(why, n, __VA_ARGS__);                                                                                     \
    goto done;                                                                                                         \
  } while (0)
  if (dl->patch_count != fx->patches) FAILF("patch_count %u, surface %u", dl->patch_count, fx->patches);
  uint32_t visible = 0, culled = 0, hist[TLOD_MAX_LEVEL + 1] = {0};
  uint64_t tris = 0;
  float emin = FLT_MAX, emaxv = -FLT_MAX;
  for (uint32_t p = 0; p < fx->patches; ++p) {
    int l = dl->levels[p];
    if (l < -1 || l > (int)lmax) FAILF("patch %u: level %d outside [-1, %u]", p, l, lmax);
    if (l < 0) {
      culled++;
      continue;
    }
    visible++;
    hist[l]++;
    tris += tlod_pattern_triangle_count(shape_of(fx, p), (uint32_t)l);
    if (!isfinite(dl->e_max[p]) || dl->e_max[p] < 0) FAILF("patch %u: e_max %g", p, dl->e_max[p]);
    emin = fminf(emin, dl->e_max[p]);
    emaxv = fmaxf(emaxv, dl->e_max[p]);
  }
  if (culled != dl->culled) FAILF("culled %u, levels say %u", dl->culled, culled);
  for (int l = 0; l <= TLOD_MAX_LEVEL; ++l)
    if (hist[l] != dl->level_histogram[l])
      FAILF("level_histogram[%d] %u, levels say %u", l, dl->level_histogram[l], hist[l]);
  if (tris != dl->pattern_triangles)
    FAILF("pattern_triangles %llu, levels say %llu", (unsigned long long)dl->pattern_triangles,
          (unsigned long long)tris);
  if (visible && (emin != dl->e_max_min || emaxv != dl->e_max_max))
    FAILF("e_max_min/max %g/%g, visible e_max %g/%g", dl->e_max_min, dl->e_max_max, emin, emaxv);
  if (dl->instance_count != visible) FAILF("%u instances, %u visible patches", dl->instance_count, visible);
  for (uint32_t k = 0; k < dl->instance_count; ++k) {
    const tlod_draw_instance* in = &dl->instances[k];
    if (in->patch >= fx->patches) FAILF("instance %u: patch %u", k, in->patch);
    if (seen[in->patch]++) FAILF("patch %u has two instances", in->patch);
    if ((int)in->level != dl->levels[in->patch])
      FAILF("instance %u: level %u, levels[%u] = %d", k, in->level, in->patch, dl->levels[in->patch]);
    if (!(in->morph >= 0 && in->morph <= 1)) FAILF("patch %u: morph %g", in->patch, in->morph);
    inst[in->patch] = in;
  }
  uint32_t next = 0;
  for (uint32_t b = 0; b < dl->bucket_count; ++b) {
    const tlod_draw_bucket* bk = &dl->buckets[b];
    if (bk->first != next) FAILF("bucket %u starts at %u, expected %u", b, bk->first, next);
    if (!bk->count) FAILF("bucket %u is empty", b);
    if (b && !pair_after((uint32_t)bk->shape, bk->level, (uint32_t)bk[-1].shape, bk[-1].level))
      FAILF("bucket %u (shape %d level %u) after shape %d level %u", b, (int)bk->shape, bk->level, (int)bk[-1].shape,
            bk[-1].level);
    next = bk->first + bk->count;
    if (next > dl->instance_count) FAILF("bucket %u runs past the instances", b);
    for (uint32_t k = bk->first; k < next; ++k) {
      const tlod_draw_instance* in = &dl->instances[k];
      if (in->level != bk->level || shape_of(fx, in->patch) != bk->shape)
        FAILF("instance %u (patch %u level %u) in bucket %u (shape %d level %u)", k, in->patch, in->level, b,
              (int)bk->shape, bk->level);
      if (k > bk->first && in->patch <= in[-1].patch)
        FAILF("bucket %u: instance %u (patch %u) after patch %u", b, k, in->patch, in[-1].patch);
    }
  }
  if (next != dl->instance_count) FAILF("buckets cover %u of %u instances", next, dl->instance_count);
  uint64_t stris = 0;
  for (uint32_t k = 0; k < dl->strip_count; ++k) {
    const tlod_draw_strip* st = &dl->strips[k];
    if (st->patch_a >= fx->patches || st->patch_b >= fx->patches)
      FAILF("strip %u: patches %u, %u", k, st->patch_a, st->patch_b);
    if (st->patch_a >= st->patch_b) FAILF("strip %u: listed from patch %u, not below %u", k, st->patch_a, st->patch_b);
    if (k && !pair_after(st->patch_a, st->edge_a, st[-1].patch_a, st[-1].edge_a))
      FAILF("strip %u (patch %u edge %u) after patch %u edge %u", k, st->patch_a, st->edge_a, st[-1].patch_a,
            st[-1].edge_a);
    if (dl->levels[st->patch_a] < 0 || dl->levels[st->patch_b] < 0)
      FAILF("strip %u joins a culled patch (%u, %u)", k, st->patch_a, st->patch_b);
    if (st->edge_a >= fx->ncorner[st->patch_a] || st->edge_b >= fx->ncorner[st->patch_b]) FAILF("strip %u: edges", k);
    tlod_edge_link lk = fx->link[st->patch_a][st->edge_a];
    if (lk.face != st->patch_b || lk.edge != st->edge_b)
      FAILF("strip %u: patch %u edge %u is not next to patch %u edge %u", k, st->patch_a, st->edge_a, st->patch_b,
            st->edge_b);
    if ((int)st->level_a != dl->levels[st->patch_a] || (int)st->level_b != dl->levels[st->patch_b])
      FAILF("strip %u: levels %u/%u, patches at %d/%d", k, st->level_a, st->level_b, dl->levels[st->patch_a],
            dl->levels[st->patch_b]);
    if (st->crease != !lk.smooth)
      FAILF("strip %u: crease %d on a %s edge", k, st->crease, lk.smooth ? "smooth" : "crease");
    /* Exact: a smooth level difference whose coarser side is at rest (its
     * edge points are the finer side's); then the degenerate triangles go. */
    const tlod_draw_instance* coarse = inst[st->level_a < st->level_b ? st->patch_a : st->patch_b];
    bool exact = lk.smooth && st->level_a != st->level_b && coarse->morph == 1.0f;
    if (st->exact != exact) FAILF("strip %u: exact %d, expected %d", k, st->exact, exact);
    strips_at[4 * st->patch_a + st->edge_a]++;
    strips_at[4 * st->patch_b + st->edge_b]++;
    uint32_t c = 0;
    if (exact)
      tlod_patterns_connection_exact(fx->pat, st->level_a, st->level_b, &c);
    else
      tlod_patterns_connection(fx->pat, st->level_a, st->level_b, &c);
    stris += c;
  }
  if (stris != dl->strip_triangles)
    FAILF("strip_triangles %llu, the strips' connection patterns %llu", (unsigned long long)dl->strip_triangles,
          (unsigned long long)stris);
  for (uint32_t p = 0; p < fx->patches; ++p) {
    if (dl->levels[p] < 0) continue;
    for (uint32_t e = 0; e < fx->ncorner[p]; ++e) {
      tlod_edge_link lk = fx->link[p][e];
      uint32_t count = strips_at[4 * p + e];
      if (count > 1) FAILF("patch %u edge %u: %u strips", p, e, count);
      if (lk.face == UINT32_MAX || dl->levels[lk.face] < 0) {
        if (count) FAILF("patch %u edge %u: strip on a boundary or next to a culled patch", p, e);
        continue;
      }
      bool need = !lk.smooth || dl->levels[p] != dl->levels[lk.face];
      if (need && !count)
        FAILF("patch %u edge %u (level %d) meets patch %u (level %d) across a %s edge without a strip", p, e,
              dl->levels[p], lk.face, dl->levels[lk.face], lk.smooth ? "smooth" : "crease");
      if (!count && inst[p]->morph != inst[lk.face]->morph)
        FAILF("patch %u edge %u: edge morph %.9g, neighbour %u edge %u: %.9g, equal levels %d and no strip", p, e,
              inst[p]->morph, lk.face, lk.edge, inst[lk.face]->morph, dl->levels[p]);
    }
  }
  ok = true;
done:
#undef FAILF
  free(seen);
  free(strips_at);
  free(inst);
  return ok;
}

/* ------------------------------------------------------------------------ */
/* Realised topology                                                        */
/* ------------------------------------------------------------------------ */

/* Edges of the pattern (bit e) that vertex v lies on, N = 2^patterns max. */
static unsigned vertex_edges(tlod_pattern_shape sh, uint32_t N, const tlod_pattern_vertex* v) {
  if (sh == TLOD_PATTERN_TRIANGLE) return (v->i + v->j == N ? 1u : 0u) | (v->i == 0 ? 2u : 0u) | (v->j == 0 ? 4u : 0u);
  return (v->j == 0 ? 1u : 0u) | (v->i == N ? 2u : 0u) | (v->j == N ? 4u : 0u) | (v->i == 0 ? 8u : 0u);
}

/* With culling: the realised output welds into a manifold whose only open
 * edges lie on patch edges between a visible and a culled patch. */
static bool open_only_at_culled(const fixture* fx, const tlod_draw_list* dl, uint32_t* open_edges, char* why,
                                size_t n) {
  const tlod_cpu_mesh* m = fx->out;
  uint32_t cap = 3 * m->triangle_count + 1;
  uint32_t* list = malloc(sizeof *list * cap);
  shape_census c = shape_half_edge_census(m->positions, m->vertex_count, m->indices, m->triangle_count, list, cap);
  bool ok = c.degenerate == 0 && c.duplicated == 0;
  if (!ok) snprintf(why, n, "%u degenerate triangles, %u doubled directed edges", c.degenerate, c.duplicated);
  uint32_t N = 1u << tlod_patterns_max_level(fx->pat);
  for (uint32_t k = 0; k < c.open && ok; ++k) {
    uint32_t t = list[k] / 3, corner = list[k] % 3, p = m->triangle_patch[t];
    if (p == UINT32_MAX) {
      snprintf(why, n, "strip triangle %u has an open edge", t);
      ok = false;
      break;
    }
    uint32_t a = m->indices[3 * t + corner] - fx->base[p], b = m->indices[3 * t + (corner + 1) % 3] - fx->base[p];
    uint32_t count;
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(fx->pat, shape_of(fx, p), &count);
    unsigned common = vertex_edges(shape_of(fx, p), N, &pv[a]) & vertex_edges(shape_of(fx, p), N, &pv[b]);
    bool at_culled = false;
    for (uint32_t e = 0; e < fx->ncorner[p]; ++e)
      if (common >> e & 1) {
        tlod_edge_link lk = fx->link[p][e];
        at_culled = at_culled || (lk.face != UINT32_MAX && dl->levels[lk.face] < 0);
      }
    if (!at_culled) {
      snprintf(why, n, "open edge inside patch %u (pattern vertices %u-%u, edges %#x) or next to a visible patch", p, a,
               b, common);
      ok = false;
    }
  }
  *open_edges += c.open;
  free(list);
  return ok;
}

static bool realised_closed(const fixture* fx, char* why, size_t n) {
  const tlod_cpu_mesh* m = fx->out;
  return shape_closed_manifold(m->positions, m->vertex_count, m->indices, m->triangle_count, m->triangle_patch, why, n);
}

/* ------------------------------------------------------------------------ */
/* 0. Pure helpers against the reference                                    */
/* ------------------------------------------------------------------------ */

TEST(test_pure_helpers) {
  shape_rng rng = {11};
  uint32_t checked = 0, ambiguous = 0;
  for (int k = 0; k < 20000; ++k) {
    float eps = (float)exp(shape_rng_range(&rng, log(0.05), log(20.0)));
    float e = k % 10 == 0 ? eps * (float)ldexp(1.0, 2 * (int)(shape_rng_next(&rng) % 6)) /* on a threshold */
                          : (float)(eps * exp(shape_rng_range(&rng, -3.0, 9.0)));
    uint32_t lmax = (uint32_t)(shape_rng_next(&rng) % (TLOD_MAX_LEVEL + 1));
    bool amb;
    int want = ref_level(e, eps, (int)lmax, &amb);
    uint32_t got = tlod_level_for_error(e, eps, lmax);
    ambiguous += amb;
    CHECK_MSG(got == (uint32_t)want || (amb && abs((int)got - want) <= 1),
              "tlod_level_for_error(%.9g, %.9g, %u) = %u, reference %d", e, eps, lmax, got, want);
    checked++;
  }
  CHECK(tlod_level_for_error(0.0f, 1.0f, 5) == 0);
  CHECK(tlod_level_for_error(1.0f, 1.0f, 5) == 0);
  CHECK(tlod_level_for_error(4.0f, 1.0f, 5) == 1);
  CHECK(tlod_level_for_error(4.0001f, 1.0f, 5) == 2);
  CHECK(tlod_level_for_error(1e30f, 1.0f, 5) == 5);
  for (int k = 0; k < 200; ++k) {
    camera c = random_camera(&rng, 1.0, k % 5, k % 3 == 0);
    tlod_view_desc v = make_view(&c);
    view_ref r = make_ref(&v, &c);
    double depth = shape_rng_range(&rng, 0.01, 100.0);
    double want = r.ortho ? r.pix : r.pix / depth;
    float got = tlod_projection_scale(v.proj, v.viewport_height, (float)depth);
    CHECK_MSG(fabs(got - want) <= 1e-6 * want, "tlod_projection_scale(%s, %u, %g) = %.9g, reference %.9g",
              r.ortho ? "ortho" : "perspective", v.viewport_height, depth, got, want);
  }
  printf("  %u level rules checked (%u within 1e-5 of a threshold)\n", checked, ambiguous);
}

/* ------------------------------------------------------------------------ */
/* 1. Level choice and culling against the reference                       */
/* ------------------------------------------------------------------------ */

typedef struct ref_stats {
  uint32_t patches, culled, kept, edge_zone, ambiguous, policy_checked;
  double worst_rel;
} ref_stats;

/* The level rule on the per-level tables: the smallest l <= lmax with
 * tlod_patch_error_bound(in, l) * scale <= eps. *ambiguous: a rung lies
 * within 1e-5 (relative) of eps. */
static int ref_table_level(const tlod_patch_info* in, double scale, double eps, int lmax, bool* ambiguous) {
  *ambiguous = false;
  int want = -1;
  for (int l = 0; l <= lmax; ++l) {
    double b = (double)tlod_patch_error_bound(in, (uint32_t)l) * scale;
    if (fabs(b - eps) <= 1e-5 * eps) *ambiguous = true;
    if (want < 0 && b <= eps) want = l;
  }
  return want < 0 ? lmax : want;
}

/* Every patch of one draw list against the reference: structure, culling,
 * e_max, and (ERROR policy) the level rule. */
static void check_levels(const fixture* fx, const tlod_draw_list* dl, const view_ref* r, tlod_lod_policy policy,
                         double eps, int lmax, bool no_cull, const char* what, ref_stats* st) {
  char why[256];
  CHECK_MSG(check_draw_list(fx, dl, (uint32_t)lmax, why, sizeof why), "%s: %s", what, why);
  CHECK_MSG(dl->effective_epsilon == (float)eps, "%s: effective_epsilon %.9g without budget, epsilon %.9g", what,
            dl->effective_epsilon, eps);
  if (no_cull) CHECK_MSG(dl->culled == 0, "%s: no_frustum_cull, %u culled", what, dl->culled);
  for (uint32_t p = 0; p < fx->patches; ++p) {
    const tlod_patch_info* in = &fx->info[p];
    int level = dl->levels[p];
    if (!no_cull) {
      int cull = ref_cull(r, in->center, in->radius);
      st->edge_zone += cull < 0;
      if (cull == 1) {
        CHECK_MSG(level == -1, "%s: patch %u (sphere %.4g %.4g %.4g r %.4g) is outside a frustum plane, level %d", what,
                  p, in->center[0], in->center[1], in->center[2], in->radius, level);
        st->culled++;
      } else if (cull == 0) {
        CHECK_MSG(level >= 0, "%s: patch %u meets the frustum but was culled", what, p);
        st->kept++;
      }
    }
    if (level < 0) continue;
    st->patches++;
    double e = ref_emax(r, in);
    double rel = fabs(dl->e_max[p] - e) / fmax(e, 1e-30);
    if (e == 0) rel = dl->e_max[p] == 0 ? 0 : 1;
    st->worst_rel = fmax(st->worst_rel, rel);
    CHECK_MSG(rel <= 1e-5, "%s: patch %u e_max %.9g, reference %.9g (level-0 bound %.6g, depth %.6g, radius %.6g)",
              what, p, dl->e_max[p], e, in->error_table[0], ref_depth(r, in->center), in->radius);
    if (policy != TLOD_POLICY_ERROR) continue; /* other policies: test_policy_rules */
    bool amb = false;
    int want = ref_table_level(in, ref_scale(r, in), eps, lmax, &amb);
    st->ambiguous += amb;
    st->policy_checked++;
    CHECK_MSG(level == want || (amb && abs(level - want) <= 1), "%s: patch %u level %d, reference %d (e_max %.9g)",
              what, p, level, want, e);
  }
}

TEST(test_level_choice) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[3] = {shape_icosphere(2), shape_torus(12, 8), shape_quad_sphere(2)};
  const double radius[3] = {1.0, 1.4, 1.0};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  const tlod_lod_policy policies[3] = {TLOD_POLICY_ERROR, TLOD_POLICY_HYBRID, TLOD_POLICY_SILHOUETTE};
  const char* pnames[3] = {"error", "hybrid", "silhouette"};
  ref_stats st = {0};
  uint32_t frames = 0, run = 0;
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti, ++run) {
      if (shapes[si].corners == 4 && types[ti] == TLOD_SURFACE_PN) continue;
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &shapes[si], types[ti]));
      int lmax = run % 2 ? 4 : PAT_MAX; /* 4: the desc's max_level clamps below the patterns' */
      double eps = run % 3 == 0 ? 0.5 : run % 3 == 1 ? 1.0 : 2.0;
      tlod_scheduler* sch[4];
      for (int k = 0; k < 4; ++k) {
        tlod_scheduler_desc d = {.epsilon_px = (float)eps,
                                 .max_level = run % 2 ? 4u : 0u,
                                 .policy = policies[k % 3],
                                 .morph = TLOD_MORPH_NONE,
                                 .no_frustum_cull = k == 3};
        sch[k] = new_scheduler(&fx, d);
        CHECK(sch[k]);
      }
      shape_rng rng = {100 + (uint64_t)run};
      for (int cam = 0; cam < 40; ++cam) {
        camera c = random_camera(&rng, radius[si], cam % 5, cam % 4 == 3);
        tlod_view_desc v = make_view(&c);
        view_ref r = make_ref(&v, &c);
        for (int k = 0; k < 4; ++k) {
          const tlod_draw_list* dl = plan(&fx, sch[k], &v, 1, 16.0f, 0.0f);
          CHECK(dl);
          char what[160];
          snprintf(what, sizeof what, "%s %s %s%s camera %d (%s, kind %d)", shapes[si].name, type_name(types[ti]),
                   pnames[k % 3], k == 3 ? " no_frustum_cull" : "", cam, c.ortho ? "ortho" : "perspective", cam % 5);
          CALL(check_levels(&fx, dl, &r, policies[k % 3], eps, lmax, k == 3, what, &st));
          frames++;
        }
      }
      for (int k = 0; k < 4; ++k)
        tlod_scheduler_destroy(sch[k]);
      fixture_free(&fx);
    }
  printf("  %u frames, %u visible patches: worst e_max relative error %.2g; culling: %u must-cull and %u must-keep "
         "patches confirmed, %u near a frustum edge (either); %u error-policy levels checked (%u within 1e-5 of a "
         "threshold)\n",
         frames, st.patches, st.worst_rel, st.culled, st.kept, st.edge_zone, st.policy_checked, st.ambiguous);
  CHECK(st.culled > 100 && st.kept > 1000);
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 1b. HYBRID and SILHOUETTE against the rules lod.h documents              */
/* ------------------------------------------------------------------------ */

/* lod.h: d_i = (1 - |n.v|) m, m = silhouette_depth (segments per edge,
 * "0 == 2^max_level"); SILHOUETTE: l = ceil(log2(max d_i)) over the patch's
 * corners, 0 when max d_i <= 1; HYBRID: eps_p = eps relax^(1 - s), s = max
 * d_i / m over the corners, s = 1 where the corner normals face both towards
 * and away from the camera. Perspective cameras (the eye defines v).
 * Mismatches are counted per rule and reported together. */
TEST(test_policy_rules) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(2);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  const int lmax = 4;
  const double m_explicit = 6.0, eps = 1.0;
  tlod_scheduler* hyb = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = (float)eps,
                                                                 .max_level = lmax,
                                                                 .policy = TLOD_POLICY_HYBRID,
                                                                 .morph = TLOD_MORPH_NONE,
                                                                 .silhouette_depth = (float)m_explicit,
                                                                 .no_frustum_cull = true});
  tlod_scheduler* sil = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = (float)eps,
                                                                 .max_level = lmax,
                                                                 .policy = TLOD_POLICY_SILHOUETTE,
                                                                 .morph = TLOD_MORPH_NONE,
                                                                 .no_frustum_cull = true});
  tlod_scheduler* def = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = lmax, .no_frustum_cull = true});
  CHECK(hyb && sil && def);
  tlod_scheduler_desc dd = tlod_scheduler_query_desc(def);
  printf("  resolved defaults: epsilon %g, policy %d, morph %d, morph_ms %g, hybrid_relax %g, silhouette_depth %g "
         "(max_level %u)\n",
         dd.epsilon_px, (int)dd.policy, (int)dd.morph, dd.morph_ms, dd.hybrid_relax, dd.silhouette_depth, dd.max_level);
  CHECK(dd.epsilon_px == 0.5f && dd.policy == TLOD_POLICY_HYBRID && dd.morph == TLOD_MORPH_TIME &&
        dd.morph_ms == 200.0f && dd.hybrid_relax == 16.0f && dd.max_level == (uint32_t)lmax);
  CHECK_MSG(dd.silhouette_depth == (float)(1 << lmax), "silhouette_depth 0 resolves to %g, lod.h: 2^max_level",
            dd.silhouette_depth);
  const double m_default = 1 << lmax;
  uint32_t depth_bad = 0, sil_bad = 0, hyb_bad = 0, checked = 0, straddling = 0, ambiguous = 0;
  double worst_depth = 0;
  shape_rng rng = {77};
  char first_sil[200] = "", first_hyb[200] = "";
  for (int cam = 0; cam < 30; ++cam) {
    camera c = random_camera(&rng, 1.0, cam % 5 == 3 ? 4 : cam % 5, false);
    tlod_view_desc v = make_view(&c);
    view_ref r = make_ref(&v, &c);
    const tlod_draw_list* dh = plan(&fx, hyb, &v, 1, 16, 0);
    CHECK(dh);
    char why[256];
    CHECK_MSG(check_draw_list(&fx, dh, lmax, why, sizeof why), "hybrid: %s", why);
    for (uint32_t vx = 0; vx < fx.vertices; ++vx) {
      double want = ref_vertex_depth(&fx, &r, vx, m_explicit);
      double err = fabs(dh->vertex_depth[vx] - want);
      worst_depth = fmax(worst_depth, err);
      depth_bad += err > 1e-4 * m_explicit;
    }
    for (uint32_t p = 0; p < fx.patches; ++p) {
      double s = ref_patch_s(&fx, &r, p);
      bool front = false, back = false, tie = false;
      for (uint32_t k = 0; k < fx.ncorner[p]; ++k) {
        const double* q = fx.vpos[fx.corner[p][k]];
        double d[3] = {r.eye[0] - q[0], r.eye[1] - q[1], r.eye[2] - q[2]};
        double f = dot3(fx.vnrm[fx.corner[p][k]], d) / len3(d);
        front = front || f > 0, back = back || f <= 0, tie = tie || fabs(f) < 1e-5;
      }
      if (front && back) s = 1, straddling++;
      bool amb;
      int want = ref_table_level(&fx.info[p], ref_scale(&r, &fx.info[p]), eps * pow(16.0, 1.0 - s), lmax, &amb);
      amb = amb || tie;
      ambiguous += amb;
      if (!(dh->levels[p] == want || (amb && abs(dh->levels[p] - want) <= 1))) {
        hyb_bad++;
        if (!first_hyb[0])
          snprintf(first_hyb, sizeof first_hyb, "camera %d patch %u: level %d, reference %d (s = %.4f%s)", cam, p,
                   dh->levels[p], want, s, front && back ? ", straddles the contour" : "");
      }
    }
    const tlod_draw_list* ds = plan(&fx, sil, &v, 1, 16, 0);
    CHECK(ds);
    CHECK_MSG(check_draw_list(&fx, ds, lmax, why, sizeof why), "silhouette: %s", why);
    for (uint32_t p = 0; p < fx.patches; ++p) {
      double d = ref_patch_s(&fx, &r, p) * m_default;
      double lg = d > 1 ? log2(d) : 0;
      int want = (int)fmin(ceil(lg), lmax);
      bool amb = fabs(lg - floor(lg + 0.5)) <= 1e-5 * (1 + lg);
      ambiguous += amb;
      if (!(ds->levels[p] == want || (amb && abs(ds->levels[p] - want) <= 1))) {
        sil_bad++;
        if (!first_sil[0])
          snprintf(first_sil, sizeof first_sil, "camera %d patch %u: level %d, ceil(log2(max d_i)) = %d (max d_i %.4f)",
                   cam, p, ds->levels[p], want, d);
      }
      checked++;
    }
  }
  printf("  %u patches x 2 policies (%u straddling the contour, %u within 1e-5 of a threshold); vertex depth "
         "(m = %g): worst error %.2g\n",
         checked, straddling, ambiguous, m_explicit, worst_depth);
  tlod_scheduler_destroy(hyb);
  tlod_scheduler_destroy(sil);
  tlod_scheduler_destroy(def);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
  CHECK_MSG(depth_bad == 0, "%u vertex depths differ from (1 - |n.v|) m", depth_bad);
  CHECK_MSG(sil_bad == 0, "%u SILHOUETTE levels differ from l = ceil(log2(max d_i)); first: %s", sil_bad, first_sil);
  CHECK_MSG(hyb_bad == 0, "%u HYBRID levels differ from eps_p = eps relax^(1 - s); first: %s", hyb_bad, first_hyb);
  CHECK(straddling > 0);
}

/* ------------------------------------------------------------------------ */
/* 2. Crack-free realisation of random frames                               */
/* ------------------------------------------------------------------------ */

typedef struct crack_stats {
  uint32_t frames, fractional_frames, strips, nostitch_runs, nostitch_open, culled_frames, open_edges;
  double seconds;
} crack_stats;

/* Random cameras (near, far, grazing, inside the bounding box, medium;
 * every sixth orthographic) on one surface. Schedulers: ERROR and HYBRID,
 * each with morph NONE and TIME (random dt, so blends are fractional), all
 * with no_frustum_cull: every realised frame must weld into a closed
 * manifold. A fifth (HYBRID, culling) frame may only be open where a
 * visible patch meets a culled one. Every other camera the ERROR frame is
 * also realised with no_stitch, which must open somewhere. */
static void crack_suite(tlod_context* ctx, const shape* s, double R, uint32_t lmax, tlod_surface_type type, int cameras,
                        uint64_t seed, crack_stats* st) {
  double t0 = now_seconds();
  fixture fx;
  CHECK(fixture_make(&fx, ctx, s, type));
  tlod_scheduler* sch[5];
  for (int k = 0; k < 5; ++k) {
    tlod_scheduler_desc d = {.epsilon_px = k % 2 ? 0.75f : 1.0f,
                             .max_level = lmax,
                             .policy = k % 2 ? TLOD_POLICY_HYBRID : TLOD_POLICY_ERROR,
                             .morph = k >= 2 && k < 4 ? TLOD_MORPH_TIME : TLOD_MORPH_NONE,
                             .morph_ms = 120,
                             .no_frustum_cull = k < 4};
    sch[k] = new_scheduler(&fx, d);
    CHECK(sch[k]);
  }
  static const char* names[5] = {"error/none", "hybrid/none", "error/time", "hybrid/time", "hybrid/culled"};
  shape_rng rng = {seed};
  for (int cam = 0; cam < cameras; ++cam) {
    camera c = random_camera(&rng, R, cam % 5, cam % 6 == 5);
    tlod_view_desc v = make_view(&c);
    float dt = (float)shape_rng_range(&rng, 0.0, 40.0);
    for (int k = 0; k < 5; ++k) {
      const tlod_draw_list* dl = plan(&fx, sch[k], &v, 1, dt, 0);
      CHECK(dl);
      char why[256] = "";
      CHECK_MSG(check_draw_list(&fx, dl, lmax, why, sizeof why), "%s %s %s camera %d: %s", s->name, type_name(type),
                names[k], cam, why);
      if (k < 4) {
        bool frac = false;
        for (uint32_t i = 0; i < dl->instance_count; ++i)
          frac = frac || (dl->instances[i].level > 0 && dl->instances[i].morph < 1.0f);
        st->fractional_frames += frac && k == cam % 4;
        if (k == 0 && cam % 4 == 2) {
          CHECK(realise(&fx, dl, true));
          st->nostitch_runs++;
          st->nostitch_open += !realised_closed(&fx, why, sizeof why);
        }
        if (k != cam % 4) continue; /* each camera realises one of the four */
        CHECK_MSG(realise(&fx, dl, false), "%s %s %s camera %d", s->name, type_name(type), names[k], cam);
        bool closed = realised_closed(&fx, why, sizeof why);
        CHECK_MSG(closed, "%s %s %s camera %d (kind %d, %s): not closed: %s (%u strips)", s->name, type_name(type),
                  names[k], cam, cam % 5, c.ortho ? "ortho" : "perspective", why, dl->strip_count);
        st->frames++;
        st->strips += dl->strip_count;
      } else if (cam % 3 == 0) {
        CHECK_MSG(realise(&fx, dl, false), "%s %s %s camera %d", s->name, type_name(type), names[k], cam);
        CHECK_MSG(open_only_at_culled(&fx, dl, &st->open_edges, why, sizeof why), "%s %s culled camera %d: %s", s->name,
                  type_name(type), cam, why);
        st->culled_frames += dl->culled > 0 && dl->culled < fx.patches;
      }
    }
  }
  for (int k = 0; k < 5; ++k)
    tlod_scheduler_destroy(sch[k]);
  fixture_free(&fx);
  st->seconds += now_seconds() - t0;
}

TEST(test_crack_free) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  shape shapes[4] = {shape_icosphere(1), shape_torus(12, 8), shape_cube_soft(), shape_quad_sphere(2)};
  const double R[4] = {1.0, 1.4, 0.87, 1.0};
  const uint32_t lmax[4] = {4, 3, 5, 4}; /* about 20k triangles at most */
  const int cameras = 200;
  for (int si = 0; si < 4; ++si) {
    crack_stats st = {0};
    for (int ti = 0; ti < 2; ++ti) {
      tlod_surface_type type = ti ? TLOD_SURFACE_PN : TLOD_SURFACE_PHONG;
      if (shapes[si].corners == 4 && type == TLOD_SURFACE_PN) continue;
      CALL(crack_suite(ctx, &shapes[si], R[si], lmax[si], type, cameras, 1000 + 17 * (uint64_t)si + (uint64_t)ti, &st));
    }
    printf("  %-11s %u closed frames (%u with fractional blends, %u strips), no_stitch open in %u of %u, %u culled "
           "frames open only at culled neighbours (%u open edges), %.1f s\n",
           shapes[si].name, st.frames, st.fractional_frames, st.strips, st.nostitch_open, st.nostitch_runs,
           st.culled_frames, st.open_edges, st.seconds);
    CHECK_MSG(st.nostitch_open > 0, "%s: no_stitch never opened the mesh: the checker would miss cracks",
              shapes[si].name);
    CHECK_MSG(st.fractional_frames > 0, "%s: no frame had a fractional blend", shapes[si].name);
    CHECK_MSG(st.culled_frames > 0 && st.open_edges > 0, "%s: culling never opened the mesh", shapes[si].name);
  }
  for (int k = 0; k < 4; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 3. Creases at equal levels                                               */
/* ------------------------------------------------------------------------ */

/* Split-normal cubes: a camera inside the cube (no_frustum_cull: every
 * patch's nearest depth clamps to the near plane, so every patch gets one
 * level) and an orthographic camera (e_max = error_bound * scale). Every
 * crease edge needs a strip with crease = true even at equal levels, and the
 * realisation is closed; without strips the soft cube opens. */
TEST(test_creases) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape cubes[2] = {shape_cube_soft(), shape_cube_split()};
  uint32_t runs = 0, crease_strips = 0;
  for (int ci = 0; ci < 2; ++ci)
    for (int ti = 0; ti < 2; ++ti) {
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &cubes[ci], ti ? TLOD_SURFACE_PN : TLOD_SURFACE_PHONG));
      uint32_t crease_edges = 0;
      for (uint32_t p = 0; p < fx.patches; ++p)
        for (uint32_t e = 0; e < 3; ++e)
          crease_edges += fx.link[p][e].face != UINT32_MAX && !fx.link[p][e].smooth && fx.link[p][e].face > p;
      CHECK_MSG(crease_edges == 12, "%s: %u crease edges, a cube has 12", cubes[ci].name, crease_edges);
      for (int cam = 0; cam < 2; ++cam) {
        tlod_scheduler* sch = new_scheduler(
            &fx, (tlod_scheduler_desc){
                     .epsilon_px = 1, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE, .no_frustum_cull = true});
        CHECK(sch);
        camera c = look_from(0, 0, 0, 1, 0.2, 0.1);
        if (cam == 1) {
          c = look_from(3, 2.5, 4, 0, 0, 0);
          c.ortho = true, c.half_h = 1.0;
        }
        tlod_view_desc v = make_view(&c);
        const tlod_draw_list* dl = plan(&fx, sch, &v, 1, 16, 0);
        CHECK(dl);
        char why[256];
        CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "%s %s camera %d: %s", cubes[ci].name,
                  type_name(fx.type), cam, why);
        int level = dl->levels[0];
        bool equal = true;
        for (uint32_t p = 0; p < fx.patches; ++p)
          equal = equal && dl->levels[p] == level;
        CHECK_MSG(equal || cam == 1, "%s %s: levels differ with the camera inside", cubes[ci].name, type_name(fx.type));
        if (!equal) {
          tlod_scheduler_destroy(sch);
          continue;
        }
        uint32_t creases = 0;
        for (uint32_t k = 0; k < dl->strip_count; ++k)
          creases += dl->strips[k].crease && dl->strips[k].level_a == dl->strips[k].level_b;
        CHECK_MSG(creases == 12 && dl->strip_count == 12, "%s %s camera %d: %u strips, %u equal-level crease strips",
                  cubes[ci].name, type_name(fx.type), cam, dl->strip_count, creases);
        crease_strips += creases;
        CHECK(realise(&fx, dl, false));
        CHECK_MSG(realised_closed(&fx, why, sizeof why), "%s %s camera %d level %d: %s", cubes[ci].name,
                  type_name(fx.type), cam, level, why);
        if (ci == 0) {
          CHECK(realise(&fx, dl, true));
          CHECK_MSG(!realised_closed(&fx, why, sizeof why), "%s %s: closed without its crease strips", cubes[ci].name,
                    type_name(fx.type));
        }
        printf("  %-10s %-5s %s: all patches at level %d, %u crease strips, closed\n", cubes[ci].name,
               type_name(fx.type), cam ? "orthographic" : "inside     ", level, creases);
        runs++;
        tlod_scheduler_destroy(sch);
      }
      fixture_free(&fx);
    }
  CHECK(runs >= 4 && crease_strips >= 48);
  for (int k = 0; k < 2; ++k)
    shape_free(&cubes[k]);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 4. Geomorphs                                                             */
/* ------------------------------------------------------------------------ */

/* A copy of a draw list whose instances can be edited. */
typedef struct dl_copy {
  tlod_draw_list dl;
  tlod_draw_instance* inst;
} dl_copy;

static dl_copy copy_draw_list(const tlod_draw_list* src) {
  dl_copy c;
  c.dl = *src;
  c.inst = malloc(sizeof *c.inst * (src->instance_count + 1));
  memcpy(c.inst, src->instances, sizeof *c.inst * src->instance_count);
  c.dl.instances = c.inst;
  return c;
}

static float* copy_positions(const tlod_cpu_mesh* m) {
  float* p = malloc(sizeof(float) * 3 * ((size_t)m->vertex_count + 1));
  memcpy(p, m->positions, sizeof(float) * 3 * m->vertex_count);
  return p;
}

static bool bits_equal3(const float* a, const float* b) { return memcmp(a, b, 3 * sizeof(float)) == 0; }

static void mid_f(const float* a, const float* b, float out[3]) {
  for (int k = 0; k < 3; ++k)
    out[k] = 0.5f * (a[k] + b[k]);
}

static double dist3f(const float* a, const float* b) {
  double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
  return len3(d);
}

/* The smallest blend a of level l whose morphed mesh meets eps (lod.h
 * TLOD_MORPH_CONTINUOUS, docs/design.md 3.9): (1 - a) b_{l-1} + a b_l = eps,
 * b_x = tlod_patch_error_bound(in, x) * scale; 0 when level l - 1 meets eps,
 * 1 when level l does not. */
static double ref_eps_blend(const tlod_patch_info* in, double scale, double eps, int l) {
  if (l <= 0) return 1.0;
  double hi = (double)tlod_patch_error_bound(in, (uint32_t)l - 1) * scale;
  double lo = (double)tlod_patch_error_bound(in, (uint32_t)l) * scale;
  if (hi <= eps) return 0.0;
  if (lo > eps) return 1.0;
  return (hi - eps) / (hi - lo);
}

/* (a) TIME: settle far away, step close with dt = 16 ms. Patches whose level
 * rose by one start with blend max(dt / morph_ms, a_eps), a_eps the smallest
 * blend that meets eps (ref_eps_blend); the frame realised with those
 * blends set to 0 is the old level exactly: the old vertices are bitwise the
 * old frame's and each new vertex is bitwise its parents' midpoint. With the
 * real blend each new vertex lies blend * |surface - midpoint| from it. */
TEST(test_geomorph_starts_at_coarse_level) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape shapes[2] = {shape_icosphere(1), shape_torus(12, 8)};
  uint32_t risen_total = 0, new_vertices = 0, at_step = 0, jumped = 0;
  double worst_blend_dev = 0;
  for (int run = 0; run < 3; ++run) {
    const shape* s = &shapes[run == 2];
    fixture fx;
    CHECK(fixture_make(&fx, ctx, s, run == 1 ? TLOD_SURFACE_PN : TLOD_SURFACE_PHONG));
    const float morph_ms = 200, dt = 16;
    tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = 1,
                                                                   .policy = TLOD_POLICY_ERROR,
                                                                   .morph = TLOD_MORPH_TIME,
                                                                   .morph_ms = morph_ms,
                                                                   .no_frustum_cull = true});
    CHECK(sch);
    camera far = look_from(0.3, 0.5, 14, 0, 0, 0), near = look_from(0.3, 0.5, 6.0, 0, 0, 0);
    tlod_view_desc vf = make_view(&far), vn = make_view(&near);
    view_ref rn = make_ref(&vn, &near);
    const tlod_draw_list* dl = NULL;
    for (int k = 0; k < 3; ++k)
      dl = plan(&fx, sch, &vf, 1, 1000, 0); /* dt >= morph_ms: settled */
    CHECK(dl);
    for (uint32_t i = 0; i < dl->instance_count; ++i)
      CHECK_MSG(dl->instances[i].morph == 1.0f, "settled frame: patch %u morph %g", dl->instances[i].patch,
                dl->instances[i].morph);
    CHECK(realise(&fx, dl, false));
    float* p0 = copy_positions(fx.out);
    uint32_t* base0 = malloc(sizeof *base0 * (fx.patches + 1));
    memcpy(base0, fx.base, sizeof *base0 * (fx.patches + 1));
    int8_t* lev0 = malloc(fx.patches);
    memcpy(lev0, dl->levels, fx.patches);
    dl = plan(&fx, sch, &vn, 1, dt, 0);
    CHECK(dl);
    char why[256];
    CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "%s", why);
    const float step = dt / morph_ms;
    uint32_t risen = 0;
    dl_copy zero = copy_draw_list(dl), one = copy_draw_list(dl);
    float* blend = calloc(fx.patches, sizeof *blend);
    for (uint32_t i = 0; i < dl->instance_count; ++i) {
      const tlod_draw_instance* in = &dl->instances[i];
      int l0 = lev0[in->patch];
      /* More than one level up only where eps asks for it at once. */
      bool amb;
      int need = ref_table_level(&fx.info[in->patch], ref_scale(&rn, &fx.info[in->patch]), 1.0, PAT_MAX, &amb);
      jumped += (int)in->level > l0 + 1;
      CHECK_MSG(((int)in->level <= l0 + 1 || (int)in->level <= need + amb) && (int)in->level >= l0 - 1,
                "patch %u jumped from level %d to %u in one frame of %g ms (eps needs %d)", in->patch, l0, in->level,
                dt, need);
      one.inst[i].morph = 1;
      if ((int)in->level != l0 + 1) continue;
      risen++;
      const tlod_patch_info* pi = &fx.info[in->patch];
      double a_eps = ref_eps_blend(pi, ref_scale(&rn, pi), 1.0, (int)in->level);
      double want = fmax(step, fmax(a_eps, 1e-4));
      at_step += a_eps < step;
      blend[in->patch] = in->morph;
      CHECK_MSG(in->morph > 0 && fabs(in->morph - want) <= 1e-5 * want + 1e-7,
                "patch %u rose to level %u with blend %.9g (step %g, eps blend %.9g)", in->patch, in->level, in->morph,
                step, a_eps);
      zero.inst[i].morph = 0;
    }
    CHECK_MSG(risen > fx.patches / 2, "%s: only %u of %u patches rose", s->name, risen, fx.patches);
    risen_total += risen;
    /* blend 0: the old level exactly */
    CHECK(realise(&fx, &zero.dl, false));
    CHECK_MSG(realised_closed(&fx, why, sizeof why), "blend-0 frame: %s", why);
    float* pz = copy_positions(fx.out);
    uint32_t* basez = malloc(sizeof *basez * (fx.patches + 1));
    memcpy(basez, fx.base, sizeof *basez * (fx.patches + 1));
    CHECK(realise(&fx, &one.dl, false));
    float* p1 = copy_positions(fx.out);
    CHECK(realise(&fx, dl, false));
    const float* pr = fx.out->positions;
    for (uint32_t p = 0; p < fx.patches; ++p) {
      int l0 = lev0[p], l1 = dl->levels[p];
      if (l1 != l0 + 1) continue;
      tlod_pattern_shape sh = shape_of(&fx, p);
      uint32_t count, n0 = tlod_pattern_vertex_count(sh, (uint32_t)l0),
                      n1 = tlod_pattern_vertex_count(sh, (uint32_t)l1);
      const tlod_pattern_vertex* pv = tlod_patterns_vertices(fx.pat, sh, &count);
      for (uint32_t x = 0; x < n1; ++x) {
        const float* q = pz + 3 * (size_t)(basez[p] + x);
        if (x < n0) {
          CHECK_MSG(bits_equal3(q, p0 + 3 * (size_t)(base0[p] + x)),
                    "%s: patch %u vertex %u of level %d moved at blend 0", s->name, p, x, l0);
          continue;
        }
        float mid[3], mid0[3];
        mid_f(pz + 3 * (size_t)(basez[p] + pv[x].parent[0]), pz + 3 * (size_t)(basez[p] + pv[x].parent[1]), mid);
        mid_f(p0 + 3 * (size_t)(base0[p] + pv[x].parent[0]), p0 + 3 * (size_t)(base0[p] + pv[x].parent[1]), mid0);
        CHECK_MSG(bits_equal3(q, mid) && bits_equal3(q, mid0),
                  "%s: patch %u new vertex %u at blend 0 is %.9g %.9g %.9g, parents' midpoint %.9g %.9g %.9g", s->name,
                  p, x, q[0], q[1], q[2], mid[0], mid[1], mid[2]);
        new_vertices++;
        /* the real blend: within blend * |surface - midpoint| of the midpoint */
        double full = dist3f(p1 + 3 * (size_t)(fx.base[p] + x), mid);
        double dev = dist3f(pr + 3 * (size_t)(fx.base[p] + x), mid);
        worst_blend_dev = fmax(worst_blend_dev, full > 0 ? dev / full : 0);
        CHECK_MSG(dev <= blend[p] * full * (1 + 1e-4) + 1e-6,
                  "%s: patch %u vertex %u is %.3g from the midpoint, %.3g x %g allowed", s->name, p, x, dev, full,
                  blend[p]);
      }
    }
    free(p0), free(pz), free(p1), free(base0), free(basez), free(lev0), free(zero.inst), free(one.inst), free(blend);
    tlod_scheduler_destroy(sch);
    fixture_free(&fx);
  }
  printf("  %u patches rose one level (%u starting at dt / morph_ms, the rest at the blend that meets eps), %u two "
         "(eps needs it); %u new vertices at blend 0 bitwise on their parents' midpoints; with the real blend at most "
         "%.4f of the way to the surface\n",
         risen_total, at_step, jumped, new_vertices, worst_blend_dev);
  for (int k = 0; k < 2; ++k)
    shape_free(&shapes[k]);
  tlod_context_destroy(ctx);
}

/* (b) Positions along a slow camera path, every frame realised (no_weld):
 * a pattern vertex present in two consecutive frames (same patch, same
 * index) that belongs to a coarser level than the drawn one in both is an
 * exact surface point and must not move at all; one that is blending may
 * move at most step * 4^-(l-1) * error_bound * K (step = dt / morph_ms,
 * l = the level that inserts it: its distance from its parents' midpoint is
 * what the level-(l-1) pattern misses, at most 4^-(l-1) error_bound). A
 * vertex that appears or disappears with a level change must then lie that
 * close to its parents' midpoint. Without morphs (NONE) the jump at a switch
 * is the full distance. */
typedef struct path_stats {
  double max_jump, max_ratio;
  uint32_t frames, switches, checked;
} path_stats;

static void geomorph_path(const shape* s, tlod_surface_type type, tlod_morph_mode mode, double K, path_stats* st) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, s, type));
  const float morph_ms = 200, dt = 16, step = dt / morph_ms;
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = 0.5f,
                                                                 .max_level = 4,
                                                                 .policy = TLOD_POLICY_ERROR,
                                                                 .morph = mode,
                                                                 .morph_ms = morph_ms,
                                                                 .no_frustum_cull = true});
  CHECK(sch);
  float* prev = NULL;
  uint32_t* prev_base = malloc(sizeof *prev_base * (fx.patches + 1));
  int8_t* prev_lev = malloc(fx.patches);
  const int frames = 160;
  for (int f = 0; f < frames; ++f) {
    double t = (double)f / (frames - 1), ang = 0.6 * t;
    double d = 1.6 + 5.4 * (0.5 + 0.5 * cos(2 * SHAPES_PI * t)); /* 7 -> 1.6 -> 7 */
    camera c = look_from(d * sin(ang), 0.4 * d, d * cos(ang), 0, 0, 0);
    tlod_view_desc v = make_view(&c);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 1, dt, 0);
    CHECK(dl);
    char why[256];
    CHECK_MSG(check_draw_list(&fx, dl, 4, why, sizeof why), "frame %d: %s", f, why);
    CHECK(realise(&fx, dl, false));
    if (mode == TLOD_MORPH_TIME) /* mid-transition frames are closed too */
      CHECK_MSG(realised_closed(&fx, why, sizeof why), "%s %s frame %d: %s", s->name, type_name(type), f, why);
    const float* cur = fx.out->positions;
    if (prev) {
      bool switched = false;
      for (uint32_t p = 0; p < fx.patches; ++p) {
        int l0 = prev_lev[p], l1 = dl->levels[p];
        if (mode == TLOD_MORPH_TIME)
          CHECK_MSG(abs(l1 - l0) <= 1, "%s frame %d: patch %u level %d -> %d", s->name, f, p, l0, l1);
        switched = switched || l0 != l1;
        tlod_pattern_shape sh = shape_of(&fx, p);
        uint32_t count;
        const tlod_pattern_vertex* pv = tlod_patterns_vertices(fx.pat, sh, &count);
        int lo = l0 < l1 ? l0 : l1, hi = l0 < l1 ? l1 : l0;
        uint32_t n_lo = tlod_pattern_vertex_count(sh, (uint32_t)lo), n_hi = tlod_pattern_vertex_count(sh, (uint32_t)hi);
        double eb = fx.info[p].error_bound;
        for (uint32_t x = 0; x < n_hi; ++x) {
          double jump;
          if (x < n_lo) {
            const float* a = prev + 3 * (size_t)(prev_base[p] + x);
            const float* b = cur + 3 * (size_t)(fx.base[p] + x);
            if (pv[x].level < lo) {
              CHECK_MSG(bits_equal3(a, b), "%s frame %d: patch %u vertex %u (level %u, drawn %d/%d) moved %.3g",
                        s->name, f, p, x, pv[x].level, l0, l1, dist3f(a, b));
              continue;
            }
            jump = dist3f(a, b);
          } else { /* only in the finer frame: its distance from the coarser surface */
            const float* fine = l1 > l0 ? cur : prev;
            uint32_t fb = l1 > l0 ? fx.base[p] : prev_base[p];
            float mid[3];
            mid_f(fine + 3 * (size_t)(fb + pv[x].parent[0]), fine + 3 * (size_t)(fb + pv[x].parent[1]), mid);
            jump = dist3f(fine + 3 * (size_t)(fb + x), mid);
          }
          double bound = ldexp(eb, -2 * (pv[x].level - 1)) * step;
          st->max_jump = fmax(st->max_jump, jump);
          st->checked++;
          if (bound > 0) st->max_ratio = fmax(st->max_ratio, jump / bound);
          if (mode == TLOD_MORPH_TIME)
            CHECK_MSG(jump <= K * bound + 1e-6,
                      "%s %s frame %d: patch %u vertex %u (level %u; drawn %d -> %d) jumped %.4g, bound %.4g (error "
                      "bound %.4g)",
                      s->name, type_name(type), f, p, x, pv[x].level, l0, l1, jump, K * bound, eb);
        }
      }
      st->switches += switched;
    }
    free(prev);
    prev = copy_positions(fx.out);
    memcpy(prev_base, fx.base, sizeof *prev_base * (fx.patches + 1));
    memcpy(prev_lev, dl->levels, fx.patches);
    st->frames++;
  }
  free(prev);
  free(prev_base);
  free(prev_lev);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  tlod_context_destroy(ctx);
}

TEST(test_geomorph_continuity) {
  shape sph = shape_icosphere(1), tor = shape_torus(12, 8);
  struct {
    const shape* s;
    tlod_surface_type type;
  } cases[3] = {{&sph, TLOD_SURFACE_PHONG}, {&sph, TLOD_SURFACE_PN}, {&tor, TLOD_SURFACE_PHONG}};
  const double K = 1.0; /* Phong: exact quadratic law (ratio 3/4 expected); PN: the paper's 9/4 d'_max estimate */
  for (int k = 0; k < 3; ++k) {
    path_stats none = {0}, timed = {0};
    CALL(geomorph_path(cases[k].s, cases[k].type, TLOD_MORPH_NONE, K, &none));
    CALL(geomorph_path(cases[k].s, cases[k].type, TLOD_MORPH_TIME, K, &timed));
    printf("  %-10s %-5s %u frames: largest per-frame vertex jump NONE %.4g (%u switching frames), TIME %.4g "
           "(%.3g of step x 4^-(l-1) x error_bound; %u vertex pairs)\n",
           cases[k].s->name, type_name(cases[k].type), timed.frames, none.max_jump, none.switches, timed.max_jump,
           timed.max_ratio, timed.checked);
    CHECK_MSG(none.switches > 0 && timed.switches > 0, "the path never changed a level");
    CHECK_MSG(none.max_jump > timed.max_jump, "geomorphs did not reduce the jump (%.4g vs %.4g)", timed.max_jump,
              none.max_jump);
  }
  shape_free(&sph);
  shape_free(&tor);
}

/* (c) CONTINUOUS: the drawn level is the table rule's and the blend the
 * smallest that meets eps (ref_eps_blend), in (0, 1]. */
TEST(test_geomorph_continuous) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PN));
  const float eps = 1;
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = eps,
                                                                 .max_level = 4,
                                                                 .policy = TLOD_POLICY_ERROR,
                                                                 .morph = TLOD_MORPH_CONTINUOUS,
                                                                 .no_frustum_cull = true});
  CHECK(sch);
  uint32_t fractional = 0, checked = 0;
  double worst = 0;
  for (int f = 0; f < 30; ++f) {
    double d = 1.7 + 0.25 * f;
    camera c = look_from(0.2 * d, 0.3 * d, d, 0, 0, 0);
    tlod_view_desc v = make_view(&c);
    view_ref r = make_ref(&v, &c);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 1, 16, 0);
    CHECK(dl);
    char why[256];
    CHECK_MSG(check_draw_list(&fx, dl, 4, why, sizeof why), "frame %d: %s", f, why);
    for (uint32_t i = 0; i < dl->instance_count; ++i) {
      const tlod_draw_instance* in = &dl->instances[i];
      CHECK_MSG(in->morph > 0 && in->morph <= 1, "patch %u: blend %.9g outside (0, 1]", in->patch, in->morph);
      fractional += in->morph < 1;
      const tlod_patch_info* pi = &fx.info[in->patch];
      double scale = ref_scale(&r, pi);
      bool amb;
      int lw = ref_table_level(pi, scale, eps, 4, &amb);
      if (in->level == 0 || in->level == 4) continue;
      CHECK_MSG((int)in->level == lw || amb, "patch %u: level %u, table rule %d", in->patch, in->level, lw);
      if (amb) continue;
      double want = fmax(ref_eps_blend(pi, scale, eps, (int)in->level), 1e-4);
      worst = fmax(worst, fabs(in->morph - want));
      CHECK_MSG(in->morph >= want * (1 - 1e-6) && in->morph - want <= 1e-5,
                "patch %u level %u: blend %.7f, the blend that meets eps %.7f", in->patch, in->level, in->morph, want);
      checked++;
    }
    CHECK(realise(&fx, dl, false));
    CHECK_MSG(realised_closed(&fx, why, sizeof why), "frame %d: %s", f, why);
  }
  printf("  %u blends checked against the blend that meets eps (worst error %.2g), %u fractional; all frames closed\n",
         checked, worst, fractional);
  CHECK(fractional > 100 && checked > 100);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 5. Screen-space error of the realised frame                              */
/* ------------------------------------------------------------------------ */

/* Pixel position of a world point (x right, y up), its clip w and whether
 * it lies inside the frustum. */
static bool pixel_of(const view_ref* r, const double p[3], double px[2], double* w) {
  double clip[4];
  for (int row = 0; row < 4; ++row)
    clip[row] = r->M[row] * p[0] + r->M[4 + row] * p[1] + r->M[8 + row] * p[2] + r->M[12 + row];
  *w = clip[3];
  double x = clip[0] / clip[3], y = clip[1] / clip[3], z = clip[2] / clip[3];
  px[0] = (x + 1) * r->width / 2, px[1] = (y + 1) * r->height / 2;
  return clip[3] > 0 && fabs(x) <= 1 && fabs(y) <= 1 && fabs(z) <= 1;
}

/* (a) tlod_patch_projection_scale against finite differences of the
 * projection: for random spheres and cameras, at random points of the
 * sphere inside the frustum, |pixel(p + h d) - pixel(p)| / h over random
 * directions d and the worst direction (d = R^T (a, -r^2) in view space,
 * a = (x/z, y/z)) never exceeds the scale; at each point the worst
 * direction's magnification is (f / z) sqrt(1 + r^2) (to 1e-4, f the
 * pixel scale: the viewports here have square pixels to 1/64). */
TEST(test_projection_scale) {
  shape_rng rng = {4242};
  uint32_t points = 0;
  double worst = 0, formula_err = 0, tight_sum = 0;
  uint32_t tight_n = 0;
  for (int k = 0; k < 400; ++k) {
    camera c = random_camera(&rng, 1.0, k % 5, k % 7 == 6);
    tlod_view_desc v = make_view(&c);
    view_ref r = make_ref(&v, &c);
    float centre[3];
    for (int a = 0; a < 3; ++a)
      centre[a] = (float)shape_rng_range(&rng, -1.2, 1.2);
    float radius = (float)exp(shape_rng_range(&rng, log(0.005), log(0.8)));
    double scale = tlod_patch_projection_scale(&v, centre, radius);
    CHECK_MSG(scale > 0 && isfinite(scale), "camera %d: scale %g", k, scale);
    double best = 0;
    for (int t = 0; t < 200; ++t) {
      double dir[3], p[3];
      shape_rng_direction(&rng, dir);
      double rr = radius * cbrt(shape_rng_unit(&rng));
      for (int a = 0; a < 3; ++a)
        p[a] = centre[a] + rr * dir[a];
      double px[2], w;
      if (!pixel_of(&r, p, px, &w)) continue;
      /* view space: x, y and depth z = -z_view */
      double xv = r.V[0] * p[0] + r.V[4] * p[1] + r.V[8] * p[2] + r.V[12];
      double yv = r.V[1] * p[0] + r.V[5] * p[1] + r.V[9] * p[2] + r.V[13];
      double zv = -(r.V[2] * p[0] + r.V[6] * p[1] + r.V[10] * p[2] + r.V[14]);
      double ax = r.ortho ? 0 : xv / zv, ay = r.ortho ? 0 : yv / zv, r2 = ax * ax + ay * ay;
      double dv[3] = {ax, ay, r.ortho ? 0 : -r2}; /* view-space worst direction (depth axis = -z_view) */
      double worst_dir[3] = {0, 0, 0};
      if (r2 > 0) {
        double n = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
        for (int a = 0; a < 3; ++a) /* world = R^T (x, y, z_view) with z_view = -depth */
          worst_dir[a] = (r.V[4 * a + 0] * dv[0] + r.V[4 * a + 1] * dv[1] - r.V[4 * a + 2] * dv[2]) / n;
      } else {
        for (int a = 0; a < 3; ++a)
          worst_dir[a] = r.V[4 * a + 0];
      }
      for (int d = 0; d < 9; ++d) {
        double u[3];
        if (d == 0) {
          memcpy(u, worst_dir, sizeof u);
        } else {
          shape_rng_direction(&rng, u);
        }
        double h = 1e-6 * (1 + fabs(zv)), q[3] = {p[0] + h * u[0], p[1] + h * u[1], p[2] + h * u[2]};
        double qx[2], qw, qm[3] = {p[0] - h * u[0], p[1] - h * u[1], p[2] - h * u[2]}, mx[2], mw;
        pixel_of(&r, q, qx, &qw);
        pixel_of(&r, qm, mx, &mw);
        if (!(qw > 0 && mw > 0)) continue;
        double mag = hypot(qx[0] - mx[0], qx[1] - mx[1]) / (2 * h);
        worst = fmax(worst, mag / scale);
        best = fmax(best, mag);
        CHECK_MSG(mag <= scale * (1 + 1e-4), "camera %d (%s) point %d: magnification %.7g above the scale %.7g", k,
                  r.ortho ? "ortho" : "perspective", t, mag, scale);
        if (d == 0) {
          double f = r.height / 2 * fabs(r.P[5]), want = r.ortho ? f : f / zv * sqrt(1 + r2);
          double fx = r.width / 2 * fabs(r.P[0]), aniso = fabs(fx - f) / f;
          formula_err = fmax(formula_err, fabs(mag - want) / want - aniso);
          CHECK_MSG(fabs(mag - want) <= (1e-4 + aniso) * want,
                    "camera %d point %d: worst-direction magnification %.7g, (f / z) sqrt(1 + r^2) = %.7g", k, t, mag,
                    want);
        }
        points++;
      }
    }
    if (best > 0) tight_sum += best / scale, tight_n++;
  }
  printf("  %u (point, direction) pairs: worst magnification / scale %.5f, mean of the per-sphere best %.3f; the "
         "worst direction matches (f/z) sqrt(1 + r^2) to %.1g\n",
         points, worst, tight_sum / fmax(tight_n, 1), formula_err);
  CHECK(points > 100000);
}

/* (b) The true on-screen error of the drawn mesh. For random cameras
 * (ERROR policy, eps 0.5 / 1 / 2 px, morph NONE settled and TIME half-way
 * through a change of camera), every visible patch not clamped at the max
 * level, each pattern triangle of the realised frame sampled at 10 points:
 * the surface point S = tlod_surface_eval(u, v) and the point A of the
 * drawn triangle at the same barycentrics (the linear interpolation of its
 * drawn corners: exact surface points when settled, blended ones while
 * morphing), both projected to pixels with the float matrices in double;
 * |S - A| in pixels <= eps (1 + 1e-4) wherever S is inside the frustum.
 * Nothing here reads the error table except to skip patches clamped at the
 * max level. Cameras: the eye at 0.1 to 10 model diagonals from the bounding
 * sphere (log-uniform), the look-at point off the centre by up to the half
 * field of view (off-axis), and one camera in four with its near plane
 * through the model. */
typedef struct screen_stats {
  double worst;    /* measured / eps, over samples */
  double* ratios;  /* per patch: its worst measured / eps */
  double* tight;   /* per patch: its worst measured / the projected bound of its blend */
  uint32_t n, cap; /* ratios, tight */
  uint64_t samples;
  uint32_t clamped, cameras, morphing;
} screen_stats;

static void push_ratio(screen_stats* st, double x, double t) {
  if (st->n == st->cap) {
    st->cap = st->cap ? 2 * st->cap : 1024;
    st->ratios = realloc(st->ratios, sizeof *st->ratios * st->cap);
    st->tight = realloc(st->tight, sizeof *st->tight * st->cap);
  }
  st->tight[st->n] = t;
  st->ratios[st->n++] = x;
}

static int cmp_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y;
}

static double median_of(double* x, uint32_t n) {
  if (!n) return 0;
  qsort(x, n, sizeof *x, cmp_double);
  return x[n / 2];
}

static camera screen_camera(shape_rng* rng, double R, double dist_diag, int cam) {
  double dir[3], off[3];
  shape_rng_direction(rng, dir);
  shape_rng_direction(rng, off);
  double dist = R + dist_diag * 2 * R, fovy = shape_rng_range(rng, 30, 90) * DEG;
  /* off axis: the target moves sideways by up to the half field of view */
  double side = shape_rng_range(rng, 0, 0.9) * tan(fovy / 2) * dist;
  double t[3];
  cross3(dir, off, t);
  shape_normalize3(t);
  camera c = look_from(dir[0] * dist, dir[1] * dist, dir[2] * dist, t[0] * side, t[1] * side, t[2] * side);
  c.fovy = fovy;
  c.width = 400 + (uint32_t)(shape_rng_next(rng) % 800);
  c.height = 300 + (uint32_t)(shape_rng_next(rng) % 500);
  c.aspect = (double)c.width / c.height;
  c.znear = cam % 4 == 3 ? dist - 0.5 * R : fmin(0.05 * R, 0.5 * (dist - R)); /* 3: the near plane cuts the model */
  c.zfar = dist + 4 * R;
  return c;
}

/* The surface against the drawn pattern triangles of one frame. */
static void measure_frame(fixture* fx, const tlod_draw_list* dl, const view_ref* r, double eps, int lmax,
                          const char* what, screen_stats* st) {
  static const double bary[10][3] = {{0.5, 0.5, 0},
                                     {0, 0.5, 0.5},
                                     {0.5, 0, 0.5},
                                     {1.0 / 3, 1.0 / 3, 1.0 / 3},
                                     {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                     {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                     {1.0 / 6, 1.0 / 6, 2.0 / 3},
                                     {0.25, 0.75, 0},
                                     {0, 0.25, 0.75},
                                     {0.75, 0, 0.25}};
  CHECK(realise(fx, dl, false));
  for (uint32_t i = 0; i < dl->instance_count; ++i) {
    const tlod_draw_instance* in = &dl->instances[i];
    uint32_t p = in->patch;
    int l = (int)in->level;
    double scale = ref_scale(r, &fx->info[p]);
    if ((double)tlod_patch_error_bound(&fx->info[p], (uint32_t)l) * scale > eps && l == lmax) {
      st->clamped++;
      continue;
    }
    st->morphing += in->morph < 1;
    tlod_pattern_shape sh = shape_of(fx, p);
    uint32_t nidx, count;
    const uint32_t* idx = tlod_patterns_indices(fx->pat, sh, (uint32_t)l, &nidx);
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(fx->pat, sh, &count);
    double patch_worst = -1;
    for (uint32_t t = 0; t < nidx; t += 3) {
      const float* P[3];
      for (int q = 0; q < 3; ++q)
        P[q] = fx->out->positions + 3 * (size_t)(fx->base[p] + idx[t + q]);
      for (int smp = 0; smp < 10; ++smp) {
        const double* b = bary[smp];
        double u = 0, vv = 0, A[3] = {0, 0, 0};
        for (int q = 0; q < 3; ++q) {
          u += b[q] * pv[idx[t + q]].u;
          vv += b[q] * pv[idx[t + q]].v;
          for (int k3 = 0; k3 < 3; ++k3)
            A[k3] += b[q] * P[q][k3];
        }
        tlod_surface_point sp;
        tlod_surface_eval(fx->surf, p, (float)u, (float)vv, &sp);
        double S[3] = {sp.position[0], sp.position[1], sp.position[2]}, ps[2], pa[2], ws, wa;
        if (!pixel_of(r, S, ps, &ws)) continue; /* off screen or clipped */
        pixel_of(r, A, pa, &wa);
        if (!(wa > 0)) continue;
        double dev = hypot(ps[0] - pa[0], ps[1] - pa[1]);
        patch_worst = fmax(patch_worst, dev / eps);
        st->samples++;
        CHECK_MSG(dev <= eps * (1 + 1e-4) + 1e-6,
                  "%s patch %u level %u (blend %.4f): %.5g px at (u, v) = (%.4f, %.4f), "
                  "eps %.3g",
                  what, p, in->level, in->morph, dev, u, vv, eps);
      }
    }
    /* the bound of the drawn blend: (1 - a) b_{l-1} + a b_l, projected */
    double a = in->morph, bl = (double)tlod_patch_error_bound(&fx->info[p], (uint32_t)l) * scale;
    double bb = l > 0 ? (1 - a) * (double)tlod_patch_error_bound(&fx->info[p], (uint32_t)l - 1) * scale + a * bl : bl;
    if (patch_worst >= 0) push_ratio(st, patch_worst, bb > 0 ? patch_worst * eps / bb : 0);
    st->worst = fmax(st->worst, patch_worst);
  }
}

static void screen_error_suite(tlod_context* ctx, const shape* s, tlod_surface_type type, tlod_error_tables tables,
                               int cameras, uint64_t seed, screen_stats* settled, screen_stats* morphing) {
  fixture fx;
  CHECK(fixture_make_tables(&fx, ctx, s, type, tables));
  double R = 0;
  for (uint32_t v = 0; v < fx.vertices; ++v)
    R = fmax(R, len3(fx.vpos[v]));
  const int lmax = PAT_MAX;
  const float eps_of[3] = {0.5f, 1.0f, 2.0f}, morph_ms = 200;
  shape_rng rng = {seed};
  for (int cam = 0; cam < cameras; ++cam) {
    int k = cam % 3;
    double eps = eps_of[k], dd = exp(shape_rng_range(&rng, log(0.1), log(10.0)));
    camera c = screen_camera(&rng, R, dd, cam);
    tlod_view_desc v = make_view(&c);
    view_ref r = make_ref(&v, &c);
    char what[160];
    /* settled: NONE */
    tlod_scheduler* sn = new_scheduler(
        &fx, (tlod_scheduler_desc){
                 .epsilon_px = eps_of[k], .max_level = lmax, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE});
    CHECK(sn);
    const tlod_draw_list* dl = plan(&fx, sn, &v, 1, 16, 0);
    CHECK(dl);
    snprintf(what, sizeof what, "%s %s camera %d (%.3g diagonals) settled", s->name, type_name(type), cam, dd);
    CALL(measure_frame(&fx, dl, &r, eps, lmax, what, settled));
    settled->cameras++;
    tlod_scheduler_destroy(sn);
    /* TIME half-way: settled at a camera twice as far (or half as far: the
     * levels then fall), then half a morph_ms at this one */
    tlod_scheduler* st = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = eps_of[k],
                                                                  .max_level = lmax,
                                                                  .policy = TLOD_POLICY_ERROR,
                                                                  .morph = TLOD_MORPH_TIME,
                                                                  .morph_ms = morph_ms});
    CHECK(st);
    camera c0 = c;
    double g = cam % 2 ? 2.0 : 0.5;
    for (int a = 0; a < 3; ++a)
      c0.eye[a] = c.target[a] + g * (c.eye[a] - c.target[a]);
    tlod_view_desc v0 = make_view(&c0);
    CHECK(plan(&fx, st, &v0, 1, 1000, 0) && plan(&fx, st, &v0, 1, 1000, 0));
    dl = plan(&fx, st, &v, 1, morph_ms / 2, 0);
    CHECK(dl);
    snprintf(what, sizeof what, "%s %s camera %d (%.3g diagonals) mid-morph from %gx the distance", s->name,
             type_name(type), cam, dd, g);
    CALL(measure_frame(&fx, dl, &r, eps, lmax, what, morphing));
    morphing->cameras++;
    tlod_scheduler_destroy(st);
  }
  fixture_free(&fx);
}

TEST(test_screen_error) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1), qs = shape_quad_sphere(2), cube = shape_cube_soft();
  struct {
    const shape* s;
    tlod_surface_type type;
  } cases[4] = {
      {&sph, TLOD_SURFACE_PHONG}, {&sph, TLOD_SURFACE_PN}, {&qs, TLOD_SURFACE_PHONG}, {&cube, TLOD_SURFACE_PN}};
  for (int k = 0; k < 4; ++k) {
    screen_stats a = {0}, b = {0};
    CALL(screen_error_suite(ctx, cases[k].s, cases[k].type, TLOD_ERROR_TABLES_DEFAULT, 24, 300 + (uint64_t)k, &a, &b));
    printf("  %-11s %-5s %u cameras: settled %u patches, %llu samples: worst %.3f eps, median over patches %.3f "
           "(measured / bound: median %.3f); TIME half-way %u patches (%u blending), %llu samples: worst %.3f eps, "
           "median %.3f (measured / bound %.3f); %u clamped at the max level skipped\n",
           cases[k].s->name, type_name(cases[k].type), a.cameras, a.n, (unsigned long long)a.samples, a.worst,
           median_of(a.ratios, a.n), median_of(a.tight, a.n), b.n, b.morphing, (unsigned long long)b.samples, b.worst,
           median_of(b.ratios, b.n), median_of(b.tight, b.n), a.clamped + b.clamped);
    CHECK(a.samples > 10000 && b.samples > 10000 && b.morphing > 50);
    free(a.ratios), free(a.tight);
    free(b.ratios), free(b.tight);
  }
  shape_free(&sph);
  shape_free(&qs);
  shape_free(&cube);
  tlod_context_destroy(ctx);
}

/* The closed-form tables (TLOD_ERROR_TABLES_CLOSED_FORM, error_bound 4^-l)
 * drive the same level rule: the drawn mesh is within eps too, settled and
 * mid-morph, on a triangle and a quad mesh. */
TEST(test_screen_error_closed_form) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1), qs = shape_quad_sphere(2);
  const shape* shapes[2] = {&sph, &qs};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PN, TLOD_SURFACE_PHONG};
  for (int k = 0; k < 2; ++k) {
    screen_stats a = {0}, b = {0};
    CALL(screen_error_suite(ctx, shapes[k], types[k], TLOD_ERROR_TABLES_CLOSED_FORM, 24, 400 + (uint64_t)k, &a, &b));
    printf("  closed form %-11s %-5s %u cameras: settled worst %.3f eps (%llu samples), TIME half-way worst %.3f eps "
           "(%llu samples, %u blending)\n",
           shapes[k]->name, type_name(types[k]), a.cameras, a.worst, (unsigned long long)a.samples, b.worst,
           (unsigned long long)b.samples, b.morphing);
    CHECK(a.samples > 1000 && b.samples > 1000);
    free(a.ratios), free(a.tight);
    free(b.ratios), free(b.tight);
  }
  shape_free(&sph);
  shape_free(&qs);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 6. Monotonicity and the triangle budget                                  */
/* ------------------------------------------------------------------------ */

static uint64_t frame_tris(const tlod_draw_list* dl) { return dl->pattern_triangles + dl->strip_triangles; }

TEST(test_monotone_and_budget) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(2);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  int8_t* prev = malloc(fx.patches);
  char why[256];
  /* (a) epsilon 4 .. 0.25: every patch's level and the total never fall */
  const float eps_list[5] = {4, 2, 1, 0.5f, 0.25f};
  camera c = look_from(0.5, 0.8, 3.5, 0, 0, 0);
  tlod_view_desc v = make_view(&c);
  for (int pol = 0; pol < 2; ++pol) {
    uint64_t tris[5];
    for (int k = 0; k < 5; ++k) {
      tlod_scheduler* s =
          new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = eps_list[k],
                                                   .policy = pol ? TLOD_POLICY_HYBRID : TLOD_POLICY_ERROR,
                                                   .morph = TLOD_MORPH_NONE});
      CHECK(s);
      const tlod_draw_list* dl = plan(&fx, s, &v, 1, 16, 0);
      CHECK(dl);
      CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "%s", why);
      tris[k] = frame_tris(dl);
      for (uint32_t p = 0; p < fx.patches && k > 0; ++p)
        CHECK_MSG(dl->levels[p] >= prev[p], "%s eps %g: patch %u level %d, %d at eps %g", pol ? "hybrid" : "error",
                  eps_list[k], p, dl->levels[p], prev[p], eps_list[k - 1]);
      memcpy(prev, dl->levels, fx.patches);
      tlod_scheduler_destroy(s);
    }
    printf("  %s, epsilon 4 2 1 0.5 0.25: %llu %llu %llu %llu %llu triangles\n", pol ? "hybrid" : "error ",
           (unsigned long long)tris[0], (unsigned long long)tris[1], (unsigned long long)tris[2],
           (unsigned long long)tris[3], (unsigned long long)tris[4]);
    for (int k = 1; k < 5; ++k)
      CHECK(tris[k] >= tris[k - 1]);
    CHECK(tris[4] > 4 * tris[0]);
  }
  /* (b) the camera approaching along one ray (no_frustum_cull: every patch
   * stays; its nearest depth only falls) */
  const double dist[4] = {10, 5, 2.5, 1.5};
  uint64_t tris[4], culled_tris[4];
  for (int k = 0; k < 4; ++k) {
    camera cd = look_from(0.3 * dist[k], 0.4 * dist[k], 0.866 * dist[k], 0, 0, 0);
    tlod_view_desc vd = make_view(&cd);
    tlod_scheduler* s = new_scheduler(
        &fx, (tlod_scheduler_desc){
                 .epsilon_px = 1, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE, .no_frustum_cull = true});
    tlod_scheduler* sc = new_scheduler(
        &fx, (tlod_scheduler_desc){.epsilon_px = 1, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE});
    CHECK(s && sc);
    const tlod_draw_list* dl = plan(&fx, s, &vd, 1, 16, 0);
    CHECK(dl);
    tris[k] = frame_tris(dl);
    for (uint32_t p = 0; p < fx.patches && k > 0; ++p)
      CHECK_MSG(dl->levels[p] >= prev[p], "distance %g: patch %u level %d, %d at distance %g", dist[k], p,
                dl->levels[p], prev[p], dist[k - 1]);
    memcpy(prev, dl->levels, fx.patches);
    dl = plan(&fx, sc, &vd, 1, 16, 0);
    CHECK(dl);
    culled_tris[k] = frame_tris(dl);
    tlod_scheduler_destroy(s);
    tlod_scheduler_destroy(sc);
  }
  printf("  distance 10 5 2.5 1.5: %llu %llu %llu %llu triangles (with culling %llu %llu %llu %llu)\n",
         (unsigned long long)tris[0], (unsigned long long)tris[1], (unsigned long long)tris[2],
         (unsigned long long)tris[3], (unsigned long long)culled_tris[0], (unsigned long long)culled_tris[1],
         (unsigned long long)culled_tris[2], (unsigned long long)culled_tris[3]);
  for (int k = 1; k < 4; ++k)
    CHECK(tris[k] >= tris[k - 1]);
  CHECK(tris[3] > 4 * tris[0]);
  /* (c) budgets: the frame fits, epsilon only grows as the budget shrinks,
   * the levels follow the rule at the effective epsilon; below the level-0
   * count everything is level 0 */
  const uint32_t budgets[8] = {1000000, 40000, 10000, 4000, 1500, 640, 320, 100};
  uint32_t level0 = 0;
  for (uint32_t p = 0; p < fx.patches; ++p)
    level0 += tlod_pattern_triangle_count(shape_of(&fx, p), 0);
  for (int pol = 0; pol < 3; ++pol) {
    float prev_eps = 0;
    printf("  %-10s budget -> triangles (effective epsilon):", pol == 0 ? "error" : pol == 1 ? "hybrid" : "silhouette");
    for (int k = 0; k < 8; ++k) {
      const tlod_lod_policy policy = pol == 0   ? TLOD_POLICY_ERROR
                                     : pol == 1 ? TLOD_POLICY_HYBRID
                                                : TLOD_POLICY_SILHOUETTE;
      tlod_scheduler* s = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = 0.25f,
                                                                   .policy = policy,
                                                                   .morph = TLOD_MORPH_NONE,
                                                                   .triangle_budget = budgets[k],
                                                                   .no_frustum_cull = true});
      CHECK(s);
      const tlod_draw_list* dl = plan(&fx, s, &v, 1, 16, 0);
      CHECK(dl);
      CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "budget %u: %s", budgets[k], why);
      uint64_t t = frame_tris(dl);
      printf(" %u -> %llu (%.3g)", budgets[k], (unsigned long long)t, dl->effective_epsilon);
      CHECK_MSG(dl->effective_epsilon >= 0.25f, "budget %u: effective epsilon %g", budgets[k], dl->effective_epsilon);
      if (k == 0) CHECK(dl->effective_epsilon == 0.25f && t < budgets[0]);
      if (pol < 2)
        CHECK_MSG(dl->effective_epsilon >= prev_eps, "budget %u: effective epsilon %g fell from %g", budgets[k],
                  dl->effective_epsilon, prev_eps);
      prev_eps = dl->effective_epsilon;
      if (budgets[k] >= level0) {
        CHECK_MSG(t <= budgets[k], "budget %u: %llu triangles (%llu pattern + %llu strip)", budgets[k],
                  (unsigned long long)t, (unsigned long long)dl->pattern_triangles,
                  (unsigned long long)dl->strip_triangles);
      } else {
        CHECK_MSG(dl->level_histogram[0] == fx.patches, "budget %u below the level-0 count %u: %u patches at level 0",
                  budgets[k], level0, dl->level_histogram[0]);
      }
      view_ref rb = make_ref(&v, &c);
      if (pol == 0) /* ERROR: the levels are the rule's at the effective epsilon */
        for (uint32_t p = 0; p < fx.patches; ++p) {
          bool amb;
          int want = ref_table_level(&fx.info[p], ref_scale(&rb, &fx.info[p]), dl->effective_epsilon, PAT_MAX, &amb);
          CHECK_MSG(dl->levels[p] == want || (amb && abs(dl->levels[p] - want) <= 1),
                    "budget %u: patch %u level %d, rule at effective epsilon %g: %d", budgets[k], p, dl->levels[p],
                    dl->effective_epsilon, want);
        }
      tlod_scheduler_destroy(s);
    }
    printf("\n");
  }
  free(prev);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 7. Frame-time target                                                     */
/* ------------------------------------------------------------------------ */

TEST(test_frame_time_target) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(2);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  const float eps = 0.5f, target = 16;
  tlod_scheduler* s = new_scheduler(&fx, (tlod_scheduler_desc){.epsilon_px = eps,
                                                               .policy = TLOD_POLICY_ERROR,
                                                               .morph = TLOD_MORPH_NONE,
                                                               .frame_time_target_ms = target});
  CHECK(s);
  camera c = look_from(0.5, 0.8, 3.5, 0, 0, 0);
  tlod_view_desc v = make_view(&c);
  int8_t* first = malloc(fx.patches);
  /* on target from the start: nothing moves */
  const tlod_draw_list* dl = plan(&fx, s, &v, 1, 16, target);
  CHECK(dl && dl->effective_epsilon == eps);
  memcpy(first, dl->levels, fx.patches);
  uint64_t tris0 = frame_tris(dl);
  for (int f = 0; f < 20; ++f) {
    dl = plan(&fx, s, &v, 1, 16, target);
    CHECK(dl);
    CHECK_MSG(dl->effective_epsilon == eps && memcmp(dl->levels, first, fx.patches) == 0,
              "frame %d on target: epsilon %g, levels changed", f, dl->effective_epsilon);
  }
  /* too slow: epsilon rises, never falls */
  float e_prev = eps;
  int f_rise = 0;
  for (; f_rise < 40; ++f_rise) {
    dl = plan(&fx, s, &v, 1, 16, 2 * target);
    CHECK(dl);
    CHECK_MSG(dl->effective_epsilon >= e_prev, "slow frame %d: epsilon fell %g -> %g", f_rise, e_prev,
              dl->effective_epsilon);
    e_prev = dl->effective_epsilon;
  }
  float raised = e_prev;
  uint64_t tris_raised = frame_tris(dl);
  CHECK_MSG(raised > 2 * eps, "40 frames at twice the target raised epsilon only to %g", raised);
  CHECK(tris_raised < tris0);
  /* back on target: after the measurement settles, constant (hysteresis) */
  int settle = -1;
  float e_last = -1;
  for (int f = 0; f < 40; ++f) {
    dl = plan(&fx, s, &v, 1, 16, target);
    CHECK(dl);
    if (dl->effective_epsilon != e_last) settle = f;
    e_last = dl->effective_epsilon;
  }
  CHECK_MSG(settle < 20, "on target, epsilon still changed at frame %d of 40", settle);
  memcpy(first, dl->levels, fx.patches);
  for (int f = 0; f < 20; ++f) {
    dl = plan(&fx, s, &v, 1, 16, target);
    CHECK(dl);
    CHECK_MSG(dl->effective_epsilon == e_last && memcmp(dl->levels, first, fx.patches) == 0,
              "steady frame %d: epsilon %g -> %g or levels flicker", f, e_last, dl->effective_epsilon);
  }
  CHECK_MSG(e_last > eps, "on target the raised epsilon %g fell back to %g (no hysteresis)", raised, e_last);
  /* unknown measurement (0): nothing changes */
  for (int f = 0; f < 5; ++f) {
    dl = plan(&fx, s, &v, 1, 16, 0);
    CHECK(dl && dl->effective_epsilon == e_last);
  }
  /* fast: epsilon falls, never below epsilon, and reaches it */
  int f_fall = 0;
  e_prev = e_last;
  for (; f_fall < 400 && e_prev != eps; ++f_fall) {
    dl = plan(&fx, s, &v, 1, 16, 0.4f * target);
    CHECK(dl);
    CHECK_MSG(dl->effective_epsilon <= e_prev && dl->effective_epsilon >= eps, "fast frame %d: epsilon %g -> %g",
              f_fall, e_prev, dl->effective_epsilon);
    e_prev = dl->effective_epsilon;
  }
  CHECK_MSG(e_prev == eps, "after %d fast frames epsilon is %g, not %g", f_fall, e_prev, eps);
  CHECK(frame_tris(dl) == tris0);
  printf("  epsilon %g: 40 frames at 2x target -> %g (%llu -> %llu triangles); on target steady after %d frames at "
         "%g; %d frames at 0.4x target -> %g\n",
         eps, raised, (unsigned long long)tris0, (unsigned long long)tris_raised, settle + 1, e_last, f_fall, e_prev);
  free(first);
  tlod_scheduler_destroy(s);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 8. Multi-view                                                            */
/* ------------------------------------------------------------------------ */

TEST(test_multi_view) {
  tlod_context* ctx = new_context(2, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(2);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PN));
  tlod_scheduler* locked = new_scheduler(
      &fx, (tlod_scheduler_desc){.epsilon_px = 0.5f, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_TIME});
  tlod_scheduler* own = new_scheduler(
      &fx, (tlod_scheduler_desc){.epsilon_px = 0.5f, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE});
  CHECK(locked && own);
  uint32_t common = 0, differ = 0, frames = 0;
  ref_stats st = {0};
  char why[256];
  for (int f = 0; f < 12; ++f) {
    double a = 0.2 * f;
    camera ca = look_from(2.2 * sin(a), 0.5, 2.2 * cos(a), 0, 0, 0); /* main view, close */
    camera cb = look_from(6 * cos(a), 2, -6 * sin(a), 0.3, 0, 0);    /* second view, far, another side */
    cb.fovy = 40 * DEG;
    tlod_view_desc views[2] = {make_view(&ca), make_view(&cb)};
    views[1].lock_to_main = true;
    view_ref rb = make_ref(&views[1], &cb);
    CHECK(plan(&fx, locked, views, 2, 16, 0));
    const tlod_draw_list *d0 = tlod_scheduler_draw_list(locked, 0), *d1 = tlod_scheduler_draw_list(locked, 1);
    CHECK(d0 && d1 && tlod_scheduler_draw_list(locked, 2) == NULL);
    CHECK_MSG(check_draw_list(&fx, d1, PAT_MAX, why, sizeof why), "locked view: %s", why);
    const tlod_draw_instance** i0 = calloc(fx.patches, sizeof *i0);
    for (uint32_t k = 0; k < d0->instance_count; ++k)
      i0[d0->instances[k].patch] = &d0->instances[k];
    for (uint32_t k = 0; k < d1->instance_count; ++k) {
      const tlod_draw_instance* in = &d1->instances[k];
      if (!i0[in->patch]) continue;
      common++;
      CHECK_MSG(in->level == i0[in->patch]->level && in->morph == i0[in->patch]->morph,
                "frame %d patch %u: locked view level %u blend %g, main view %u blend %g", f, in->patch, in->level,
                in->morph, i0[in->patch]->level, i0[in->patch]->morph);
    }
    free(i0);
    /* culling stays per view */
    for (uint32_t p = 0; p < fx.patches; ++p) {
      int cull = ref_cull(&rb, fx.info[p].center, fx.info[p].radius);
      if (cull == 1) CHECK_MSG(d1->levels[p] == -1, "frame %d: patch %u outside view 1 kept", f, p);
      if (cull == 0) CHECK_MSG(d1->levels[p] >= 0, "frame %d: patch %u inside view 1 culled", f, p);
    }
    CHECK(realise(&fx, d1, false));
    uint32_t open = 0;
    CHECK_MSG(open_only_at_culled(&fx, d1, &open, why, sizeof why), "locked view frame %d: %s", f, why);
    /* without the lock, view 1 has its own levels, by its own camera */
    views[1].lock_to_main = false;
    CHECK(plan(&fx, own, views, 2, 16, 0));
    d0 = tlod_scheduler_draw_list(own, 0), d1 = tlod_scheduler_draw_list(own, 1);
    CALL(check_levels(&fx, d1, &rb, TLOD_POLICY_ERROR, 0.5, PAT_MAX, false, "unlocked view 1", &st));
    for (uint32_t p = 0; p < fx.patches; ++p)
      differ += d0->levels[p] >= 0 && d1->levels[p] >= 0 && d0->levels[p] != d1->levels[p];
    frames++;
  }
  printf("  %u frames: %u patches visible in both views took the main view's level and blend; unlocked, %u "
         "differ and all %u of view 1's follow its own camera\n",
         frames, common, differ, st.policy_checked);
  CHECK(common > 100 && differ > 100);
  tlod_scheduler_destroy(locked);
  tlod_scheduler_destroy(own);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 9. Determinism over thread counts and schedulers                         */
/* ------------------------------------------------------------------------ */

static bool same_draw_list(const tlod_draw_list* a, const tlod_draw_list* b, uint32_t vertices, char* why, size_t n) {
  return draw_lists_equal(a, b, vertices, why, n);
}

TEST(test_determinism) {
  reverse_pool pool = {0};
  tlod_context* ctxs[3] = {new_context(1, NULL, NULL), new_context(2, NULL, NULL), new_context(0, NULL, &pool)};
  CHECK(ctxs[0] && ctxs[1] && ctxs[2]);
  shape sph = shape_icosphere(2);
  fixture fx[3];
  for (int c = 0; c < 3; ++c)
    CHECK(fixture_make(&fx[c], ctxs[c], &sph, TLOD_SURFACE_PN));
  tlod_scheduler_desc d = {.epsilon_px = 0.5f,
                           .policy = TLOD_POLICY_HYBRID,
                           .morph = TLOD_MORPH_TIME,
                           .morph_ms = 100,
                           .triangle_budget = 30000,
                           .frame_time_target_ms = 16};
  tlod_scheduler* s[4] = {new_scheduler(&fx[0], d), new_scheduler(&fx[1], d), new_scheduler(&fx[2], d),
                          new_scheduler(&fx[0], d)};
  CHECK(s[0] && s[1] && s[2] && s[3]);
  shape_rng rng = {4242};
  long pool_calls = 0;
  uint32_t compared = 0;
  char why[128];
  for (int f = 0; f < 30; ++f) {
    camera c0 = random_camera(&rng, 1.0, f % 5, f % 7 == 6), c1 = random_camera(&rng, 1.0, (f + 2) % 5, false);
    tlod_view_desc views[3] = {make_view(&c0), make_view(&c1), make_view(&c1)};
    views[2].lock_to_main = true;
    float dt = (float)shape_rng_range(&rng, 0, 50), measured = (float)shape_rng_range(&rng, 5, 40);
    for (int k = 0; k < 4; ++k) {
      long before = pool.calls;
      CHECK(plan(&fx[k == 3 ? 0 : k], s[k], views, 3, dt, measured));
      if (k == 2) pool_calls += pool.calls - before;
    }
    for (uint32_t view = 0; view < 3; ++view)
      for (int k = 1; k < 4; ++k) {
        CHECK_MSG(same_draw_list(tlod_scheduler_draw_list(s[0], view), tlod_scheduler_draw_list(s[k], view),
                                 fx[0].vertices, why, sizeof why),
                  "frame %d view %u: %s vs 1 thread: %s", f, view,
                  k == 1   ? "2 threads"
                  : k == 2 ? "reversed custom parallel-for"
                           : "a second scheduler",
                  why);
        compared++;
      }
  }
  printf("  %u draw lists bitwise equal (1 thread, 2 threads, reversed parallel-for, second scheduler); the "
         "scheduler called the custom parallel-for %ld times\n",
         compared, pool_calls);
  CHECK_MSG(pool_calls > 0, "the scheduler never used the context's parallel-for");
  for (int k = 0; k < 4; ++k)
    tlod_scheduler_destroy(s[k]);
  for (int c = 0; c < 3; ++c) {
    fixture_free(&fx[c]);
    tlod_context_destroy(ctxs[c]);
  }
  shape_free(&sph);
}

/* ------------------------------------------------------------------------ */
/* 10. Dynamic meshes                                                       */
/* ------------------------------------------------------------------------ */

/* An icosphere whose faces own their corners (positions and normals
 * duplicated bitwise, so every edge is still smooth). */
static shape soup_icosphere(uint32_t subdivisions) {
  shape ico = shape_icosphere(subdivisions), out;
  uint32_t faces = shape_face_count(&ico);
  shape_alloc(&out, "ico_soup", 3 * faces, 3 * faces, 3, true);
  for (uint32_t k = 0; k < 3 * faces; ++k) {
    memcpy(out.positions + 3 * k, ico.positions + 3 * ico.indices[k], 3 * sizeof(float));
    memcpy(out.normals + 3 * k, ico.normals + 3 * ico.indices[k], 3 * sizeof(float));
    out.indices[k] = k;
  }
  out.closed = true;
  shape_free(&ico);
  return out;
}

/* e_max of every visible patch against the reference from the patch data
 * the surface holds now; returns the count that match. */
static uint32_t emax_matches(const fixture* fx, const tlod_draw_list* dl, const view_ref* r,
                             const tlod_patch_info* info) {
  uint32_t ok = 0;
  for (uint32_t p = 0; p < fx->patches; ++p) {
    if (dl->levels[p] < 0) continue;
    double e = ref_emax(r, &info[p]);
    ok += fabs(dl->e_max[p] - e) <= 1e-5 * e + 1e-9;
  }
  return ok;
}

TEST(test_dynamic_mesh) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape soup = soup_icosphere(1);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &soup, TLOD_SURFACE_PHONG));
  tlod_scheduler* s = new_scheduler(
      &fx, (tlod_scheduler_desc){
               .epsilon_px = 0.5f, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE, .no_frustum_cull = true});
  CHECK(s);
  camera c = look_from(0.4, 0.7, 3.0, 0, 0, 0);
  tlod_view_desc v = make_view(&c);
  view_ref r = make_ref(&v, &c);
  char why[256];
  const tlod_draw_list* dl = plan(&fx, s, &v, 1, 16, 0);
  CHECK(dl);
  CHECK(emax_matches(&fx, dl, &r, fx.info) == fx.patches);
  uint64_t tris_smooth = dl->pattern_triangles;
  CHECK(tris_smooth > fx.patches);
  tlod_patch_info* before = malloc(sizeof *before * fx.patches);
  memcpy(before, fx.info, sizeof *before * fx.patches);
  /* (a) flatten: every corner takes its face normal -> flat Phong patches */
  float* flat = malloc(sizeof(float) * 3 * soup.vertex_count);
  for (uint32_t f = 0; f < fx.patches; ++f) {
    const float* p = soup.positions + 9 * f;
    double e1[3] = {p[3] - p[0], p[4] - p[1], p[5] - p[2]}, e2[3] = {p[6] - p[0], p[7] - p[1], p[8] - p[2]}, n[3];
    cross3(e1, e2, n);
    shape_normalize3(n);
    for (int k = 0; k < 3; ++k)
      for (int q = 0; q < 3; ++q)
        flat[9 * f + 3 * k + q] = (float)n[q];
  }
  CHECK(tlod_mesh_update(fx.mesh, NULL, 0, flat, 0) == TLOD_SUCCESS);
  uint32_t updated = 0;
  CHECK(tlod_surface_refresh(fx.surf, &updated) == TLOD_SUCCESS);
  CHECK_MSG(updated == fx.patches, "refresh recomputed %u of %u patches", updated, fx.patches);
  fixture_read(&fx);
  dl = plan(&fx, s, &v, 1, 16, 0);
  CHECK(dl);
  CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "flattened: %s", why);
  uint32_t fresh = emax_matches(&fx, dl, &r, fx.info), stale = emax_matches(&fx, dl, &r, before);
  CHECK_MSG(fresh == fx.patches, "flattened: %u of %u e_max match the refreshed bounds (%u the old ones)", fresh,
            fx.patches, stale);
  CHECK(stale == 0);
  uint32_t creases = 0;
  for (uint32_t p = 0; p < fx.patches; ++p)
    for (int e = 0; e < 3; ++e)
      creases += !fx.link[p][e].smooth;
  printf("  flattened normals: error bounds %.3g -> %.3g, %llu -> %llu pattern triangles, %u crease edge sides\n",
         before[0].error_bound, fx.info[0].error_bound, (unsigned long long)tris_smooth,
         (unsigned long long)dl->pattern_triangles, creases);
  CHECK(dl->pattern_triangles < tris_smooth);
  CHECK(realise(&fx, dl, false));
  CHECK_MSG(realised_closed(&fx, why, sizeof why), "flattened: %s", why);
  /* (b) restore the normals and move the vertices: twice the size */
  float* big = malloc(sizeof(float) * 3 * soup.vertex_count);
  for (uint32_t k = 0; k < 3 * soup.vertex_count; ++k)
    big[k] = 2.0f * soup.positions[k];
  memcpy(before, fx.info, sizeof *before * fx.patches);
  CHECK(tlod_mesh_update(fx.mesh, big, 0, soup.normals, 0) == TLOD_SUCCESS);
  CHECK(tlod_surface_refresh(fx.surf, &updated) == TLOD_SUCCESS);
  fixture_read(&fx);
  dl = plan(&fx, s, &v, 1, 16, 0);
  CHECK(dl);
  fresh = emax_matches(&fx, dl, &r, fx.info);
  CHECK_MSG(fresh == fx.patches, "moved: %u of %u e_max match the refreshed bounds", fresh, fx.patches);
  CHECK(fabs(fx.info[0].radius - 2 * before[0].radius) > 0.1 * before[0].radius);
  printf("  moved (x2): error bound %.4g, e_max range %.3g..%.3g, %llu pattern triangles (smooth at x1: %llu)\n",
         fx.info[0].error_bound, dl->e_max_min, dl->e_max_max, (unsigned long long)dl->pattern_triangles,
         (unsigned long long)tris_smooth);
  CHECK(dl->pattern_triangles > tris_smooth);
  free(big);
  free(flat);
  free(before);
  tlod_scheduler_destroy(s);
  fixture_free(&fx);
  shape_free(&soup);
  /* (c) cost of tlod_mesh_update + tlod_surface_refresh, 100k vertices */
  shape tor = shape_torus(316, 316);
  tlod_mesh* mesh = NULL;
  tlod_surface* surf = NULL;
  tlod_mesh_desc md = shape_mesh_desc(&tor);
  CHECK(tlod_mesh_create(ctx, &md, &mesh) == TLOD_SUCCESS);
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &surf) == TLOD_SUCCESS);
  float* moved = malloc(sizeof(float) * 3 * tor.vertex_count);
  double all_u = 1e30, all_r = 1e30, some_u = 1e30, some_r = 1e30;
  uint32_t some = 0, some_patches = 0;
  for (int rep = 0; rep < 3; ++rep) {
    for (uint32_t k = 0; k < 3 * tor.vertex_count; ++k)
      moved[k] = tor.positions[k] * (1.0f + 0.001f * (float)(rep + 1) * (float)((k * 7919u) % 13u) / 13.0f);
    double t0 = now_seconds();
    CHECK(tlod_mesh_update(mesh, moved, 0, NULL, 0) == TLOD_SUCCESS);
    double t1 = now_seconds();
    CHECK(tlod_surface_refresh(surf, &updated) == TLOD_SUCCESS);
    double t2 = now_seconds();
    CHECK(updated == tlod_surface_patch_count(surf));
    all_u = fmin(all_u, t1 - t0), all_r = fmin(all_r, t2 - t1);
    /* 1% of the vertices move */
    some = 0;
    for (uint32_t vtx = 0; vtx < tor.vertex_count; vtx += 100, ++some)
      moved[3 * vtx] += 0.001f;
    t0 = now_seconds();
    CHECK(tlod_mesh_update(mesh, moved, 0, NULL, 0) == TLOD_SUCCESS);
    t1 = now_seconds();
    CHECK(tlod_surface_refresh(surf, &some_patches) == TLOD_SUCCESS);
    t2 = now_seconds();
    CHECK(some_patches < updated / 10);
    some_u = fmin(some_u, t1 - t0), some_r = fmin(some_r, t2 - t1);
  }
  printf("  %u vertices, %u patches [this build]: every vertex moved: update %.1f + refresh %.1f ms = %.0f ns per "
         "vertex; %u vertices moved (%u patches refreshed): update %.2f + refresh %.2f ms = %.0f ns per moved vertex\n",
         tor.vertex_count, tlod_surface_patch_count(surf), 1e3 * all_u, 1e3 * all_r,
         1e9 * (all_u + all_r) / tor.vertex_count, some, some_patches, 1e3 * some_u, 1e3 * some_r,
         1e9 * (some_u + some_r) / some);
  free(moved);
  tlod_surface_destroy(surf);
  tlod_mesh_destroy(mesh);
  shape_free(&tor);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* 11. Bad input, allocation                                                */
/* ------------------------------------------------------------------------ */

/* Sets a recognisable last error, then expects `expr` to fail with
 * TLOD_ERROR_INVALID_ARGUMENT and a new, non-empty message. */
#define EXPECT_INVALID(ctx, expr, what)                                                                                \
  do {                                                                                                                 \
    tlod_patterns* _p = NULL;                                                                                          \
    tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 99}, &_p); /* sets a message of its own */            \
    tlod_patterns_destroy(_p);                                                                                         \
    char _before[512];                                                                                                 \
    snprintf(_before, sizeof _before, "%s", tlod_context_last_error(ctx));                                             \
    tlod_result _r = (expr);                                                                                           \
    const char* _msg = tlod_context_last_error(ctx);                                                                   \
    printf("    %-34s %s \"%s\"\n", what, tlod_result_string(_r), _msg);                                               \
    CHECK_MSG(_r == TLOD_ERROR_INVALID_ARGUMENT, "%s: %s", what, tlod_result_string(_r));                              \
    CHECK_MSG(strlen(_msg) > 0 && strcmp(_msg, _before) != 0, "%s: no message of its own", what);                      \
  } while (0)

TEST(test_bad_input) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(1);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PHONG));
  tlod_scheduler* s = NULL;
  tlod_scheduler* bogus = (tlod_scheduler*)&fx;
  struct {
    const char* what;
    tlod_scheduler_desc d;
  } bad[] = {
      {"epsilon -1", {.epsilon_px = -1}},
      {"epsilon NaN", {.epsilon_px = NAN}},
      {"epsilon inf", {.epsilon_px = INFINITY}},
      {"max_level above the patterns", {.max_level = PAT_MAX + 1}},
      {"unknown policy", {.policy = (tlod_lod_policy)17}},
      {"unknown morph mode", {.morph = (tlod_morph_mode)9}},
      {"morph_ms -5", {.morph_ms = -5}},
      {"silhouette_depth -1", {.silhouette_depth = -1}},
      {"hybrid_relax 0.5", {.hybrid_relax = 0.5f}},
      {"frame_time_target_ms NaN", {.frame_time_target_ms = NAN}},
  };
  printf("  scheduler_create:\n");
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    bogus = (tlod_scheduler*)&fx;
    EXPECT_INVALID(ctx, tlod_scheduler_create(ctx, fx.surf, fx.pat, &bad[k].d, &bogus), bad[k].what);
    CHECK_MSG(bogus == NULL, "%s: *out not cleared", bad[k].what);
  }
  EXPECT_INVALID(ctx, tlod_scheduler_create(ctx, NULL, fx.pat, NULL, &s), "NULL surface");
  EXPECT_INVALID(ctx, tlod_scheduler_create(ctx, fx.surf, NULL, NULL, &s), "NULL patterns");
  EXPECT_INVALID(ctx, tlod_scheduler_create(ctx, fx.surf, fx.pat, NULL, NULL), "NULL out");
  CHECK(tlod_scheduler_create(NULL, fx.surf, fx.pat, NULL, &s) == TLOD_ERROR_INVALID_ARGUMENT && s == NULL);
  CHECK(tlod_scheduler_create(ctx, fx.surf, fx.pat, NULL, &s) == TLOD_SUCCESS && s); /* NULL desc: defaults */
  camera c = look_from(0, 0, 3, 0, 0, 0);
  tlod_view_desc good = make_view(&c), views[2];
  printf("  scheduler_update:\n");
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, NULL), "NULL frame");
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = &good, .view_count = 0}), "zero views");
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = NULL, .view_count = 1}), "NULL views");
  views[0] = good, views[0].view[13] = NAN;
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 1}), "NaN view");
  views[0] = good, views[0].proj[0] = INFINITY;
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 1}), "inf proj");
  views[0] = good, views[1] = good, views[1].proj[14] = -NAN;
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 2}),
                 "NaN in the second view");
  views[0] = good, views[0].viewport_width = 0;
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 1}),
                 "zero viewport width");
  views[0] = good, views[0].viewport_height = 0;
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 1}),
                 "zero viewport height");
  EXPECT_INVALID(ctx, tlod_scheduler_update(s, &(tlod_frame_desc){.views = &good, .view_count = 1, .dt_ms = NAN}),
                 "dt NaN");
  CHECK(tlod_scheduler_update(NULL, &(tlod_frame_desc){.views = &good, .view_count = 1}) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  /* a bad measurement is ignored, not fatal; then a good frame works */
  CHECK(tlod_scheduler_update(s, &(tlod_frame_desc){.views = &good, .view_count = 1, .measured_frame_ms = NAN}) ==
        TLOD_SUCCESS);
  const tlod_draw_list* dl = tlod_scheduler_draw_list(s, 0);
  char why[256];
  CHECK(dl && tlod_scheduler_draw_list(s, 1) == NULL && tlod_scheduler_draw_list(NULL, 0) == NULL);
  CHECK_MSG(check_draw_list(&fx, dl, PAT_MAX, why, sizeof why), "%s", why);
  CHECK(isfinite(dl->effective_epsilon) && dl->effective_epsilon == 0.5f);
  tlod_scheduler_destroy(s);
  tlod_scheduler_destroy(NULL);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
}

/* Scheduler create + frames of 1, 3 and 2 views under a counting allocator. */
static tlod_result scheduler_session(fixture* fx, tlod_scheduler** out, const tlod_view_desc* views) {
  tlod_result r = tlod_scheduler_create(fx->ctx, fx->surf, fx->pat,
                                        &(tlod_scheduler_desc){.epsilon_px = 0.3f, .triangle_budget = 20000}, out);
  if (r != TLOD_SUCCESS) return r;
  static const uint32_t counts[3] = {1, 3, 2};
  for (int f = 0; f < 3 && r == TLOD_SUCCESS; ++f)
    r = tlod_scheduler_update(*out, &(tlod_frame_desc){.views = views, .view_count = counts[f], .dt_ms = 16});
  return r;
}

TEST(test_allocation) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  CHECK(ctx);
  shape sph = shape_icosphere(2);
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PN));
  camera cams[3] = {look_from(0, 0, 2.2, 0, 0, 0), look_from(3, 1, 0, 0, 0, 0), look_from(0, -4, 1, 0, 0, 0)};
  tlod_view_desc views[3] = {make_view(&cams[0]), make_view(&cams[1]), make_view(&cams[2])};
  views[2].lock_to_main = true;
  long live = counter.allocs - counter.frees;
  tlod_scheduler* s = NULL;
  CHECK(scheduler_session(&fx, &s, views) == TLOD_SUCCESS);
  tlod_scheduler_destroy(s);
  CHECK_MSG(counter.allocs - counter.frees == live, "scheduler leaked %ld allocations",
            counter.allocs - counter.frees - live);
  /* fail the k-th allocation (and, in a second sweep, every one after it) */
  uint32_t points[2] = {0, 0}, recovered = 0;
  for (int sweep = 0; sweep < 2; ++sweep) {
    bool done = false;
    for (uint32_t k = 0; k < 2000 && !done; ++k) {
      counter.fail_at = counter.calls + k;
      counter.fail_all = sweep == 1;
      counter.failed = 0;
      s = NULL;
      tlod_result r = scheduler_session(&fx, &s, views);
      long failed = counter.failed;
      counter.fail_at = -1;
      if (r == TLOD_SUCCESS) {
        CHECK_MSG(failed == 0, "k = %u: success although %ld allocations failed", k, failed);
        done = true;
      } else {
        CHECK_MSG(r == TLOD_ERROR_OUT_OF_MEMORY, "k = %u: %s", k, tlod_result_string(r));
        if (s) { /* the scheduler survived: with memory back, a frame must work */
          tlod_result again =
              tlod_scheduler_update(s, &(tlod_frame_desc){.views = views, .view_count = 3, .dt_ms = 16});
          CHECK_MSG(again == TLOD_SUCCESS, "k = %u: after a failed update, the next one gives %s: %s", k,
                    tlod_result_string(again), tlod_context_last_error(ctx));
          char why[256];
          for (uint32_t vw = 0; vw < 3; ++vw)
            CHECK_MSG(check_draw_list(&fx, tlod_scheduler_draw_list(s, vw), PAT_MAX, why, sizeof why),
                      "k = %u view %u after recovery: %s", k, vw, why);
          recovered++;
        }
      }
      tlod_scheduler_destroy(s);
      CHECK_MSG(counter.allocs - counter.frees == live, "k = %u: %ld allocations leaked", k,
                counter.allocs - counter.frees - live);
      points[sweep] = k;
    }
    CHECK(done);
  }
  printf("  balanced; failing allocator: %u and %u allocation points swept, %u failed sessions recovered\n", points[0],
         points[1], recovered);
  CHECK(points[0] > 3);
  fixture_free(&fx);
  shape_free(&sph);
  tlod_context_destroy(ctx);
  CHECK_MSG(counter.allocs == counter.frees, "%ld allocations, %ld frees", counter.allocs, counter.frees);
}

/* With arguments, only the tests selected by one of them run: "=NAME" the
 * test NAME, any other argument the tests whose name contains it. ctest runs
 * this file as shards (tests/CMakeLists.txt) so the slow tests spread over
 * the cores; a selection that runs nothing fails. */
static bool selected(const char* name, int argc, char** argv) {
  if (argc < 2) return true;
  for (int a = 1; a < argc; ++a)
    if (argv[a][0] == '=' ? strcmp(name, argv[a] + 1) == 0 : strstr(name, argv[a]) != NULL) return true;
  return false;
}
static int g_selected_runs;
#define RUN_SELECTED(name)                                                                                             \
  do {                                                                                                                 \
    if (selected(#name, argc, argv)) {                                                                                 \
      g_selected_runs++;                                                                                               \
      RUN(name);                                                                                                       \
    }                                                                                                                  \
  } while (0)

int main(int argc, char** argv) {
  double t0 = now_seconds();
  RUN_SELECTED(test_pure_helpers);
  RUN_SELECTED(test_level_choice);
  RUN_SELECTED(test_policy_rules);
  RUN_SELECTED(test_crack_free);
  RUN_SELECTED(test_creases);
  RUN_SELECTED(test_geomorph_starts_at_coarse_level);
  RUN_SELECTED(test_geomorph_continuity);
  RUN_SELECTED(test_geomorph_continuous);
  RUN_SELECTED(test_projection_scale);
  RUN_SELECTED(test_screen_error);
  RUN_SELECTED(test_screen_error_closed_form);
  RUN_SELECTED(test_monotone_and_budget);
  RUN_SELECTED(test_frame_time_target);
  RUN_SELECTED(test_multi_view);
  RUN_SELECTED(test_determinism);
  RUN_SELECTED(test_dynamic_mesh);
  RUN_SELECTED(test_bad_input);
  RUN_SELECTED(test_allocation);
  printf("%.1f s\n", now_seconds() - t0);
  if (g_selected_runs == 0) {
    fprintf(stderr, "no test matches the selection\n");
    return 1;
  }
  TEST_END();
}
