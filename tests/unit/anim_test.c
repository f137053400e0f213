/*
 * anim_test.c -- the tools' animation and skinning maths
 * (tools/tlod/common/anim_sample.h, skin_apply.h) against values computed
 * by hand or in double precision here, and a generated skinned cylinder
 * (skin_cylinder.h) that must stay closed through skinning, tlod_mesh_update,
 * tlod_surface_refresh and the CPU tessellator at every sampled frame.
 * Tolerances: sampled values 1e-6 (one float rounding of values near 1);
 * skinned positions 4 ulps of the cylinder's largest coordinate.
 */
#include <float.h>
#include <stdint.h>
#include <stdio.h>

#include "common/anim_sample.h"
#include "common/skin_apply.h"
#include "common/skin_cylinder.h"
#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"

#define PI 3.14159265358979323846
#define TOL 1e-6

/* Unit quaternion of `deg` degrees about the unit axis (x, y, z). */
static void axis_angle(double x, double y, double z, double deg, float q[4]) {
  double h = deg * PI / 360.0;
  q[0] = (float)(x * sin(h)), q[1] = (float)(y * sin(h)), q[2] = (float)(z * sin(h)), q[3] = (float)cos(h);
}

static anim_channel channel(anim_path path, anim_interp interp, uint32_t keys, const float* t, const float* v) {
  return (anim_channel){.node = 0, .path = path, .interp = interp, .key_count = keys, .times = t, .values = v};
}

/* |dot| of two quaternions: 1 for the same rotation (q and -q alike). */
static double same_rotation(const float a[4], const float b[4]) {
  double d = 0.0;
  for (int i = 0; i < 4; i++)
    d += (double)a[i] * b[i];
  return fabs(d);
}

TEST(test_linear_translation_clamped) {
  const float t[3] = {0.0f, 1.0f, 3.0f}, v[9] = {0, 0, 0, 2, 0, 0, 2, 4, 0};
  anim_channel c = channel(ANIM_PATH_TRANSLATION, ANIM_INTERP_LINEAR, 3, t, v);
  const float at[5] = {-1.0f, 0.5f, 2.0f, 3.0f, 7.0f};
  const double want[5][3] = {{0, 0, 0}, {1, 0, 0}, {2, 2, 0}, {2, 4, 0}, {2, 4, 0}};
  for (int k = 0; k < 5; k++) {
    float o[4];
    anim_channel_sample(&c, at[k], o);
    for (int i = 0; i < 3; i++)
      CHECK_NEAR(o[i], want[k][i], TOL);
  }
  float o[4];
  anim_channel_sample(&c, NAN, o);
  CHECK(o[0] == 0.0f && o[1] == 0.0f);
  CHECK(anim_duration(&c, 1) == 3.0f);
}

TEST(test_step) {
  const float t[3] = {0.0f, 1.0f, 3.0f}, v[9] = {1, 1, 1, 2, 2, 2, 5, 5, 5};
  anim_channel c = channel(ANIM_PATH_SCALE, ANIM_INTERP_STEP, 3, t, v);
  const float at[5] = {0.5f, 0.999f, 1.0f, 2.9f, 3.5f};
  const float want[5] = {1, 1, 2, 2, 5};
  for (int k = 0; k < 5; k++) {
    float o[4];
    anim_channel_sample(&c, at[k], o);
    CHECK_MSG(o[0] == want[k] && o[2] == want[k], "t %g: %g, expected %g", at[k], o[0], want[k]);
  }
}

/* Keys (0 s, v0) and (2 s, v1) with out-tangent b0 and in-tangent a1: at
 * s = 0.5 the Hermite basis is h00 = h01 = 0.5, h10 = 0.125 td, h11 =
 * -0.125 td with td = 2, so p = 0.5 v0 + 0.25 b0 + 0.5 v1 - 0.25 a1:
 * x: 0.25 + 0.5 = 0.75; y: 0.5 + 0.5 + 1 = 2; z: 0.5. */
TEST(test_cubic_spline) {
  const float t[2] = {0.0f, 2.0f};
  const float v[18] = {9, 9,  9, 0, 0, 0, 1, 2, 0,  /* key 0: in (ignored), value, out */
                       0, -4, 0, 1, 1, 1, 9, 9, 9}; /* key 1: in, value, out (ignored) */
  anim_channel c = channel(ANIM_PATH_TRANSLATION, ANIM_INTERP_CUBICSPLINE, 2, t, v);
  float o[4];
  anim_channel_sample(&c, 1.0f, o);
  CHECK_NEAR(o[0], 0.75, TOL);
  CHECK_NEAR(o[1], 2.0, TOL);
  CHECK_NEAR(o[2], 0.5, TOL);
  anim_channel_sample(&c, 0.0f, o);
  CHECK(o[0] == 0.0f && o[1] == 0.0f);
  anim_channel_sample(&c, 2.0f, o);
  CHECK(o[0] == 1.0f && o[1] == 1.0f);
  /* Rotations: zero tangents, identity to 90 degrees about z: the middle is
   * half the sum, renormalised: 45 degrees. */
  float r[12 * 2] = {0}, want[4];
  axis_angle(0, 0, 1, 0, r + 4);
  axis_angle(0, 0, 1, 90, r + 16);
  anim_channel cr = channel(ANIM_PATH_ROTATION, ANIM_INTERP_CUBICSPLINE, 2, t, r);
  anim_channel_sample(&cr, 1.0f, o);
  axis_angle(0, 0, 1, 45, want);
  for (int i = 0; i < 4; i++)
    CHECK_NEAR(o[i], want[i], TOL);
}

/* Slerp from the identity: 90 degrees about z at a quarter is 22.5 degrees;
 * 179 degrees about y at a half is 89.5 degrees. */
TEST(test_slerp) {
  const float t[2] = {0.0f, 1.0f};
  const struct {
    double axis[3], deg, s, want_deg;
  } cases[] = {{{0, 0, 1}, 90, 0.25, 22.5}, {{0, 1, 0}, 179, 0.5, 89.5}, {{1, 0, 0}, 179, 0.9, 161.1}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    float v[8], o[4], want[4];
    axis_angle(0, 0, 1, 0, v);
    axis_angle(cases[k].axis[0], cases[k].axis[1], cases[k].axis[2], cases[k].deg, v + 4);
    anim_channel c = channel(ANIM_PATH_ROTATION, ANIM_INTERP_LINEAR, 2, t, v);
    anim_channel_sample(&c, (float)cases[k].s, o);
    axis_angle(cases[k].axis[0], cases[k].axis[1], cases[k].axis[2], cases[k].want_deg, want);
    for (int i = 0; i < 4; i++)
      CHECK_NEAR(o[i], want[i], TOL);
  }
}

/* The short way: 270 degrees about z is -90 degrees the short way (its
 * quaternion has a negative dot with the identity), so the middle is -45
 * degrees, not 135; and a key written as -q is the same rotation. */
TEST(test_slerp_short_way) {
  const float t[2] = {0.0f, 1.0f};
  float v[8], o[4], want[4];
  axis_angle(0, 0, 1, 0, v);
  axis_angle(0, 0, 1, 270, v + 4);
  CHECK(v[7] < 0.0f);
  anim_channel c = channel(ANIM_PATH_ROTATION, ANIM_INTERP_LINEAR, 2, t, v);
  anim_channel_sample(&c, 0.5f, o);
  axis_angle(0, 0, 1, -45, want);
  CHECK_MSG(same_rotation(o, want) > 1.0 - TOL, "got (%g %g %g %g)", o[0], o[1], o[2], o[3]);
  axis_angle(0, 0, 1, 60, v + 4);
  for (int i = 4; i < 8; i++)
    v[i] = -v[i];
  anim_channel_sample(&c, 0.5f, o);
  axis_angle(0, 0, 1, 30, want);
  CHECK_MSG(same_rotation(o, want) > 1.0 - TOL, "got (%g %g %g %g)", o[0], o[1], o[2], o[3]);
  double len = sqrt((double)o[0] * o[0] + (double)o[1] * o[1] + (double)o[2] * o[2] + (double)o[3] * o[3]);
  CHECK_NEAR(len, 1.0, TOL);
}

static void transform(const float m[16], const double p[3], double out[3]) {
  for (int r = 0; r < 3; r++)
    out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* Parent node 0 turns about y (0 to 90 degrees) and rises (0 to 4) over
 * 1 s; child node 1 sits 2 along the parent's x. The child's origin goes
 * along (2 cos a, 4 t, -2 sin a), a = 90 t degrees. */
TEST(test_node_path) {
  const float t[2] = {0.0f, 1.0f}, tv[6] = {0, 0, 0, 0, 4, 0};
  float rv[8];
  axis_angle(0, 1, 0, 0, rv);
  axis_angle(0, 1, 0, 90, rv + 4);
  anim_channel ch[2] = {channel(ANIM_PATH_TRANSLATION, ANIM_INTERP_LINEAR, 2, t, tv),
                        channel(ANIM_PATH_ROTATION, ANIM_INTERP_LINEAR, 2, t, rv)};
  const uint32_t parent[2] = {UINT32_MAX, 0};
  for (int k = 0; k <= 4; k++) {
    double tt = 0.25 * k, a = 0.5 * PI * tt, want[3] = {2 * cos(a), 4 * tt, -2 * sin(a)}, got[3];
    anim_trs nodes[2] = {{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}, {{2, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
    anim_apply(ch, 2, (float)tt, nodes, 2);
    float local[2][16], world[2][16];
    uint32_t scratch[4];
    anim_trs_matrix(&nodes[0], local[0]);
    anim_trs_matrix(&nodes[1], local[1]);
    CHECK(anim_world_matrices(2, parent, (const float(*)[16])local, world, scratch));
    transform(world[1], (const double[3]){0, 0, 0}, got);
    for (int i = 0; i < 3; i++)
      CHECK_NEAR(got[i], want[i], 4 * TOL);
  }
}

/* A chain listed child first gives the same world matrices as parent
 * first; a cycle is refused. */
TEST(test_world_matrices_any_order) {
  anim_trs trs[3] = {
      {{1, 0, 0}, {0, 0, 0, 1}, {2, 2, 2}}, {{0, 1, 0}, {0, 0, 0, 1}, {1, 1, 1}}, {{0, 0, 1}, {0, 0, 0, 1}, {1, 1, 1}}};
  axis_angle(0, 0, 1, 90, trs[1].rotation);
  float local[3][16], fwd[3][16], rev_local[3][16], rev[3][16];
  for (int i = 0; i < 3; i++)
    anim_trs_matrix(&trs[i], local[i]);
  for (int i = 0; i < 3; i++)
    memcpy(rev_local[2 - i], local[i], sizeof local[i]);
  const uint32_t parent_fwd[3] = {UINT32_MAX, 0, 1}, parent_rev[3] = {1, 2, UINT32_MAX};
  uint32_t scratch[6];
  CHECK(anim_world_matrices(3, parent_fwd, (const float(*)[16])local, fwd, scratch));
  CHECK(anim_world_matrices(3, parent_rev, (const float(*)[16])rev_local, rev, scratch));
  for (int i = 0; i < 3; i++)
    CHECK(!memcmp(fwd[i], rev[2 - i], sizeof fwd[i]));
  /* Leaf origin: 1 + 2 * Rz(90) (0, 1 + 1 * ..) by hand: the leaf sits at
   * (0, 0, 1) in node 1, node 1 at (0, 1, 0) in node 0 (scaled 2):
   * (1, 0, 0) + 2 * ((0, 1, 0) + Rz(90) (0, 0, 1)) = (1, 2, 2). */
  double got[3];
  transform(fwd[2], (const double[3]){0, 0, 0}, got);
  CHECK_NEAR(got[0], 1.0, TOL);
  CHECK_NEAR(got[1], 2.0, TOL);
  CHECK_NEAR(got[2], 2.0, TOL);
  const uint32_t cycle[3] = {2, 0, 1};
  CHECK(!anim_world_matrices(3, cycle, (const float(*)[16])local, fwd, scratch));
}

/* ------------------------------------------------------------------------ */
/* The skinned cylinder                                                     */
/* ------------------------------------------------------------------------ */

#define CYL_HEIGHT 4.0f
#define CYL_PIVOT 2.0 /* joint 1, at half the height */

/* The cylinder's skinning matrices at t: the channel turns joint 1. */
static void cylinder_pose(const skin_cylinder* c, const anim_channel* turn, float t, float mats[2][16]) {
  anim_trs trs[2] = {{{0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}}, {{0, (float)CYL_PIVOT, 0}, {0, 0, 0, 1}, {1, 1, 1}}};
  anim_apply(turn, 1, t, trs, 2);
  skin_cylinder_pose(c, trs[1].rotation, mats);
}

/* The same pose by hand in double: joint 1 turns by a about z round the
 * pivot, so p' = w0 p + w1 (c + Rz(a)(p - c)); the blended linear part is
 * w0 I + w1 Rz(a) = k Rz(phi) in the xy plane, whose inverse transpose is
 * Rz(phi) / k there, 1 along z. */
static void reference_vertex(const float p[3], const float n[3], const float w[4], double a, double out_p[3],
                             double out_n[3]) {
  double c = cos(a), s = sin(a), x = p[0], y = p[1] - CYL_PIVOT;
  double rx = c * x - s * y, ry = s * x + c * y + CYL_PIVOT;
  out_p[0] = w[0] * p[0] + w[1] * rx;
  out_p[1] = w[0] * p[1] + w[1] * ry;
  out_p[2] = p[2];
  double ma = w[0] + w[1] * c, mb = w[1] * s, k = sqrt(ma * ma + mb * mb);
  double nx = (ma * n[0] - mb * n[1]) / (k * k), ny = (mb * n[0] + ma * n[1]) / (k * k), nz = n[2];
  double len = sqrt(nx * nx + ny * ny + nz * nz);
  out_n[0] = nx / len, out_n[1] = ny / len, out_n[2] = nz / len;
}

/* Skinned arrays against reference_vertex: positions within 4 ulps of the
 * largest coordinate, normals 1e-5. */
static void check_reference(const skin_cylinder* cyl, const float* pos, const float* nrm, double a) {
  double tol = 4.0 * FLT_EPSILON * CYL_HEIGHT, worst = 0.0;
  for (uint32_t v = 0; v < cyl->vertex_count; v++) {
    double rp[3], rn[3];
    reference_vertex(cyl->positions + 3 * v, cyl->normals + 3 * v, cyl->weights + 4 * v, a, rp, rn);
    for (int i = 0; i < 3; i++) {
      double e = fabs(pos[3 * v + i] - rp[i]);
      worst = e > worst ? e : worst;
      CHECK_MSG(e <= tol, "vertex %u coord %d: %.9g, reference %.9g", v, i, pos[3 * v + i], rp[i]);
      CHECK_MSG(fabs(nrm[3 * v + i] - rn[i]) <= 1e-5, "vertex %u normal %d: %.9g, reference %.9g", v, i, nrm[3 * v + i],
                rn[i]);
    }
  }
  printf("  angle %5.1f deg: worst position error %.3g (tolerance %.3g)\n", a * 180.0 / PI, worst, tol);
}

static int cmp_position(const void* a, const void* b) { return memcmp(a, b, 12); }

/* Every skinned vertex is a corner of the tessellation, bitwise. */
static void check_corners_present(const tlod_cpu_mesh* m, const float* pos, uint32_t count) {
  float* sorted = malloc(sizeof(float) * 3 * m->vertex_count);
  CHECK(sorted);
  memcpy(sorted, m->positions, sizeof(float) * 3 * m->vertex_count);
  qsort(sorted, m->vertex_count, 12, cmp_position);
  uint32_t missing = 0;
  for (uint32_t v = 0; v < count; v++)
    missing += !bsearch(pos + 3 * v, sorted, m->vertex_count, 12, cmp_position);
  free(sorted);
  CHECK_MSG(missing == 0, "%u skinned vertices are no output corner", missing);
}

typedef struct cylinder_fixture {
  tlod_context* ctx;
  skin_cylinder_model m;
  tlod_patterns* pat;
} cylinder_fixture;

static void cylinder_free(cylinder_fixture* f) {
  tlod_patterns_destroy(f->pat);
  skin_cylinder_model_free(&f->m);
  tlod_context_destroy(f->ctx);
}

static bool cylinder_make(cylinder_fixture* f, uint32_t segments, uint32_t rings) {
  memset(f, 0, sizeof *f);
  return (f->ctx = new_context(2, NULL, NULL)) &&
         skin_cylinder_model_create(f->ctx, segments, rings, 0.5f, CYL_HEIGHT, &f->m) &&
         tlod_patterns_create(f->ctx, &(tlod_patterns_desc){.max_level = 4}, &f->pat) == TLOD_SUCCESS;
}

static skin_vertices cylinder_vertices(const skin_cylinder* c) {
  return (skin_vertices){c->vertex_count, c->positions, c->normals, c->joints, c->weights};
}

/* Tessellation at per-patch levels 0..4 (a different mix each frame) and
 * uniformly at 3: closed after welding by exact position, every skinned
 * vertex among the corners. */
static void check_tessellations(const cylinder_fixture* f, uint32_t frame) {
  uint32_t patches = tlod_surface_patch_count(f->m.surface);
  int8_t* levels = malloc(patches);
  CHECK(levels);
  uint32_t x = 0x9E3779B9u * (frame + 1);
  for (uint32_t p = 0; p < patches; p++)
    levels[p] = (int8_t)((x = x * 1664525u + 1013904223u) >> 29) % 5;
  for (int k = 0; k < 2; k++) {
    tlod_cpu_tessellate_desc d = {.level = 3, .levels = k ? NULL : levels, .no_weld = k == 1};
    tlod_cpu_mesh* m = NULL;
    CHECK(tlod_cpu_tessellate(f->ctx, f->m.surface, f->pat, &d, &m) == TLOD_SUCCESS);
    char why[256] = "";
    bool closed = shape_closed_manifold(m->positions, m->vertex_count, m->indices, m->triangle_count, m->triangle_patch,
                                        why, sizeof why);
    check_corners_present(m, f->m.positions, f->m.cyl.vertex_count);
    tlod_cpu_mesh_destroy(f->ctx, m);
    CHECK_MSG(closed, "frame %u, %s: %s", frame, k ? "uniform level 3" : "levels 0..4", why);
  }
  free(levels);
}

/* Corners of every patch evaluate to the skinned vertices exactly. */
static void check_surface_corners(const cylinder_fixture* f) {
  tlod_mesh_view mv = tlod_mesh_query_view(f->m.mesh);
  for (uint32_t p = 0; p < mv.face_count; p++) {
    const float uv[3][2] = {{1, 0}, {0, 1}, {0, 0}};
    for (int c = 0; c < 3; c++) {
      tlod_surface_point sp;
      CHECK(tlod_surface_eval(f->m.surface, p, uv[c][0], uv[c][1], &sp) == TLOD_SUCCESS);
      CHECK_MSG(!memcmp(sp.position, f->m.positions + 3 * mv.faces[p][c], 12), "patch %u corner %d", p, c);
    }
  }
}

/* Joint 1 bends the cylinder 0 to 90 degrees about z over 1 s; at every
 * sampled frame the skinned mesh matches the reference, the surface's
 * corners are the skinned vertices, and the tessellations stay closed. The
 * lower third of the cylinder (joint 0 only) never moves, so a refresh
 * after the first bend recomputes fewer than all patches. */
TEST(test_skinned_cylinder) {
  cylinder_fixture f;
  bool made = cylinder_make(&f, 16, 8);
  CHECK_MSG(made, "cylinder set-up: %s", f.ctx ? tlod_context_last_error(f.ctx) : "no context");
  tlod_mesh_info info = tlod_mesh_query_info(f.m.mesh);
  CHECK_MSG(info.closed && info.crease_edges == 32, "closed %d, %u crease edges", info.closed, info.crease_edges);
  const float t[2] = {0.0f, 1.0f};
  float rv[8];
  axis_angle(0, 0, 1, 0, rv);
  axis_angle(0, 0, 1, 90, rv + 4);
  anim_channel turn = channel(ANIM_PATH_ROTATION, ANIM_INTERP_LINEAR, 2, t, rv);
  turn.node = 1;
  skin_vertices sv = cylinder_vertices(&f.m.cyl);
  const float frames[5] = {0.0f, 0.2f, 0.5f, 0.8f, 1.0f};
  uint32_t patches = tlod_surface_patch_count(f.m.surface), updated = 0;
  for (uint32_t k = 0; k < 5; k++) {
    float mats[2][16];
    cylinder_pose(&f.m.cyl, &turn, frames[k], mats);
    skin_apply(f.ctx, &sv, 2, (const float(*)[16])mats, f.m.positions, f.m.normals);
    CHECK(tlod_mesh_update(f.m.mesh, f.m.positions, 0, f.m.normals, 0) == TLOD_SUCCESS);
    CHECK(tlod_surface_refresh(f.m.surface, &updated) == TLOD_SUCCESS);
    if (k > 0) CHECK_MSG(updated > 0 && updated + 80 <= patches, "frame %u: %u of %u patches", k, updated, patches);
    CALL(check_reference(&f.m.cyl, f.m.positions, f.m.normals, 0.5 * PI * frames[k]));
    CALL(check_surface_corners(&f));
    CALL(check_tessellations(&f, k));
  }
  cylinder_free(&f);
}

/* The same bits on one thread and on a pool running chunks in reverse. */
TEST(test_skin_thread_independent) {
  skin_cylinder cyl;
  CHECK(skin_cylinder_create(64, 60, 0.5f, CYL_HEIGHT, &cyl) && cyl.vertex_count > 3 * 1024);
  reverse_pool pool = {0};
  tlod_context *one = new_context(1, NULL, NULL), *rev = new_context(0, NULL, &pool);
  float mats[2][16], rv[8];
  axis_angle(0, 0, 1, 0, rv);
  axis_angle(1, 0, 0, 70, rv + 4);
  const float t[2] = {0.0f, 1.0f};
  anim_channel turn = channel(ANIM_PATH_ROTATION, ANIM_INTERP_LINEAR, 2, t, rv);
  turn.node = 1;
  cylinder_pose(&cyl, &turn, 0.7f, mats);
  size_t bytes = sizeof(float) * 3 * cyl.vertex_count;
  float *p1 = malloc(bytes), *n1 = malloc(bytes), *p2 = malloc(bytes), *n2 = malloc(bytes);
  skin_vertices sv = cylinder_vertices(&cyl);
  skin_apply(one, &sv, 2, (const float(*)[16])mats, p1, n1);
  skin_apply(rev, &sv, 2, (const float(*)[16])mats, p2, n2);
  bool same = !memcmp(p1, p2, bytes) && !memcmp(n1, n2, bytes);
  long chunks = pool.chunks;
  free(p1), free(n1), free(p2), free(n2);
  tlod_context_destroy(one);
  tlod_context_destroy(rev);
  skin_cylinder_free(&cyl);
  CHECK_MSG(same && chunks >= 1, "results differ (%ld chunks)", chunks);
}

/* Normals go by the inverse transpose: a joint scaling x by 2 turns the
 * normal (1, 1, 0) towards (0.5, 1, 0), not (2, 1, 0); a mirror (x by -1)
 * flips (1, 0, 0) to (-1, 0, 0) (the determinant's sign). A vertex whose
 * weights land on no joint (index past the joints) keeps its rest pose. */
TEST(test_skin_normals) {
  const float mats[2][16] = {{2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                             {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
  const float rp[9] = {1, 2, 3, 1, 2, 3, 1, 2, 3};
  const float rn[9] = {0.70710678f, 0.70710678f, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t joints[12] = {0, 0, 0, 0, 1, 0, 0, 0, 7, 0, 0, 0};
  const float weights[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  skin_vertices sv = {3, rp, rn, joints, weights};
  float p[9], n[9];
  skin_range(&sv, 2, mats, 0, 3, p, n);
  double l = sqrt(1.25);
  CHECK_NEAR(p[0], 2.0, 0.0);
  CHECK_NEAR(n[0], 0.5 / l, TOL);
  CHECK_NEAR(n[1], 1.0 / l, TOL);
  CHECK_NEAR(p[3], -1.0, 0.0);
  CHECK_NEAR(n[3], -1.0, TOL);
  CHECK(!memcmp(p + 6, rp + 6, 12) && !memcmp(n + 6, rn + 6, 12));
}

int main(void) {
  RUN(test_skin_normals);
  RUN(test_linear_translation_clamped);
  RUN(test_step);
  RUN(test_cubic_spline);
  RUN(test_slerp);
  RUN(test_slerp_short_way);
  RUN(test_node_path);
  RUN(test_world_matrices_any_order);
  RUN(test_skinned_cylinder);
  RUN(test_skin_thread_independent);
  TEST_END();
}
