/*
 * vtk_cracks_test.c -- crack-free adaptive output of imported hexahedral meshes over many cameras
 * (issue 14), checked as tests/unit/lod_scheduler_test.c checks its shapes: the scheduler's draw
 * list for a random camera (near, far, grazing, inside, orthographic) realised by the cpu
 * tessellator with no_weld (every patch its own pattern vertices, as a GPU draws them) must weld by
 * exact position into a closed, consistently oriented manifold (tests/unit/shapes.h); without
 * stitching some frame must open (the checker sees cracks). Meshes: the hex box (Phong quads, smooth
 * normals), the coarse hex cylinder (Phong quads, creases at 45 degrees: strips at the rims), the
 * 20- and 27-node hex pairs (quadratic, creases at 45 degrees), and the hex meshes of tests/data.
 * Usage: vtk_cracks_test WORK_DIR
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "vtk_test_util.h"

/* cameras per mesh; meshes of more than 100 patches get a quarter (CI time: ASan runs this too) */
#define CAMERAS 32
#define MAX_LEVEL 5

static const char* work = ".";

/* A camera around a mesh of bounding radius R about c: kind 0 near, 1 far, 2 grazing (looking
 * past the rim), 3 inside the bounds; every fifth orthographic. */
static camera random_view(shape_rng* rng, const double c[3], double R, int kind) {
  double dir[3], off[3];
  shape_rng_direction(rng, dir);
  shape_rng_direction(rng, off);
  static const double dist_lo[4] = {1.1, 5, 1.2, 0}, dist_hi[4] = {2, 30, 3, 0.8}, aim[4] = {0.5, 0.2, 1.0, 3};
  double d = R * shape_rng_range(rng, dist_lo[kind], dist_hi[kind]);
  camera cam = {.up = {0, 0, 1}, .fovy = shape_rng_range(rng, 30, 90) * M_PI / 180, .aspect = 4.0 / 3};
  for (int k = 0; k < 3; ++k)
    cam.eye[k] = c[k] + dir[k] * d, cam.target[k] = c[k] + off[k] * aim[kind] * R;
  double f[3] = {cam.target[0] - cam.eye[0], cam.target[1] - cam.eye[1], cam.target[2] - cam.eye[2]}, s[3];
  cross3(f, cam.up, s);
  if (len3(s) < 0.2 * len3(f)) cam.up[0] = 1, cam.up[2] = 0;
  cam.ortho = shape_rng_next(rng) % 5 == 0;
  cam.half_h = R * shape_rng_range(rng, 0.3, 1.5);
  cam.znear = R * 0.01, cam.zfar = d + 40 * R;
  cam.width = 640 + (uint32_t)(shape_rng_next(rng) % 1280), cam.height = (uint32_t)(cam.width / cam.aspect);
  return cam;
}

typedef struct crack_stats {
  uint32_t frames, strips, nostitch_open, nostitch_runs, max_level_seen;
} crack_stats;

static bool realise(tlod_context* ctx, const tlod_surface* s, const tlod_patterns* pat, const tlod_draw_list* dl,
                    bool no_stitch, tlod_cpu_mesh** out) {
  tlod_cpu_tessellate_desc d = {.draw_list = dl, .no_weld = true, .no_stitch = no_stitch, .no_normals = true};
  tlod_result r = *out ? tlod_cpu_tessellate_into(ctx, s, pat, &d, *out) : tlod_cpu_tessellate(ctx, s, pat, &d, out);
  if (r != TLOD_SUCCESS) fprintf(stderr, "tessellate: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return r == TLOD_SUCCESS;
}

/* Four schedulers (ERROR, HYBRID x morph NONE, TIME), no frustum culling: every frame closed. */
static void crack_suite(tlod_context* ctx, const tlod_surface* s, const char* what, int cameras, crack_stats* st) {
  tlod_patterns* pat = NULL;
  tlod_scheduler* sch[4] = {0};
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &pat) == TLOD_SUCCESS);
  for (int k = 0; k < 4; ++k) {
    tlod_scheduler_desc d = {.epsilon_px = 0.75f,
                             .max_level = MAX_LEVEL,
                             .policy = k % 2 ? TLOD_POLICY_HYBRID : TLOD_POLICY_ERROR,
                             .morph = k >= 2 ? TLOD_MORPH_TIME : TLOD_MORPH_NONE,
                             .morph_ms = 120,
                             .no_frustum_cull = true};
    CHECK(tlod_scheduler_create(ctx, s, pat, &d, &sch[k]) == TLOD_SUCCESS);
  }
  tlod_mesh_info info = tlod_mesh_query_info(tlod_surface_mesh(s));
  double c[3], R = 0;
  for (int k = 0; k < 3; ++k)
    c[k] = (info.bbox_min[k] + info.bbox_max[k]) / 2, R += pow(info.bbox_max[k] - c[k], 2);
  R = sqrt(R);
  shape_rng rng = {0x5eed + strlen(what)};
  tlod_cpu_mesh* out = NULL;
  for (int cam = 0; cam < cameras; ++cam) {
    camera cm = random_view(&rng, c, R, cam % 4);
    tlod_view_desc v = make_view(&cm);
    tlod_frame_desc f = {.views = &v, .view_count = 1, .dt_ms = (float)shape_rng_range(&rng, 0, 40)};
    for (int k = 0; k < 4; ++k) {
      CHECK(tlod_scheduler_update(sch[k], &f) == TLOD_SUCCESS);
      if (k != cam % 4 && !(k == 0 && cam % 3 == 0)) continue;
      const tlod_draw_list* dl = tlod_scheduler_draw_list(sch[k], 0);
      for (uint32_t p = 0; p < dl->patch_count; ++p)
        st->max_level_seen = dl->levels[p] > (int)st->max_level_seen ? (uint32_t)dl->levels[p] : st->max_level_seen;
      char why[200] = "";
      if (k == cam % 4) {
        CHECK(realise(ctx, s, pat, dl, false, &out));
        CHECK_MSG(vtk_test_closed(out, why, sizeof why), "%s scheduler %d camera %d (kind %d%s): not closed: %s", what,
                  k, cam, cam % 4, cm.ortho ? ", ortho" : "", why);
        st->frames++, st->strips += dl->strip_count;
      }
      if (k == 0 && cam % 3 == 0) {
        CHECK(realise(ctx, s, pat, dl, true, &out));
        st->nostitch_runs++, st->nostitch_open += !vtk_test_closed(out, why, sizeof why);
      }
    }
  }
  tlod_cpu_mesh_destroy(ctx, out);
  for (int k = 0; k < 4; ++k)
    tlod_scheduler_destroy(sch[k]);
  tlod_patterns_destroy(pat);
}

static void import_case(tlod_import_result* r, const char* name, tlod_surface_type type, float crease) {
  CHECK(r);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_mesh* mesh = vtk_test_mesh(ctx, r, crease, 0);
  tlod_surface* s = mesh ? vtk_test_surface(ctx, mesh, type) : NULL;
  crack_stats st = {0};
  int cameras = s && tlod_surface_patch_count(s) > 100 ? CAMERAS / 4 : CAMERAS;
  if (s) crack_suite(ctx, s, name, cameras, &st);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  tlod_import_free(r);
  printf("  %-14s %s: %u closed frames (%u strips, levels up to %u), no_stitch open in %u of %u\n", name,
         tlod_surface_type_name(type), st.frames, st.strips, st.max_level_seen, st.nostitch_open, st.nostitch_runs);
  CHECK_MSG(s && st.frames == (uint32_t)cameras, "%s: %u frames", name, st.frames);
  CHECK_MSG(st.strips > 0 && st.max_level_seen >= 3, "%s: the cameras never made mixed levels", name);
  CHECK_MSG(st.nostitch_open > 0, "%s: no_stitch never opened the mesh: the checker would miss cracks", name);
}

static void mesh_case(const vtk_model* m, const char* name, vtk_format format, tlod_surface_type type, float crease) {
  import_case(vtk_test_write_import(m, work, name, format), name, type, crease);
}

/* A file of tests/data (a real hex mesh from the shared corpus). */
static void data_case(const char* rel, tlod_surface_type type, float crease) {
  char path[1024], err[512];
  snprintf(path, sizeof path, "%s/%s", TLOD_TEST_DATA_DIR, rel);
  tlod_import_result* r = NULL;
  tlod_result res = tlod_import_file(path, NULL, &r, err, sizeof err);
  CHECK_MSG(res == TLOD_SUCCESS, "%s: %s", rel, err);
  import_case(r, strrchr(rel, '/') + 1, type, crease);
}

TEST(test_hex_box) {
  vtk_model m;
  vtk_build_box(&m, 4, 3, 2, 2.0, 1.5, 1.0);
  /* no creases: with them every box face is flat and one level would do */
  mesh_case(&m, "box.vtk", VTK_LEGACY_BINARY, TLOD_SURFACE_PHONG, 0);
  vtk_model_free(&m);
}

TEST(test_hex_cylinder) {
  vtk_model m;
  vtk_build_hex_cylinder(&m, 1, 2, 2);
  mesh_case(&m, "cylinder.vtu", VTK_XML_ASCII, TLOD_SURFACE_PHONG, 45);
  vtk_model_free(&m);
}

TEST(test_quadratic_hexes) {
  vtk_model m;
  vtk_build_quadratic_pair(&m, VTK_QUADRATIC_HEXAHEDRON);
  mesh_case(&m, "hex20.vtk", VTK_LEGACY_ASCII, TLOD_SURFACE_QUADRATIC, 45);
  vtk_model_free(&m);
  vtk_build_quadratic_pair(&m, VTK_TRIQUADRATIC_HEXAHEDRON);
  mesh_case(&m, "hex27.vtu", VTK_XML_ASCII, TLOD_SURFACE_QUADRATIC, 45);
  vtk_model_free(&m);
}

/* A linear hexahedron against a quadratic one: its faces take the quadratic edge nodes they meet
 * (4 edges), so the two stay closed at every level. */
TEST(test_mixed_order) {
  vtk_model m;
  vtk_build_mixed_order(&m);
  tlod_import_result* r = vtk_test_write_import(&m, work, "mixed_order.vtk", VTK_LEGACY_ASCII);
  vtk_model_free(&m);
  CHECK(r);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_mesh* mesh = vtk_test_mesh(ctx, r, 45, 0);
  tlod_mesh_info info = mesh ? tlod_mesh_query_info(mesh) : (tlod_mesh_info){0};
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  CHECK_MSG(info.face_count == 14 && info.curved_faces == 9 && info.nodes_shared == 4,
            "%u faces, %u curved, %u edges took a neighbour's node (14, 9, 4)", info.face_count, info.curved_faces,
            info.nodes_shared);
  import_case(r, "mixed_order.vtk", TLOD_SURFACE_QUADRATIC, 45);
}

/* sfepy's hsphere8.vtk (648 hexahedra, an eighth of a sphere: 432 boundary quads) and VTK's
 * Hexahedron.vtu (7 hexahedra), with the tools' VTK crease default (40 degrees). */
TEST(test_data_hex_meshes) {
  data_case("sfepy/hsphere8.vtk", TLOD_SURFACE_PHONG, 40);
  data_case("vtk-data/Hexahedron.vtu", TLOD_SURFACE_PHONG, 0);
}

int main(int argc, char** argv) {
  if (argc > 1) work = argv[1];
  RUN(test_hex_box);
  RUN(test_hex_cylinder);
  RUN(test_quadratic_hexes);
  RUN(test_mixed_order);
  RUN(test_data_hex_meshes);
  TEST_END();
}
