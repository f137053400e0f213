/*
 * cpu_fast_test.c -- the CPU tessellator's fast path (tesslod/cpu.h FAST
 * PATH) against its reference path (.reference = true), bit for bit: every
 * output array compared with memcmp, for flat, Phong (shading and true
 * normals), PN and quadratic surfaces, uniform levels 0..6, random levels,
 * draw lists with geomorph blends and strips, welded and no_weld,
 * no_normals, a mesh with attributes, every instruction set this processor
 * has and 1, 2, 3 threads. Public API only.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_lod.h"

#define MAX_LEVEL 6

typedef struct scene {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
  const char* name;
} scene;

static tlod_context* context(tlod_simd simd, uint32_t threads) {
  tlod_context* ctx = NULL;
  tlod_result r = tlod_context_create(&(tlod_context_desc){.thread_count = threads, .simd = simd}, &ctx);
  return r == TLOD_SUCCESS ? ctx : NULL;
}

static bool scene_make_desc(scene* sc, const char* name, const tlod_mesh_desc* mesh_desc, tlod_surface_desc sd) {
  memset(sc, 0, sizeof *sc);
  sc->ctx = context(TLOD_SIMD_SCALAR, 1);
  sc->name = name;
  tlod_mesh_desc md = *mesh_desc;
  tlod_result r = sc->ctx ? tlod_mesh_create(sc->ctx, &md, &sc->mesh) : TLOD_ERROR_OUT_OF_MEMORY;
  if (r == TLOD_SUCCESS) r = tlod_surface_create(sc->ctx, sc->mesh, &sd, &sc->surf);
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(sc->ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &sc->pat);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "scene %s %s: %s: %s\n", name, type_name(sd.type), tlod_result_string(r),
            sc->ctx ? tlod_context_last_error(sc->ctx) : "no context");
  return r == TLOD_SUCCESS;
}

static bool scene_make(scene* sc, const shape* s, const tlod_attribute_desc* attrs, uint32_t attr_count,
                       tlod_surface_desc sd) {
  tlod_mesh_desc md = shape_mesh_desc(s);
  md.attributes = attrs;
  md.attribute_count = attr_count;
  return scene_make_desc(sc, s->name, &md, sd);
}

static void scene_free(scene* sc) {
  tlod_surface_destroy(sc->surf);
  tlod_mesh_destroy(sc->mesh);
  tlod_patterns_destroy(sc->pat);
  tlod_context_destroy(sc->ctx);
}

static bool same_array(const void* a, const void* b, size_t bytes) {
  if (!a || !b) return a == b;
  return memcmp(a, b, bytes) == 0;
}

/* Every count and array of two outputs, bitwise. */
static bool same_mesh(const tlod_cpu_mesh* a, const tlod_cpu_mesh* b) {
  if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count) return false;
  if (a->pattern_triangles != b->pattern_triangles || a->strip_triangles != b->strip_triangles) return false;
  if (a->strips != b->strips || a->folds_skipped != b->folds_skipped || a->attribute_count != b->attribute_count)
    return false;
  size_t nv = a->vertex_count, nt = a->triangle_count;
  return same_array(a->positions, b->positions, 12 * nv) && same_array(a->normals, b->normals, 12 * nv) &&
         same_array(a->indices, b->indices, 12 * nt) && same_array(a->triangle_patch, b->triangle_patch, 4 * nt) &&
         same_array(a->vertex_patch, b->vertex_patch, 4 * nv) && same_array(a->vertex_uv, b->vertex_uv, 8 * nv) &&
         same_array(a->attributes, b->attributes, 16 * nv * a->attribute_count);
}

static tlod_cpu_mesh* run(tlod_context* ctx, const scene* sc, tlod_cpu_tessellate_desc d) {
  tlod_cpu_mesh* out = NULL;
  if (tlod_cpu_tessellate(ctx, sc->surf, sc->pat, &d, &out) != TLOD_SUCCESS) {
    fprintf(stderr, "%s: %s\n", sc->name, tlod_context_last_error(ctx));
    return NULL;
  }
  return out;
}

/* The fast path at every instruction set and 1..3 threads equals the
 * reference. */
static void check_case(const scene* sc, tlod_cpu_tessellate_desc d, const char* what) {
  tlod_cpu_tessellate_desc rd = d;
  rd.reference = true;
  tlod_cpu_mesh* ref = run(sc->ctx, sc, rd);
  CHECK_MSG(ref && ref->vertex_count > 0, "%s %s: reference", sc->name, what);
  d.reference = false;
  for (tlod_simd simd = TLOD_SIMD_SCALAR; ref && simd < TLOD_SIMD_NUM; simd++) {
    for (uint32_t threads = 1; threads <= 3; threads++) {
      tlod_context* ctx = context(simd, threads);
      if (tlod_context_simd(ctx) != simd) { /* this processor lacks it */
        tlod_context_destroy(ctx);
        break;
      }
      tlod_cpu_mesh* got = run(ctx, sc, d);
      CHECK_MSG(got && same_mesh(ref, got), "%s %s: %s, %u threads differ from the reference", sc->name, what,
                tlod_simd_name(simd), threads);
      tlod_cpu_mesh_destroy(ctx, got);
      tlod_context_destroy(ctx);
    }
  }
  tlod_cpu_mesh_destroy(sc->ctx, ref);
}

static int8_t* random_levels(uint32_t patches, uint64_t seed, int max_level) {
  shape_rng rng = {seed};
  int8_t* l = malloc(patches + 1);
  for (uint32_t p = 0; p < patches; ++p)
    l[p] = (int8_t)((int)(shape_rng_next(&rng) % (uint64_t)(max_level + 2)) - 1); /* -1: left out */
  return l;
}

/* A draw list over random levels: blends 1, 0 or in between, and a strip on
 * every drawn edge whose sides differ in level or are a crease. */
typedef struct crafted {
  tlod_draw_list dl;
  int8_t* levels;
  tlod_draw_instance* inst;
  tlod_draw_strip* strips;
} crafted;

static crafted craft(const scene* sc, uint64_t seed) {
  uint32_t nf = tlod_mesh_face_count(sc->mesh);
  crafted c = {.levels = random_levels(nf, seed, 4)};
  c.inst = calloc(nf + 1, sizeof(*c.inst));
  c.strips = calloc(4 * (size_t)nf + 1, sizeof(*c.strips));
  shape_rng rng = {seed ^ 0x5eed};
  uint32_t ni = 0, ns = 0;
  tlod_mesh_view m = tlod_mesh_query_view(sc->mesh);
  for (uint32_t f = 0; f < nf; f++) {
    if (c.levels[f] < 0) continue;
    uint64_t r = shape_rng_next(&rng) % 3;
    c.inst[ni++] = (tlod_draw_instance){f, (uint32_t)c.levels[f], r == 0 ? 1.0f : r == 1 ? 0.0f : 0.37f};
    for (uint32_t e = 0; e < m.face_corners[f]; e++) {
      tlod_edge_link l = m.links[f][e];
      if (l.face == UINT32_MAX || l.face < f || c.levels[l.face] < 0) continue;
      if (l.smooth && c.levels[l.face] == c.levels[f]) continue;
      c.strips[ns++] = (tlod_draw_strip){
          f, l.face, (uint8_t)e, l.edge, (uint8_t)c.levels[f], (uint8_t)c.levels[l.face], !l.smooth, false};
    }
  }
  c.dl = (tlod_draw_list){.patch_count = nf,
                          .levels = c.levels,
                          .instances = c.inst,
                          .instance_count = ni,
                          .strips = c.strips,
                          .strip_count = ns};
  return c;
}

static void crafted_free(crafted* c) {
  free(c->levels);
  free(c->inst);
  free(c->strips);
}

/* Uniform levels up to top, random levels, a crafted draw list; each
 * welded and not, with and without normals. */
static void check_scene(const scene* sc, uint32_t top) {
  char what[64];
  for (uint32_t l = 0; l <= top; l++) {
    snprintf(what, sizeof what, "level %u", l);
    check_case(sc, (tlod_cpu_tessellate_desc){.level = l}, what);
    snprintf(what, sizeof what, "level %u no_normals", l);
    check_case(sc, (tlod_cpu_tessellate_desc){.level = l, .no_normals = true}, what);
  }
  uint32_t nf = tlod_mesh_face_count(sc->mesh);
  int8_t* levels = random_levels(nf, 7, 5);
  crafted c = craft(sc, 11);
  for (int v = 0; v < 4; v++) {
    bool no_weld = v & 1, no_normals = v & 2;
    snprintf(what, sizeof what, "levels%s%s", no_weld ? " no_weld" : "", no_normals ? " no_normals" : "");
    check_case(sc, (tlod_cpu_tessellate_desc){.levels = levels, .no_weld = no_weld, .no_normals = no_normals}, what);
    snprintf(what, sizeof what, "draw list%s%s", no_weld ? " no_weld" : "", no_normals ? " no_normals" : "");
    check_case(sc, (tlod_cpu_tessellate_desc){.draw_list = &c.dl, .no_weld = no_weld, .no_normals = no_normals}, what);
  }
  free(levels);
  crafted_free(&c);
}

static void check_shape(shape s, tlod_surface_desc sd, uint32_t top) {
  scene sc;
  CHECK_MSG(scene_make(&sc, &s, NULL, 0, sd), "%s", s.name);
  if (sc.surf) check_scene(&sc, top);
  scene_free(&sc);
  shape_free(&s);
}

TEST(test_flat) {
  check_shape(shape_icosphere(0), (tlod_surface_desc){.type = TLOD_SURFACE_FLAT}, 6);
  check_shape(shape_quad_sphere(2), (tlod_surface_desc){.type = TLOD_SURFACE_FLAT}, 4);
}

TEST(test_phong) {
  check_shape(shape_icosphere(0), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, 6);
  check_shape(shape_torus(8, 6), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, 3);
  check_shape(shape_cube_split(), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, 4);
  check_shape(shape_open_grid(3), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, 3);
  check_shape(shape_quad_sphere(2), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, 4);
  check_shape(shape_icosphere(0),
              (tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .shading_normal = TLOD_SHADING_NORMAL_TRUE}, 3);
}

TEST(test_pn) {
  check_shape(shape_icosphere(0), (tlod_surface_desc){.type = TLOD_SURFACE_PN}, 6);
  check_shape(shape_cube_split(), (tlod_surface_desc){.type = TLOD_SURFACE_PN}, 4);
}

TEST(test_quadratic) {
  check_shape(shape_icosphere(0), (tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, 4);
  check_shape(shape_quad_cube(), (tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, 4);
}

/* A seam sphere with a UV attribute: seams keep their own vertices. */
TEST(test_attributes) {
  shape s = shape_seam_sphere(4, 6);
  uint32_t cols = 7;
  float* uv = calloc(2 * (size_t)5 * cols, sizeof(float));
  for (uint32_t i = 0; i <= 4; i++)
    for (uint32_t j = 0; j <= 6; j++)
      uv[2 * (i * cols + j)] = (float)j / 6.0f, uv[2 * (i * cols + j) + 1] = (float)i / 4.0f;
  tlod_attribute_desc a = {.data = uv, .components = 2, .name = "TEXCOORD_0"};
  scene sc;
  CHECK(scene_make(&sc, &s, &a, 1, (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}));
  if (sc.surf) check_scene(&sc, 3);
  scene_free(&sc);
  shape_free(&s);
  free(uv);
}

/* Frame k of a deformation: positions scaled about the origin by a wobble,
 * normals in one of three modes: the shape's (creases where it has them),
 * the normalised position (vertices at one position agree: every crease
 * becomes smooth), or the shape's shifted to the next vertex at the same
 * position (a weld group's normals sorted in another order). */
static void deform(const shape* s, uint32_t k, float* pos, float* nrm) {
  uint32_t mode = (k / 3) % 3;
  for (uint32_t v = 0; v < s->vertex_count; v++) {
    float w = 1.0f + 0.05f * sinf(0.9f * (float)k + (float)v), *p = pos + 3 * v, *n = nrm + 3 * v;
    for (int c = 0; c < 3; c++)
      p[c] = s->positions[3 * v + c] * w;
    const float* src = s->normals + 3 * v;
    for (uint32_t x = 1; mode == 2 && x < s->vertex_count; x++) {
      uint32_t o = (v + x) % s->vertex_count;
      if (!memcmp(s->positions + 3 * o, s->positions + 3 * v, 12)) {
        src = s->normals + 3 * o;
        break;
      }
    }
    float len = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int c = 0; c < 3; c++)
      n[c] = mode == 1 ? p[c] / len : src[c];
  }
}

/* One reused mesh through tlod_cpu_tessellate_into over frames that move
 * positions, change normals (creases made smooth and back, weld groups
 * reordered), levels, draw lists and options: every frame bitwise equal to
 * a fresh reference tessellation. Each desc is held for two frames, so the
 * second reuses the kept topology unless the mesh update changed it. */
static void check_kept(shape s, tlod_surface_desc sd, tlod_simd simd, uint32_t threads) {
  scene sc;
  CHECK_MSG(scene_make(&sc, &s, NULL, 0, sd), "%s", s.name);
  tlod_context* ctx = context(simd, threads);
  uint32_t nf = tlod_mesh_face_count(sc.mesh);
  int8_t* levels = random_levels(nf, 5, 4);
  crafted c = craft(&sc, 13);
  const tlod_cpu_tessellate_desc descs[] = {
      {.level = 2},
      {.level = 2, .no_normals = true},
      {.level = 3},
      {.levels = levels},
      {.draw_list = &c.dl},
      {.draw_list = &c.dl, .no_weld = true},
      {.level = 1, .no_stitch = true},
      {.level = 2, .reference = true},
      {.levels = levels, .no_normals = true},
  };
  uint32_t nd = sizeof descs / sizeof descs[0];
  float* pos = malloc(12 * (size_t)s.vertex_count);
  float* nrm = malloc(12 * (size_t)s.vertex_count);
  tlod_cpu_mesh* kept = run(ctx, &sc, descs[0]);
  for (uint32_t k = 0; sc.surf && kept && k < 4 * nd; k++) {
    deform(&s, k, pos, nrm);
    CHECK(tlod_mesh_update(sc.mesh, pos, 0, nrm, 0) == TLOD_SUCCESS);
    CHECK(tlod_surface_refresh(sc.surf, NULL) == TLOD_SUCCESS);
    tlod_cpu_tessellate_desc d = descs[(k / 2) % nd], rd = d;
    rd.reference = true;
    CHECK(tlod_cpu_tessellate_into(ctx, sc.surf, sc.pat, &d, kept) == TLOD_SUCCESS);
    tlod_cpu_mesh* ref = run(sc.ctx, &sc, rd);
    CHECK_MSG(ref && same_mesh(ref, kept), "%s %s %u threads: frame %u (desc %u) differs from a fresh tessellation",
              s.name, tlod_simd_name(simd), threads, k, (k / 2) % nd);
    tlod_cpu_mesh_destroy(sc.ctx, ref);
  }
  tlod_cpu_mesh_destroy(ctx, kept);
  tlod_context_destroy(ctx);
  free(pos);
  free(nrm);
  free(levels);
  crafted_free(&c);
  scene_free(&sc);
  shape_free(&s);
}

TEST(test_kept_topology) {
  tlod_context* probe = context(TLOD_SIMD_DEFAULT, 1);
  tlod_simd best = tlod_context_simd(probe);
  tlod_context_destroy(probe);
  for (uint32_t v = 0; v < 2; v++) {
    tlod_simd simd = v ? best : TLOD_SIMD_SCALAR;
    uint32_t threads = v ? 2 : 1;
    check_kept(shape_cube_split(), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, simd, threads);
    check_kept(shape_cube_soft(), (tlod_surface_desc){.type = TLOD_SURFACE_PN}, simd, threads);
    check_kept(shape_torus(8, 6), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, simd, threads);
    check_kept(shape_quad_sphere(2), (tlod_surface_desc){.type = TLOD_SURFACE_FLAT}, simd, threads);
  }
}

/* The batch evaluations refuse what tlod_surface_eval_grid() refuses, and
 * an edge batch gives the grid evaluation's values bitwise. */
TEST(test_batch_arguments) {
  shape s = shape_icosphere(0);
  scene sc;
  CHECK(scene_make(&sc, &s, NULL, 0, (tlod_surface_desc){.type = TLOD_SURFACE_PN}));
  float u = 0.25f, v = 0.25f, pos[9], nrm[9], ref_pos[9], ref_nrm[9];
  uint32_t bad = 16, param[3] = {1, 7, 15};
  uint16_t ij[3][2] = {{15, 1}, {9, 7}, {1, 15}}; /* edge 0 of a triangle: i + j = 16, weight of j */
  CHECK(tlod_surface_eval_interior(NULL, 0, TLOD_SIMD_SCALAR, 1, &u, &v, pos, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_interior(sc.surf, 99, TLOD_SIMD_SCALAR, 1, &u, &v, pos, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_interior(sc.surf, 0, TLOD_SIMD_SCALAR, 1, NULL, &v, pos, NULL) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edge(sc.surf, 0, 3, 4, 1, param, pos, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edge(sc.surf, 0, 0, 4, 1, &bad, pos, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edge(sc.surf, 0, 0, 16, 1, param, pos, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edge(sc.surf, 0, 0, 4, 3, param, pos, nrm) == TLOD_SUCCESS);
  CHECK(tlod_surface_eval_grid(sc.surf, 0, 4, &ij[0][0], sizeof(ij[0]), 3, ref_pos, ref_nrm) == TLOD_SUCCESS);
  CHECK(memcmp(pos, ref_pos, sizeof pos) == 0 && memcmp(nrm, ref_nrm, sizeof nrm) == 0);
  scene_free(&sc);
  shape_free(&s);
}

/* tlod_surface_eval_edges() against tlod_surface_eval_edge() edge by edge,
 * bitwise: every edge of every patch (more than one block of lanes), both
 * directions of every shared edge, at each instruction set this processor
 * has; PN and quadratic surfaces through its fallback. */
static void check_edges(shape s, tlod_surface_desc sd, uint32_t* edge_count) {
  scene sc;
  CHECK_MSG(scene_make(&sc, &s, NULL, 0, sd), "%s", s.name);
  uint32_t nf = sc.surf ? tlod_mesh_face_count(sc.mesh) : 0, ne = 0, param[3] = {1, 6, 15};
  uint32_t* patches = malloc(sizeof(uint32_t) * 4 * (nf + 1));
  uint32_t* first = malloc(sizeof(uint32_t) * 4 * (nf + 1));
  uint8_t* edges = malloc(4 * (nf + 1));
  float* ref = calloc(3 * 3 * 4 * (size_t)(nf + 1), sizeof(float));
  float* got = calloc(3 * 3 * 4 * (size_t)(nf + 1), sizeof(float));
  tlod_mesh_view mv = tlod_mesh_query_view(sc.mesh);
  for (uint32_t f = 0; f < nf; f++) {
    for (uint32_t e = 0; e < mv.face_corners[f]; e++, ne++) {
      patches[ne] = f, edges[ne] = (uint8_t)e, first[ne] = 3 * (ne ^ 1); /* written out of order */
      CHECK(tlod_surface_eval_edge(sc.surf, f, e, 4, 3, param, ref + 9 * (size_t)(ne ^ 1), NULL) == TLOD_SUCCESS);
    }
  }
  for (tlod_simd simd = TLOD_SIMD_SCALAR; sc.surf && simd < TLOD_SIMD_NUM; simd++) {
    tlod_context* ctx = context(simd, 1);
    if (tlod_context_simd(ctx) == simd) {
      memset(got, 0, 3 * 3 * 4 * (size_t)(nf + 1) * sizeof(float));
      CHECK(tlod_surface_eval_edges(sc.surf, simd, 4, ne & ~1u, patches, edges, 3, param, first, got) == TLOD_SUCCESS);
      CHECK_MSG(!memcmp(got, ref, sizeof(float) * 9 * (ne & ~1u)), "%s %s: edges differ from tlod_surface_eval_edge",
                s.name, tlod_simd_name(simd));
    }
    tlod_context_destroy(ctx);
  }
  uint32_t bad_param = 16, bad_patch = nf;
  uint8_t bad_edge = 4;
  CHECK(tlod_surface_eval_edges(NULL, TLOD_SIMD_SCALAR, 4, 1, patches, edges, 3, param, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edges(sc.surf, TLOD_SIMD_SCALAR, 16, 1, patches, edges, 3, param, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edges(sc.surf, TLOD_SIMD_SCALAR, 4, 1, patches, edges, 1, &bad_param, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edges(sc.surf, TLOD_SIMD_SCALAR, 4, 1, &bad_patch, edges, 3, param, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edges(sc.surf, TLOD_SIMD_SCALAR, 4, 1, patches, &bad_edge, 3, param, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_edges(sc.surf, TLOD_SIMD_SCALAR, 4, 1, patches, edges, 3, param, NULL, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  free(patches);
  free(first);
  free(edges);
  free(ref);
  free(got);
  scene_free(&sc);
  shape_free(&s);
  *edge_count = ne;
}

TEST(test_edge_batch) {
  uint32_t ne = 0;
  check_edges(shape_torus(8, 6), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &ne);
  CHECK(ne > 64); /* more than one block of lanes */
  check_edges(shape_cube_split(),
              (tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = 0.4f}, &ne);
  check_edges(shape_icosphere(1), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &ne);
  check_edges(shape_quad_sphere(2), (tlod_surface_desc){.type = TLOD_SURFACE_FLAT}, &ne);
  check_edges(shape_icosphere(1), (tlod_surface_desc){.type = TLOD_SURFACE_PN}, &ne);
  check_edges(shape_quad_cube(), (tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC}, &ne);
}

/* The torus's triangle pairs, every other one merged back into its quad:
 * triangles and quads alternate along the face order (a mixed mesh). */
typedef struct mixed_faces {
  uint32_t* indices;
  uint8_t* sizes;
  uint32_t index_count, face_count;
} mixed_faces;

static mixed_faces mixed_of(const shape* s) {
  uint32_t pairs = s->index_count / 6;
  mixed_faces m = {malloc(sizeof(uint32_t) * 6 * pairs), malloc(2 * (size_t)pairs), 0, 0};
  for (uint32_t q = 0; q < pairs; q++) {
    const uint32_t* t = s->indices + 6 * q; /* a b c, a c d */
    uint32_t quad[4] = {t[0], t[1], t[2], t[5]};
    bool merge = q % 2 == 1;
    memcpy(m.indices + m.index_count, merge ? quad : t, sizeof(uint32_t) * (merge ? 4 : 6));
    m.index_count += merge ? 4 : 6;
    if (merge)
      m.sizes[m.face_count++] = 4;
    else
      m.sizes[m.face_count++] = 3, m.sizes[m.face_count++] = 3;
  }
  return m;
}

static bool mixed_scene(scene* sc, const shape* s, mixed_faces* m, tlod_surface_desc sd) {
  *m = mixed_of(s);
  tlod_mesh_desc md = shape_mesh_desc(s);
  md.indices = m->indices, md.index_count = m->index_count;
  md.face_type = TLOD_FACE_MIXED, md.face_sizes = m->sizes, md.face_count = m->face_count;
  return scene_make_desc(sc, "mixed torus", &md, sd);
}

/* tlod_surface_eval_interiors() against tlod_surface_eval_interior() patch
 * by patch, bitwise, with the patches in reverse order (triangles and
 * quads alternating on a mixed mesh) and written out of order. */
static void check_interiors(const scene* sc) {
  uint32_t nf = tlod_mesh_face_count(sc->mesh);
  float u[3] = {0.25f, 0.125f, 0.5f}, v[3] = {0.25f, 0.625f, 0.375f};
  uint32_t* patches = malloc(sizeof(uint32_t) * (nf + 1));
  uint32_t* first = malloc(sizeof(uint32_t) * (nf + 1));
  float* ref = calloc(9 * (size_t)(nf + 1), sizeof(float));
  float* got = calloc(9 * (size_t)(nf + 1), sizeof(float));
  for (uint32_t r = 0; r < nf; r++) {
    patches[r] = nf - 1 - r, first[r] = 3 * (r ^ 1);
    CHECK(tlod_surface_eval_interior(sc->surf, patches[r], TLOD_SIMD_SCALAR, 3, u, v, ref + 9 * (size_t)(r ^ 1),
                                     NULL) == TLOD_SUCCESS);
  }
  uint32_t n = nf & ~1u;
  for (tlod_simd simd = TLOD_SIMD_SCALAR; simd < TLOD_SIMD_NUM; simd++) {
    tlod_context* ctx = context(simd, 1);
    if (tlod_context_simd(ctx) == simd) {
      memset(got, 0, 9 * (size_t)(nf + 1) * sizeof(float));
      CHECK(tlod_surface_eval_interiors(sc->surf, simd, n, patches, 3, u, v, first, got) == TLOD_SUCCESS);
      CHECK_MSG(!memcmp(got, ref, sizeof(float) * 9 * n), "%s %s: interiors differ from tlod_surface_eval_interior",
                sc->name, tlod_simd_name(simd));
    }
    tlod_context_destroy(ctx);
  }
  uint32_t bad_patch = nf;
  CHECK(tlod_surface_eval_interiors(NULL, TLOD_SIMD_SCALAR, 1, patches, 3, u, v, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_interiors(sc->surf, TLOD_SIMD_SCALAR, 1, &bad_patch, 3, u, v, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_interiors(sc->surf, TLOD_SIMD_SCALAR, 1, patches, 3, u, NULL, first, got) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  free(patches);
  free(first);
  free(ref);
  free(got);
}

static void check_interiors_of(shape s, tlod_surface_desc sd) {
  scene sc;
  CHECK_MSG(scene_make(&sc, &s, NULL, 0, sd), "%s", s.name);
  if (sc.surf) check_interiors(&sc);
  scene_free(&sc);
  shape_free(&s);
}

TEST(test_interior_batch) {
  check_interiors_of(shape_torus(8, 6), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG});
  check_interiors_of(shape_quad_sphere(3), (tlod_surface_desc){.type = TLOD_SURFACE_PHONG});
  check_interiors_of(shape_cube_split(),
                     (tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = 0.4f});
  check_interiors_of(shape_quad_sphere(2), (tlod_surface_desc){.type = TLOD_SURFACE_FLAT});
  check_interiors_of(shape_icosphere(1), (tlod_surface_desc){.type = TLOD_SURFACE_PN});
  check_interiors_of(shape_quad_cube(), (tlod_surface_desc){.type = TLOD_SURFACE_QUADRATIC});
}

/* Triangles and quads alternating: the fast path's lanes per shape, and
 * the batch evaluation over both, against the reference. */
TEST(test_mixed) {
  shape s = shape_torus(12, 8);
  tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_FLAT};
  for (int k = 0; k < 2; k++) {
    scene sc;
    mixed_faces m;
    CHECK(mixed_scene(&sc, &s, &m, (tlod_surface_desc){.type = types[k]}));
    if (sc.surf) {
      check_scene(&sc, 4);
      check_interiors(&sc);
    }
    scene_free(&sc);
    free(m.indices);
    free(m.sizes);
  }
  shape_free(&s);
}

int main(void) {
  RUN(test_flat);
  RUN(test_phong);
  RUN(test_pn);
  RUN(test_quadratic);
  RUN(test_attributes);
  RUN(test_kept_topology);
  RUN(test_batch_arguments);
  RUN(test_edge_batch);
  RUN(test_interior_batch);
  RUN(test_mixed);
  TEST_END();
}
