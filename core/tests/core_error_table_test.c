/*
 * core_error_table_test.c -- the per-level error tables of tesslod/core.h
 * (issue #9) against the densely sampled true deviation, and the
 * per-vertex-alpha Phong net against the surface it stands for.
 * Reads private state: surface_eval.h (_tlod_phong_alpha_net; the scalar
 * Phong quad path, the oracle of the lanes in test_quad_lanes_bitwise).
 *
 * The true deviation of level l is measured independently of the table's
 * maths: the surface (tlod_surface_eval, float, as the renderer sees it) on a
 * dense barycentric grid inside every level-l pattern triangle (triangles:
 * the 4^l cells; quads: 2 * 4^l, diagonal (a,b)-(a+1,b+1) as
 * lod/src/pattern_refine.c draws them) minus the linear interpolation (in
 * double) of the triangle's corner surface points. Grid: 16 segments per
 * cell edge at levels 0..2, 8 at 3, 4 at 4..6 (the table's own sampling is
 * 4 per cell edge at levels 0..2 for triangles and 1/8 of the patch for quads).
 *
 * Tolerance: bound >= dense - 1e-12 * scale. The table includes a slack for
 * the float rounding of the evaluation, so what is left is the rounding of
 * the test's own double interpolation (a few 1e-16 relative).
 */
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "surface_eval.h"
#include "tesslod/core.h"
#include "test.h"

#define MAX_TEST_LEVEL 6
/* Every patch in release builds; under the sanitizers (10-20x slower) every
 * k-th, which still exercises every code path with memory checks. */
#ifndef TLOD_TEST_PATCH_STEP
#define TLOD_TEST_PATCH_STEP 1
#endif
#define TOL_REL 1e-12

static tlod_context* new_context(void) {
  tlod_context* ctx = NULL;
  tlod_context_desc desc = {.thread_count = 1};
  return tlod_context_create(&desc, &ctx) == TLOD_SUCCESS ? ctx : NULL;
}

/* ------------------------------------------------------------------------ */
/* Meshes: plain arrays                                                     */
/* ------------------------------------------------------------------------ */

typedef struct mesh_data {
  const char* name;
  float *positions, *normals, *alphas; /* normals may be NULL (computed) */
  uint32_t* indices;
  uint8_t* sizes;
  uint32_t vertex_count, index_count, face_count;
  bool has_quads;
} mesh_data;

static void mesh_data_free(mesh_data* m) {
  free(m->positions), free(m->normals), free(m->alphas), free(m->indices), free(m->sizes);
  memset(m, 0, sizeof *m);
}

static void random_alphas(mesh_data* m, uint64_t seed) {
  shape_rng rng = {seed};
  m->alphas = malloc(sizeof(float) * m->vertex_count);
  for (uint32_t v = 0; v < m->vertex_count; v++)
    m->alphas[v] = (float)shape_rng_unit(&rng);
}

static void d_sub(double o[3], const double a[3], const double b[3]) {
  for (int c = 0; c < 3; c++)
    o[c] = a[c] - b[c];
}
static double d_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void d_cross(double o[3], const double a[3], const double b[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static void d_normalize(double a[3]) {
  double l = sqrt(d_dot(a, a));
  for (int c = 0; c < 3; c++)
    a[c] /= l;
}

/* Independent random patches: well-shaped triangles or jittered
 * parallelograms; corner normals the face normal tilted by up to
 * max_tilt_deg about a random tangent axis; every fourth patch has one
 * corner normal facing away from the others' side (tilted the other way). */
static mesh_data random_patches(uint64_t seed, uint32_t count, uint32_t corners, double max_tilt_deg) {
  shape_rng rng = {seed};
  mesh_data m = {0};
  m.name = corners == 3 ? "random triangles" : "random quads";
  m.vertex_count = m.index_count = count * corners;
  m.face_count = count;
  m.has_quads = corners == 4;
  m.positions = malloc(sizeof(float) * 3 * m.vertex_count);
  m.normals = malloc(sizeof(float) * 3 * m.vertex_count);
  m.indices = malloc(sizeof(uint32_t) * m.index_count);
  m.sizes = malloc(count);
  for (uint32_t f = 0; f < count; f++) {
    double p[4][3];
    for (;;) {
      if (corners == 3) {
        for (int x = 0; x < 3; x++)
          for (int c = 0; c < 3; c++)
            p[x][c] = shape_rng_range(&rng, -1, 1);
      } else {
        double o[3], a[3], b[3], la = shape_rng_range(&rng, 0.5, 1.2), lb = shape_rng_range(&rng, 0.5, 1.2);
        shape_rng_direction(&rng, a);
        shape_rng_direction(&rng, b);
        for (int c = 0; c < 3; c++) {
          o[c] = shape_rng_range(&rng, -0.5, 0.5);
          p[0][c] = o[c], p[1][c] = o[c] + la * a[c], p[2][c] = o[c] + la * a[c] + lb * b[c],
          p[3][c] = o[c] + lb * b[c];
        }
        for (int x = 0; x < 4; x++)
          for (int c = 0; c < 3; c++)
            p[x][c] += shape_rng_range(&rng, -0.15, 0.15);
      }
      bool ok = true;
      for (uint32_t x = 0; x < corners && ok; x++) {
        double e1[3], e2[3];
        d_sub(e1, p[(x + 1) % corners], p[x]);
        d_sub(e2, p[(x + corners - 1) % corners], p[x]);
        double ca = d_dot(e1, e2) / sqrt(d_dot(e1, e1) * d_dot(e2, e2));
        if (!(ca < cos(15.0 * SHAPES_PI / 180.0)) || ca < cos(165.0 * SHAPES_PI / 180.0) || d_dot(e1, e1) < 0.04)
          ok = false;
      }
      if (ok) break;
    }
    double fn[3], e1[3], e2[3];
    d_sub(e1, corners == 3 ? p[1] : p[2], p[0]);
    d_sub(e2, corners == 3 ? p[2] : p[3], corners == 3 ? p[0] : p[1]);
    d_cross(fn, e1, e2);
    d_normalize(fn);
    for (uint32_t x = 0; x < corners; x++) {
      uint32_t vi = f * corners + x;
      double d[3], axis[3], n[3];
      shape_rng_direction(&rng, d);
      d_cross(axis, fn, d); /* a tangent direction */
      d_normalize(axis);
      double ang = shape_rng_unit(&rng) * max_tilt_deg * SHAPES_PI / 180.0;
      if (f % 4 == 3 && x == 0) ang = max_tilt_deg * SHAPES_PI / 180.0;
      for (int c = 0; c < 3; c++)
        n[c] = cos(ang) * fn[c] + sin(ang) * axis[c];
      for (int c = 0; c < 3; c++) {
        m.positions[3 * vi + c] = (float)p[x][c];
        m.normals[3 * vi + c] = (float)n[c];
      }
      m.indices[vi] = vi;
    }
    m.sizes[f] = (uint8_t)corners;
  }
  random_alphas(&m, seed + 1);
  return m;
}

/* Pairs of triangles folded back along their shared edge (dihedral ~170
 * degrees): computed normals then stand ~85 degrees off each face and the
 * two faces face opposite ways. */
static mesh_data folded_pairs(uint64_t seed, uint32_t count) {
  shape_rng rng = {seed};
  mesh_data m = {0};
  m.name = "folded pairs";
  m.vertex_count = 4 * count;
  m.index_count = 6 * count;
  m.face_count = 2 * count;
  m.positions = malloc(sizeof(float) * 3 * m.vertex_count);
  m.indices = malloc(sizeof(uint32_t) * m.index_count);
  m.sizes = malloc(m.face_count);
  for (uint32_t k = 0; k < count; k++) {
    double fold = shape_rng_range(&rng, 160.0, 175.0) * SHAPES_PI / 180.0;
    double a = shape_rng_range(&rng, 0.5, 1.5), b = shape_rng_range(&rng, 0.5, 1.5);
    double q[4][3] = {{0, 0, 0}, {1, 0, 0}, {0.4, a, 0}, {0.6, b * cos(fold), b * sin(fold)}};
    for (int x = 0; x < 4; x++)
      for (int c = 0; c < 3; c++)
        m.positions[3 * (4 * k + (uint32_t)x) + (uint32_t)c] = (float)q[x][c];
    uint32_t idx[6] = {0, 1, 2, 1, 0, 3};
    for (int x = 0; x < 6; x++)
      m.indices[6 * k + (uint32_t)x] = 4 * k + idx[x];
    m.sizes[2 * k] = m.sizes[2 * k + 1] = 3;
  }
  random_alphas(&m, seed + 1);
  return m;
}

/* OBJ: v, vn, f with v, v//vn, v/vt/vn, negative indices. A vertex per
 * distinct (v, vn) pair. */
static bool load_obj(const char* path, mesh_data* m) {
  FILE* f = fopen(path, "r");
  if (!f) return false;
  memset(m, 0, sizeof *m);
  m->name = path;
  size_t vc = 0, vcap = 1024, nc = 0, ncap = 1024, ic = 0, icap = 4096, fc = 0, fcap = 1024;
  double* v = malloc(sizeof(double) * 3 * vcap);
  double* vn = malloc(sizeof(double) * 3 * ncap);
  int* pairs = malloc(sizeof(int) * 2 * icap);
  m->sizes = malloc(fcap);
  char line[512];
  while (fgets(line, sizeof line, f)) {
    if (line[0] == 'v' && line[1] == ' ') {
      if (vc == vcap) v = realloc(v, sizeof(double) * 3 * (vcap *= 2));
      sscanf(line + 2, "%lf %lf %lf", &v[3 * vc], &v[3 * vc + 1], &v[3 * vc + 2]);
      vc++;
    } else if (line[0] == 'v' && line[1] == 'n') {
      if (nc == ncap) vn = realloc(vn, sizeof(double) * 3 * (ncap *= 2));
      sscanf(line + 3, "%lf %lf %lf", &vn[3 * nc], &vn[3 * nc + 1], &vn[3 * nc + 2]);
      nc++;
    } else if (line[0] == 'f' && line[1] == ' ') {
      char* s = line + 2;
      int n = 0;
      while (*s && n < 4) {
        while (*s == ' ' || *s == '\t')
          s++;
        if (!*s || *s == '\n' || *s == '\r') break;
        int a = (int)strtol(s, &s, 10), c = 0;
        if (*s == '/') {
          s++;
          if (*s != '/') strtol(s, &s, 10);
          if (*s == '/') s++, c = (int)strtol(s, &s, 10);
        }
        if (a < 0) a += (int)vc + 1;
        if (c < 0) c += (int)nc + 1;
        if (ic == icap) pairs = realloc(pairs, sizeof(int) * 2 * (icap *= 2));
        pairs[2 * ic] = a - 1, pairs[2 * ic + 1] = c - 1;
        ic++, n++;
        while (*s && *s != ' ' && *s != '\t' && *s != '\n')
          s++;
      }
      if (fc == fcap) m->sizes = realloc(m->sizes, (fcap *= 2));
      m->sizes[fc++] = (uint8_t)n;
      m->has_quads |= n == 4;
    }
  }
  fclose(f);
  /* one output vertex per index (simple; the mesh welds equal positions) */
  m->vertex_count = m->index_count = (uint32_t)ic;
  m->face_count = (uint32_t)fc;
  m->positions = malloc(sizeof(float) * 3 * ic);
  m->normals = nc ? malloc(sizeof(float) * 3 * ic) : NULL;
  m->indices = malloc(sizeof(uint32_t) * ic);
  for (size_t k = 0; k < ic; k++) {
    for (int c = 0; c < 3; c++) {
      m->positions[3 * k + (size_t)c] = (float)v[3 * pairs[2 * k] + c];
      if (nc) m->normals[3 * k + (size_t)c] = (float)vn[3 * (pairs[2 * k + 1] < 0 ? 0 : pairs[2 * k + 1]) + c];
    }
    m->indices[k] = (uint32_t)k;
  }
  free(v), free(vn), free(pairs);
  random_alphas(m, 77);
  return true;
}

/* The Duck's one primitive (positions 2, normals 1, indices 0, u16). */
static char* read_all(const char* path, long* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  fseek(f, 0, SEEK_SET);
  char* b = malloc((size_t)*size + 1);
  size_t got = fread(b, 1, (size_t)*size, f);
  b[got] = 0;
  fclose(f);
  return b;
}

/* n-th object of the JSON array named key: the object's text span. */
static const char* json_nth(const char* json, const char* key, int n, const char** end) {
  const char* s = strstr(json, key);
  if (!s) return NULL;
  s = strchr(s, '[');
  int depth = 0, index = -1;
  for (; *s; s++) {
    if (*s == '{') {
      if (depth == 1) index++;
      if (depth == 1 && index == n) {
        const char* b = s;
        int d = 0;
        for (; *s; s++) {
          d += *s == '{', d -= *s == '}';
          if (d == 0) break;
        }
        *end = s;
        return b;
      }
      depth++;
    } else if (*s == '[') {
      depth++;
    } else if (*s == '}' || *s == ']') {
      if (--depth == 0) break;
    }
  }
  return NULL;
}

static long json_int(const char* b, const char* e, const char* key, long fallback) {
  char k[64];
  snprintf(k, sizeof k, "\"%s\"", key);
  const char* s = strstr(b, k);
  if (!s || s > e) return fallback;
  s = strchr(s, ':');
  return strtol(s + 1, NULL, 10);
}

static bool load_duck(const char* dir, mesh_data* m) {
  char path[512];
  long jsize, bsize;
  snprintf(path, sizeof path, "%s/Duck.gltf", dir);
  char* json = read_all(path, &jsize);
  snprintf(path, sizeof path, "%s/Duck0.bin", dir);
  char* bin = read_all(path, &bsize);
  if (!json || !bin) return free(json), free(bin), false;
  memset(m, 0, sizeof *m);
  m->name = "Duck";
  const char *e, *a;
  long view[3], offset[3], count[3];
  int acc[3] = {2, 1, 0}; /* POSITION, NORMAL, indices (checked below) */
  if (!strstr(json, "\"POSITION\": 2") && !strstr(json, "\"POSITION\":2")) return free(json), free(bin), false;
  for (int k = 0; k < 3; k++) {
    a = json_nth(json, "\"accessors\"", acc[k], &e);
    view[k] = json_int(a, e, "bufferView", 0), offset[k] = json_int(a, e, "byteOffset", 0);
    count[k] = json_int(a, e, "count", 0);
    const char* vb = json_nth(json, "\"bufferViews\"", (int)view[k], &e);
    offset[k] += json_int(vb, e, "byteOffset", 0);
  }
  m->vertex_count = (uint32_t)count[0];
  m->index_count = (uint32_t)count[2];
  m->face_count = m->index_count / 3;
  m->positions = malloc(sizeof(float) * 3 * m->vertex_count);
  m->normals = malloc(sizeof(float) * 3 * m->vertex_count);
  m->indices = malloc(sizeof(uint32_t) * m->index_count);
  memcpy(m->positions, bin + offset[0], sizeof(float) * 3 * m->vertex_count);
  memcpy(m->normals, bin + offset[1], sizeof(float) * 3 * m->vertex_count);
  for (uint32_t k = 0; k < m->index_count; k++) {
    uint16_t i;
    memcpy(&i, bin + offset[2] + 2 * k, 2);
    m->indices[k] = i;
  }
  free(json), free(bin);
  random_alphas(m, 78);
  return true;
}

static tlod_mesh* make_mesh(tlod_context* ctx, const mesh_data* d) {
  tlod_mesh_desc md = {.positions = d->positions,
                       .normals = d->normals,
                       .alphas = d->alphas,
                       .vertex_count = d->vertex_count,
                       .indices = d->indices,
                       .index_count = d->index_count,
                       .normal_mode = d->normals ? TLOD_NORMALS_KEEP : TLOD_NORMALS_ANGLE,
                       .label = d->name};
  bool mixed = false;
  for (uint32_t f = 0; d->sizes && f < d->face_count; f++)
    mixed |= d->sizes[f] != d->sizes[0];
  if (mixed) {
    md.face_type = TLOD_FACE_MIXED, md.face_sizes = d->sizes, md.face_count = d->face_count;
  } else {
    md.face_type = (d->sizes ? d->sizes[0] : 3) == 4 ? TLOD_FACE_QUADS : TLOD_FACE_TRIANGLES;
  }
  tlod_mesh* mesh = NULL;
  if (tlod_mesh_create(ctx, &md, &mesh) != TLOD_SUCCESS) {
    fprintf(stderr, "mesh %s: %s\n", d->name, tlod_context_last_error(ctx));
    return NULL;
  }
  return mesh;
}

/* ------------------------------------------------------------------------ */
/* Dense true deviation                                                     */
/* ------------------------------------------------------------------------ */

static void eval_d(const tlod_surface* s, uint32_t f, double u, double v, double out[3]) {
  tlod_surface_point pt;
  tlod_surface_eval(s, f, (float)u, (float)v, &pt);
  for (int c = 0; c < 3; c++)
    out[c] = pt.position[c];
}

/* max over a triangle with (u, v) corners c[3] of |S - interpolant|, on a
 * barycentric grid of d segments. */
static double tri_dev(const tlod_surface* s, uint32_t f, const double c[3][2], int d) {
  double p[3][3], worst = 0;
  for (int x = 0; x < 3; x++)
    eval_d(s, f, c[x][0], c[x][1], p[x]);
  for (int i = 0; i <= d; i++) {
    for (int j = 0; i + j <= d; j++) {
      double b1 = (double)i / d, b2 = (double)j / d, b0 = 1.0 - b1 - b2;
      double u = b0 * c[0][0] + b1 * c[1][0] + b2 * c[2][0], v = b0 * c[0][1] + b1 * c[1][1] + b2 * c[2][1];
      double q[3], e2 = 0;
      eval_d(s, f, u, v, q);
      for (int k = 0; k < 3; k++) {
        double e = q[k] - (b0 * p[0][k] + b1 * p[1][k] + b2 * p[2][k]);
        e2 += e * e;
      }
      worst = fmax(worst, sqrt(e2));
    }
  }
  return worst;
}

/* The level-l pattern's triangles (lod/src/pattern_refine.c build_indices). */
static double dense_dev(const tlod_surface* s, uint32_t f, uint32_t corners, uint32_t level) {
  int n = 1 << level, d = level <= 2 ? 16 : level == 3 ? 8 : 4;
  double h = 1.0 / n, worst = 0;
  for (int b = 0; b < n; b++) {
    for (int a = 0; a < (corners == 3 ? n - b : n); a++) {
      double A = a * h, B = b * h, A1 = (a + 1) * h, B1 = (b + 1) * h;
      if (corners == 3) {
        double lo[3][2] = {{A, B}, {A1, B}, {A, B1}};
        worst = fmax(worst, tri_dev(s, f, lo, d));
        if (a + b + 2 <= n) {
          double up[3][2] = {{A1, B}, {A1, B1}, {A, B1}};
          worst = fmax(worst, tri_dev(s, f, up, d));
        }
      } else {
        double t1[3][2] = {{A, B}, {A1, B}, {A1, B1}}, t2[3][2] = {{A, B}, {A1, B1}, {A, B1}};
        worst = fmax(worst, fmax(tri_dev(s, f, t1, d), tri_dev(s, f, t2, d)));
      }
    }
  }
  return worst;
}

/* ------------------------------------------------------------------------ */
/* Tightness statistics                                                     */
/* ------------------------------------------------------------------------ */

enum { KIND_FLAT_TRI, KIND_FLAT_QUAD, KIND_PHONG, KIND_PHONG_PV, KIND_PHONG_QUAD, KIND_PHONG_QUAD_PV, KIND_PN, KINDS };
static const char* k_kind_names[KINDS] = {"flat tri",   "flat quad",     "phong tri", "phong tri pv-alpha",
                                          "phong quad", "phong quad pv", "pn tri"};

typedef struct stats {
  double* r[KINDS][MAX_TEST_LEVEL + 1]; /* bound / dense */
  size_t n[KINDS][MAX_TEST_LEVEL + 1], cap[KINDS][MAX_TEST_LEVEL + 1];
  double old_sum[KINDS][MAX_TEST_LEVEL + 1]; /* median of the old bound's ratio */
  double* old_r[KINDS][MAX_TEST_LEVEL + 1];
  double worst_excess; /* (dense - bound) / scale, largest */
} stats;

static stats g_stats;
static bool g_collect = true; /* false: checks without adding to the tightness statistics */

static void stats_add(int kind, uint32_t l, double ratio, double old_ratio) {
  if (g_stats.n[kind][l] == g_stats.cap[kind][l]) {
    g_stats.cap[kind][l] = g_stats.cap[kind][l] ? 2 * g_stats.cap[kind][l] : 256;
    g_stats.r[kind][l] = realloc(g_stats.r[kind][l], sizeof(double) * g_stats.cap[kind][l]);
    g_stats.old_r[kind][l] = realloc(g_stats.old_r[kind][l], sizeof(double) * g_stats.cap[kind][l]);
  }
  g_stats.old_r[kind][l][g_stats.n[kind][l]] = old_ratio;
  g_stats.r[kind][l][g_stats.n[kind][l]++] = ratio;
}

static int cmp_d(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y;
}

static double patch_scale(const tlod_mesh* mesh, uint32_t f) {
  uint32_t vid[4], n = tlod_mesh_face_corners(mesh, f, vid);
  double scale = 0;
  for (uint32_t x = 0; x < n; x++) {
    float p[3], nn[3];
    tlod_mesh_vertex(mesh, vid[x], p, nn);
    for (int c = 0; c < 3; c++)
      scale = fmax(scale, fabs(p[c]));
  }
  return fmax(scale, 1e-30);
}

/* Checks every patch (every `stride`-th above level 3) of one surface;
 * returns the number of violations. */
static int check_surface(const tlod_surface* s, const tlod_mesh* mesh, int kind_tri, int kind_quad, uint32_t stride_hi,
                         uint32_t max_patches) {
  int bad = 0;
  uint32_t count = tlod_surface_patch_count(s);
  if (count > max_patches) count = max_patches;
  for (uint32_t f = 0; f < count; f += TLOD_TEST_PATCH_STEP) {
    tlod_patch_info info = tlod_surface_patch(s, f);
    int kind = info.corner_count == 3 ? kind_tri : kind_quad;
    double scale = patch_scale(mesh, f);
    for (uint32_t l = 0; l <= MAX_TEST_LEVEL; l++) {
      if (l > 3 && f % stride_hi) continue;
      double dense = dense_dev(s, f, info.corner_count, l);
      double bound = tlod_patch_error_bound(&info, l);
      double excess = (dense - bound) / scale;
      g_stats.worst_excess = fmax(g_stats.worst_excess, excess);
      if (excess > TOL_REL) {
        if (bad < 5)
          fprintf(stderr, "  %s patch %u level %u: bound %.9g < dense deviation %.9g (scale %.3g)\n",
                  k_kind_names[kind], f, l, bound, dense, scale);
        bad++;
      }
      /* Tightness where the deviation is above float noise. */
      if (g_collect && dense > 4.0 * info.error_slack)
        stats_add(kind, l, bound / dense, (double)info.error_bound * pow(0.25, (double)l) / dense);
    }
    /* Non-increasing, and the tail continues the table. */
    for (uint32_t l = 1; l <= 10; l++) {
      if (tlod_patch_error_bound(&info, l) > tlod_patch_error_bound(&info, l - 1)) {
        if (bad < 5) fprintf(stderr, "  patch %u: bound increases at level %u\n", f, l);
        bad++;
      }
    }
  }
  return bad;
}

typedef struct surf_case {
  tlod_surface_type type;
  tlod_alpha_mode alpha_mode;
  float alpha;
  int kind_tri, kind_quad;
} surf_case;

static const surf_case k_cases[] = {
    {TLOD_SURFACE_FLAT, TLOD_ALPHA_GLOBAL, 0.0f, KIND_FLAT_TRI, KIND_FLAT_QUAD},
    {TLOD_SURFACE_PHONG, TLOD_ALPHA_GLOBAL, 0.75f, KIND_PHONG, KIND_PHONG_QUAD},
    {TLOD_SURFACE_PHONG, TLOD_ALPHA_GLOBAL, 1.0f, KIND_PHONG, KIND_PHONG_QUAD},
    {TLOD_SURFACE_PHONG, TLOD_ALPHA_PER_VERTEX, 0.0f, KIND_PHONG_PV, KIND_PHONG_QUAD_PV},
    {TLOD_SURFACE_PN, TLOD_ALPHA_GLOBAL, 0.75f, KIND_PN, KIND_PN},
};

static int check_mesh(tlod_context* ctx, const mesh_data* d, uint32_t stride_hi, uint32_t max_patches) {
  tlod_mesh* mesh = make_mesh(ctx, d);
  if (!mesh) return 1;
  int bad = 0;
  for (size_t k = 0; k < sizeof k_cases / sizeof k_cases[0]; k++) {
    const surf_case* c = &k_cases[k];
    if (c->type == TLOD_SURFACE_PN && d->has_quads) continue;
    tlod_surface_desc sd = {.type = c->type, .alpha_mode = c->alpha_mode, .alpha = c->alpha, .label = "t"};
    tlod_surface* s = NULL;
    if (tlod_surface_create(ctx, mesh, &sd, &s) != TLOD_SUCCESS) {
      fprintf(stderr, "surface on %s: %s\n", d->name, tlod_context_last_error(ctx));
      bad++;
      continue;
    }
    int b = check_surface(s, mesh, c->kind_tri, c->kind_quad, stride_hi, max_patches);
    if (b) fprintf(stderr, "  %s, %s: %d violations\n", d->name, tlod_surface_type_name(c->type), b);
    bad += b;
    tlod_surface_destroy(s);
  }
  tlod_mesh_destroy(mesh);
  return bad;
}

TEST(test_tables_random) {
  tlod_context* ctx = new_context();
  CHECK(ctx);
  int bad = 0;
  for (int tilt = 0; tilt < 2; tilt++) {
    double deg = tilt ? 85.0 : 40.0;
    mesh_data t = random_patches(100 + (uint64_t)tilt, 1200, 3, deg),
              q = random_patches(200 + (uint64_t)tilt, 400, 4, deg);
    bad += check_mesh(ctx, &t, 12, UINT32_MAX);
    bad += check_mesh(ctx, &q, 20, UINT32_MAX);
    mesh_data_free(&t), mesh_data_free(&q);
  }
  mesh_data fp = folded_pairs(300, 300);
  bad += check_mesh(ctx, &fp, 12, UINT32_MAX);
  mesh_data_free(&fp);
  tlod_context_destroy(ctx);
  CHECK_MSG(bad == 0, "%d bounds below the dense deviation", bad);
}

TEST(test_tables_meshes) {
  tlod_context* ctx = new_context();
  CHECK(ctx);
  int bad = 0;
  const char* objs[] = {"obj/quad_cube.obj", "obj/mixed.obj", "derived/fran_cut.obj"};
  for (int k = 0; k < 3; k++) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", TLOD_TEST_DATA_DIR, objs[k]);
    mesh_data d;
    CHECK_MSG(load_obj(path, &d), "cannot read %s", path);
    bad += check_mesh(ctx, &d, 40, 1500);
    mesh_data_free(&d);
  }
  mesh_data duck;
  CHECK(load_duck(TLOD_TEST_DATA_DIR "/glTF-Sample-Models/Duck/glTF", &duck));
  bad += check_mesh(ctx, &duck, 40, 1500);
  mesh_data_free(&duck);
  /* A quad sphere: curved quads with smooth normals. */
  shape qs = shape_quad_sphere(4);
  mesh_data d = {.name = "quad sphere",
                 .positions = qs.positions,
                 .normals = qs.normals,
                 .indices = qs.indices,
                 .vertex_count = qs.vertex_count,
                 .index_count = qs.index_count,
                 .face_count = shape_face_count(&qs),
                 .has_quads = true};
  d.sizes = malloc(d.face_count);
  memset(d.sizes, 4, d.face_count);
  random_alphas(&d, 79);
  bad += check_mesh(ctx, &d, 8, UINT32_MAX);
  free(d.sizes), free(d.alphas);
  shape_free(&qs);
  tlod_context_destroy(ctx);
  CHECK_MSG(bad == 0, "%d bounds below the dense deviation", bad);
}

/* TLOD_ERROR_TABLES_CLOSED_FORM on one mesh and case: every bound at least
 * the measured table's (levels 0..10) and the closed form error_bound 4^-l
 * plus the slack; a zero desc builds the measured tables. Returns the
 * violations. */
static int closed_form_case(tlod_context* ctx, tlod_mesh* mesh, const surf_case* c) {
  tlod_surface_desc sd = {.type = c->type, .alpha_mode = c->alpha_mode, .alpha = c->alpha};
  tlod_surface *dflt = NULL, *meas = NULL, *closed = NULL;
  int bad = tlod_surface_create(ctx, mesh, &sd, &dflt) != TLOD_SUCCESS;
  sd.error_tables = TLOD_ERROR_TABLES_MEASURED;
  bad += tlod_surface_create(ctx, mesh, &sd, &meas) != TLOD_SUCCESS;
  sd.error_tables = TLOD_ERROR_TABLES_CLOSED_FORM;
  bad += tlod_surface_create(ctx, mesh, &sd, &closed) != TLOD_SUCCESS;
  if (bad) return bad;
  bad += tlod_surface_query_desc(dflt).error_tables != TLOD_ERROR_TABLES_MEASURED;
  bad += tlod_surface_query_desc(closed).error_tables != TLOD_ERROR_TABLES_CLOSED_FORM;
  for (uint32_t f = 0; f < tlod_surface_patch_count(meas); f++) {
    tlod_patch_info d = tlod_surface_patch(dflt, f), m = tlod_surface_patch(meas, f), k = tlod_surface_patch(closed, f);
    bad += memcmp(&d, &m, sizeof d) != 0;
    for (uint32_t l = 0; l <= 10; l++) {
      double kb = tlod_patch_error_bound(&k, l), mb = tlod_patch_error_bound(&m, l);
      double closed_form = (double)k.error_bound * ldexp(1.0, -2 * (int)l);
      if (kb >= mb && kb >= closed_form && kb <= closed_form * (1 + 1e-6) + 2.0 * k.error_slack) continue;
      if (bad < 5)
        fprintf(stderr, "  %s patch %u level %u: closed form %.9g, measured %.9g, error_bound 4^-l %.9g\n",
                tlod_surface_type_name(c->type), f, l, kb, mb, closed_form);
      bad++;
    }
  }
  /* and rigorous against the dense deviation, as the measured tables are */
  g_collect = false;
  bad += check_surface(closed, mesh, c->kind_tri, c->kind_quad, 1000, 100);
  g_collect = true;
  tlod_surface_destroy(dflt), tlod_surface_destroy(meas), tlod_surface_destroy(closed);
  return bad;
}

TEST(test_closed_form_tables) {
  tlod_context* ctx = new_context();
  CHECK(ctx);
  mesh_data t = random_patches(500, 300, 3, 85.0), q = random_patches(501, 100, 4, 85.0);
  const mesh_data* meshes[2] = {&t, &q};
  int bad = 0;
  for (int m = 0; m < 2; m++) {
    tlod_mesh* mesh = make_mesh(ctx, meshes[m]);
    CHECK(mesh);
    for (size_t k = 0; k < sizeof k_cases / sizeof k_cases[0]; k++)
      if (!(k_cases[k].type == TLOD_SURFACE_PN && meshes[m]->has_quads))
        bad += closed_form_case(ctx, mesh, &k_cases[k]);
    tlod_mesh_destroy(mesh);
  }
  /* an unknown mode is refused */
  tlod_mesh* mesh = make_mesh(ctx, &t);
  tlod_surface* s = (tlod_surface*)&bad;
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.error_tables = TLOD_ERROR_TABLES_NUM}, &s) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(s == NULL && strstr(tlod_context_last_error(ctx), "error_tables"));
  tlod_mesh_destroy(mesh);
  mesh_data_free(&t), mesh_data_free(&q);
  tlod_context_destroy(ctx);
  CHECK_MSG(bad == 0, "%d closed-form bounds below the measured table or off error_bound 4^-l", bad);
}

/* Refresh recomputes the tables of the patches that changed, as a fresh build. */
TEST(test_tables_refresh) {
  tlod_context* ctx = new_context();
  CHECK(ctx);
  shape sp = shape_icosphere(2);
  tlod_mesh_desc md = shape_mesh_desc(&sp);
  tlod_mesh* mesh = NULL;
  CHECK(tlod_mesh_create(ctx, &md, &mesh) == TLOD_SUCCESS);
  tlod_surface* s = NULL;
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &s) == TLOD_SUCCESS);
  for (uint32_t v = 0; v < 3; v++)
    sp.positions[3 * v] *= 1.2f;
  CHECK(tlod_mesh_update(mesh, sp.positions, 0, sp.normals, 0) == TLOD_SUCCESS);
  uint32_t updated = 0;
  CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS);
  CHECK(updated > 0 && updated < tlod_surface_patch_count(s));
  tlod_surface* fresh = NULL;
  CHECK(tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &fresh) == TLOD_SUCCESS);
  for (uint32_t f = 0; f < tlod_surface_patch_count(s); f++) {
    tlod_patch_info a = tlod_surface_patch(s, f), b = tlod_surface_patch(fresh, f);
    CHECK_MSG(memcmp(a.error_table, b.error_table, sizeof a.error_table) == 0 && a.error_tail == b.error_tail,
              "patch %u: refreshed table differs from a fresh build", f);
  }
  tlod_surface_destroy(fresh);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  shape_free(&sp);
  tlod_context_destroy(ctx);
}

/* The per-vertex-alpha net (phong.c), evaluated here as a Bezier triangle
 * and added to the flat patch, is the surface: to float precision. */
TEST(test_phong_alpha_net_is_the_surface) {
  tlod_context* ctx = new_context();
  CHECK(ctx);
  mesh_data d = random_patches(400, 200, 3, 85.0);
  tlod_mesh* mesh = make_mesh(ctx, &d);
  CHECK(mesh);
  tlod_surface* s = NULL;
  CHECK(tlod_surface_create(ctx, mesh,
                            &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_PER_VERTEX},
                            &s) == TLOD_SUCCESS);
  static const int idx[10][3] = {{3, 0, 0}, {0, 3, 0}, {0, 0, 3}, {2, 1, 0}, {1, 2, 0},
                                 {0, 2, 1}, {0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {1, 1, 1}};
  shape_rng rng = {401};
  double worst = 0;
  for (uint32_t f = 0; f < tlod_surface_patch_count(s); f++) {
    _tlod_corners c;
    _tlod_patch_corners(s, f, &c);
    double net[10][3];
    _tlod_phong_alpha_net(&c, net);
    for (int k = 0; k < 200; k++) {
      double u = shape_rng_unit(&rng), v = shape_rng_unit(&rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      float uf = (float)u, vf = (float)v;
      u = uf, v = vf;
      double w = 1 - u - v, ref[3] = {0, 0, 0};
      for (int b = 0; b < 10; b++) {
        int i = idx[b][0], j = idx[b][1], kk = idx[b][2];
        double fact[4] = {1, 1, 2, 6};
        double coef = 6.0 / (fact[i] * fact[j] * fact[kk]) * pow(u, i) * pow(v, j) * pow(w, kk);
        for (int x = 0; x < 3; x++)
          ref[x] += coef * net[b][x];
      }
      double pc[3] = {c.p[0].x, c.p[0].y, c.p[0].z}, pj[3] = {c.p[1].x, c.p[1].y, c.p[1].z};
      double pk[3] = {c.p[2].x, c.p[2].y, c.p[2].z};
      for (int x = 0; x < 3; x++)
        ref[x] += u * pc[x] + v * pj[x] + w * pk[x];
      tlod_surface_point pt;
      tlod_surface_eval(s, f, uf, vf, &pt);
      for (int x = 0; x < 3; x++)
        worst = fmax(worst, fabs(pt.position[x] - ref[x]));
    }
  }
  printf("  per-vertex-alpha net vs surface: max |difference| %.3g (coordinates in [-1, 1])\n", worst);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  mesh_data_free(&d);
  tlod_context_destroy(ctx);
  /* float evaluation of O(1) coordinates: a few ulps (2^-24 = 6e-8) */
  CHECK_MSG(worst <= 1e-6, "net and surface differ by %.3g", worst);
}

/* The median of bound / dense for one kind and level (the statistics'
 * array sorted in place; print_tightness sorts it again). */
static double tightness_median(int kind, int level) {
  size_t n = g_stats.n[kind][level];
  if (!n) return INFINITY;
  qsort(g_stats.r[kind][level], n, sizeof(double), cmp_d);
  return g_stats.r[kind][level][n / 2];
}

/* The measured Phong quad entries stay tight against the dense deviation
 * (their float samples add a rounding allowance; the closed form's medians
 * are 1.8-5.4 on these patches): today's medians plus about 5%. */
TEST(test_quad_tables_tight) {
  static const double limit[2][3] = {{1.10, 1.20, 1.55}, {1.15, 1.30, 1.75}};
  static const int kinds[2] = {KIND_PHONG_QUAD, KIND_PHONG_QUAD_PV};
  for (int k = 0; k < 2; k++)
    for (int l = 0; l < 3; l++) {
      double median = tightness_median(kinds[k], l);
      CHECK_MSG(median <= limit[k][l], "%s level %d: median bound / dense %.3f above %.2f", k_kind_names[kinds[k]], l,
                median, limit[k][l]);
    }
}

static void print_tightness(void) {
  printf("  tightness = bound / dense true deviation (patches with deviation > 4 x float slack)\n");
  printf("  %-20s %5s %7s %7s %7s %7s %7s | old bound median\n", "surface", "level", "n", "min", "median", "p95",
         "max");
  for (int k = 0; k < KINDS; k++) {
    for (int l = 0; l <= MAX_TEST_LEVEL; l++) {
      size_t n = g_stats.n[k][l];
      if (!n) continue;
      double* r = g_stats.r[k][l];
      qsort(r, n, sizeof(double), cmp_d);
      qsort(g_stats.old_r[k][l], n, sizeof(double), cmp_d);
      printf("  %-20s %5d %7zu %7.3f %7.3f %7.3f %7.3f | %7.3f\n", k_kind_names[k], l, n, r[0], r[n / 2],
             r[(size_t)(0.95 * (double)(n - 1))], r[n - 1], g_stats.old_r[k][l][n / 2]);
      free(r), free(g_stats.old_r[k][l]);
    }
  }
  printf("  largest (dense - bound) / scale: %.3g (tolerance %.0e)\n", g_stats.worst_excess, TOL_REL);
}

/* The scalar path of one Phong quad patch (phong.c, error_table.c), as
 * build_patch ran it before the lanes: the oracle of the lane kernels. */
static tlod_patch_info scalar_quad_patch(const tlod_surface* s, uint32_t f, bool closed) {
  _tlod_corners c;
  _tlod_patch_corners(s, f, &c);
  tlod_patch_info info = {.corner_count = c.n};
  double net[4][4][3];
  _tlod_quad_net(&c, net);
  info.error_bound = _tlod_quad_net_bound((const double(*)[4][3])net, &c, &info.d_max);
  _tlod_sphere_of(&c, NULL, 0, info.error_bound, &info);
  if (closed)
    _tlod_error_table_closed(&c, NULL, 0, &info);
  else
    _tlod_error_table(TLOD_SURFACE_PHONG, &c, NULL, (const double(*)[4][3])net, &info);
  return info;
}

/* Phong quads are built in lanes of 16 patches (error_table_lanes.c): every
 * patch's info bitwise the scalar path's, at every instruction set and
 * thread count, MEASURED and CLOSED_FORM, per-vertex and global alphas,
 * patch counts that leave part-filled lanes, quads between triangles. */
static int lanes_case(const mesh_data* d, tlod_simd simd, uint32_t threads, tlod_error_tables tables,
                      tlod_alpha_mode am) {
  tlod_context* ctx = NULL;
  tlod_context_desc cd = {.thread_count = threads, .simd = simd};
  if (tlod_context_create(&cd, &ctx) != TLOD_SUCCESS) return 1;
  tlod_mesh* mesh = make_mesh(ctx, d);
  tlod_surface* s = NULL;
  int bad =
      !mesh ||
      tlod_surface_create(
          ctx, mesh,
          &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = am, .alpha = 0.6f, .error_tables = tables},
          &s) != TLOD_SUCCESS;
  for (uint32_t f = 0; !bad && f < tlod_surface_patch_count(s); f++) {
    tlod_patch_info got = tlod_surface_patch(s, f);
    if (got.corner_count != 4) continue;
    tlod_patch_info want = scalar_quad_patch(s, f, tables == TLOD_ERROR_TABLES_CLOSED_FORM);
    if (memcmp(&got, &want, sizeof got) != 0 && bad++ < 5)
      fprintf(stderr, "  %s simd %d, %u threads, tables %d: patch %u differs from the scalar path\n", d->name,
              (int)simd, threads, (int)tables, f);
  }
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  return bad;
}

TEST(test_quad_lanes_bitwise) {
  mesh_data q = random_patches(600, 203, 4, 85.0), t = random_patches(601, 5, 3, 40.0);
  /* q with t's triangles after every 50th quad: a mixed mesh */
  mesh_data m = {.name = "mixed random", .has_quads = true};
  m.vertex_count = m.index_count = q.vertex_count + t.vertex_count;
  m.face_count = q.face_count + t.face_count;
  m.positions = malloc(sizeof(float) * 3 * m.vertex_count), m.normals = malloc(sizeof(float) * 3 * m.vertex_count);
  m.alphas = malloc(sizeof(float) * m.vertex_count), m.indices = malloc(sizeof(uint32_t) * m.index_count);
  m.sizes = malloc(m.face_count);
  for (uint32_t f = 0, qf = 0, tf = 0, v = 0; f < m.face_count; f++) {
    bool tri = tf < t.face_count && (qf == q.face_count || qf % 50 == 7);
    const mesh_data* src = tri ? &t : &q;
    uint32_t n = tri ? 3 : 4, first = (tri ? tf++ : qf++) * n;
    for (uint32_t x = 0; x < n; x++, v++) {
      memcpy(m.positions + 3 * v, src->positions + 3 * (first + x), sizeof(float) * 3);
      memcpy(m.normals + 3 * v, src->normals + 3 * (first + x), sizeof(float) * 3);
      m.alphas[v] = src->alphas[first + x], m.indices[v] = v;
    }
    m.sizes[f] = (uint8_t)n;
  }
  const mesh_data* meshes[2] = {&q, &m};
  int bad = 0;
  for (int k = 0; k < 2; k++)
    for (int simd = TLOD_SIMD_SCALAR; simd < TLOD_SIMD_NUM; simd++)
      for (uint32_t threads = 1; threads <= 2; threads++) {
        bad += lanes_case(meshes[k], (tlod_simd)simd, threads, TLOD_ERROR_TABLES_MEASURED, TLOD_ALPHA_PER_VERTEX);
        bad += lanes_case(meshes[k], (tlod_simd)simd, threads, TLOD_ERROR_TABLES_CLOSED_FORM, TLOD_ALPHA_PER_VERTEX);
        bad += lanes_case(meshes[k], (tlod_simd)simd, threads, TLOD_ERROR_TABLES_MEASURED, TLOD_ALPHA_GLOBAL);
      }
  mesh_data_free(&q), mesh_data_free(&t), mesh_data_free(&m);
  CHECK_MSG(bad == 0, "%d Phong quad patches differ from the scalar path", bad);
}

int main(void) {
  g_stats.worst_excess = -INFINITY;
  RUN(test_phong_alpha_net_is_the_surface);
  RUN(test_tables_refresh);
  RUN(test_quad_lanes_bitwise);
  RUN(test_closed_form_tables);
  RUN(test_tables_random);
  RUN(test_tables_meshes);
  RUN(test_quad_tables_tight);
  print_tightness();
  TEST_END();
}
