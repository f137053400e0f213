/*
 * vtk_surface_test.c -- volume meshes of known size, written as VTK files at run time and read
 * through tlod_import_file() (issue 14): boundary face counts against the counts known by
 * construction, quads kept as quads, closed and outward boundaries, area and enclosed volume
 * against the known values, Phong quads of a coarse hex cylinder closer to the true cylinder than
 * the flat quads, and fields (point, vector, cell data averaged to points) with their min/max
 * through tessellation. Usage: vtk_surface_test WORK_DIR
 *
 * Tolerances: flat tessellations of planar boundaries match area and volume to 1e-5 relative
 * (float positions); curved ones are compared with the flat ones, not with a fixed number.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test.h"
#include "vtk_test_util.h"

static const char* work = ".";

static const tlod_import_cell_count* cell_type(const tlod_import_vtk_info* v, uint32_t type) {
  for (uint32_t k = 0; k < v->cell_type_count; ++k)
    if (v->cell_types[k].vtk_type == type) return &v->cell_types[k];
  return NULL;
}

static uint64_t cells_of(const tlod_import_vtk_info* v, uint32_t type) {
  const tlod_import_cell_count* c = cell_type(v, type);
  return c ? c->count : 0;
}

/* Counts an import must report for a volume mesh. */
typedef struct expect {
  uint64_t cells, triangles, quads, interior, reoriented;
} expect;

static void check_counts(const tlod_import_result* r, const expect* e, const char* what) {
  CHECK_MSG(r->vtk, "%s: no VTK info", what);
  const tlod_import_vtk_info* v = r->vtk;
  CHECK_MSG(v->cells == e->cells && v->volume_cells == e->cells, "%s: cells %llu, volume cells %llu, built %llu", what,
            (unsigned long long)v->cells, (unsigned long long)v->volume_cells, (unsigned long long)e->cells);
  CHECK_MSG(v->boundary_triangles == e->triangles && v->boundary_quads == e->quads,
            "%s: boundary %llu triangles %llu quads, by construction %llu and %llu", what,
            (unsigned long long)v->boundary_triangles, (unsigned long long)v->boundary_quads,
            (unsigned long long)e->triangles, (unsigned long long)e->quads);
  CHECK_MSG(v->interior_faces == e->interior && v->non_manifold_faces == 0,
            "%s: %llu interior faces (built %llu), %llu "
            "non-manifold",
            what, (unsigned long long)v->interior_faces, (unsigned long long)e->interior,
            (unsigned long long)v->non_manifold_faces);
  CHECK_MSG(v->cells_reoriented == e->reoriented, "%s: %llu cells reoriented, %llu written inverted", what,
            (unsigned long long)v->cells_reoriented, (unsigned long long)e->reoriented);
  uint32_t tris, quads;
  vtk_test_face_sizes(r, &tris, &quads);
  CHECK_MSG(tris == e->triangles && quads == e->quads, "%s: result faces %u triangles %u quads (quads kept as quads)",
            what, tris, quads);
}

/* Mesh + surface + uniform tessellation of an import; the boundary must be closed, its flat (or
 * given) surface's area and volume are returned. */
typedef struct measured {
  double area, volume;
  bool closed;
  tlod_mesh_info info;
} measured;

static measured measure(const tlod_import_result* r, tlod_surface_type type, uint32_t level, float crease) {
  measured out = {0};
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) != TLOD_SUCCESS) return out;
  tlod_mesh* mesh = vtk_test_mesh(ctx, r, crease, 0);
  tlod_surface* s = mesh ? vtk_test_surface(ctx, mesh, type) : NULL;
  tlod_cpu_mesh* cm = s ? vtk_test_tessellate(ctx, s, level, true) : NULL;
  if (cm) {
    char why[160] = "";
    out.closed = vtk_test_closed(cm, why, sizeof why);
    if (!out.closed) fprintf(stderr, "  not closed: %s\n", why);
    vtk_test_area_volume(cm, &out.area, &out.volume);
    out.info = tlod_mesh_query_info(mesh);
  }
  tlod_cpu_mesh_destroy(ctx, cm);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  return out;
}

/* ---- box ---- */

TEST(test_box_all_formats) {
  static const struct {
    const char* name;
    vtk_format format;
  } files[3] = {{"box_ascii.vtk", VTK_LEGACY_ASCII}, {"box_binary.vtk", VTK_LEGACY_BINARY}, {"box.vtu", VTK_XML_ASCII}};
  vtk_model m;
  vtk_build_box(&m, 4, 3, 2, 2.0, 1.5, 1.0);
  /* 4x3x2 cells: 2 (4*3 + 3*2 + 4*2) = 52 boundary quads of 144 cell faces, (144 - 52) / 2 interior */
  expect e = {24, 0, 52, 46, m.inverted};
  for (int k = 0; k < 3; ++k) {
    tlod_import_result* r = vtk_test_write_import(&m, work, files[k].name, files[k].format);
    CHECK_MSG(r, "%s", files[k].name);
    check_counts(r, &e, files[k].name);
    measured f = measure(r, TLOD_SURFACE_FLAT, 2, 0);
    tlod_import_free(r);
    CHECK_MSG(f.closed && f.info.closed && f.info.quad_count == 52 && f.info.triangle_count == 0,
              "%s: closed %d (core: %d), %u quads %u triangles", files[k].name, f.closed, f.info.closed,
              f.info.quad_count, f.info.triangle_count);
    CHECK_MSG(fabs(f.area - 13.0) <= 1e-5 * 13 && fabs(f.volume - 3.0) <= 1e-5 * 3,
              "%s: area %.9g (13), volume %.9g (3; negative: faces inward)", files[k].name, f.area, f.volume);
  }
  vtk_model_free(&m);
}

/* ---- fields ---- */

/* The model point at an imported vertex (positions are unique in the box). */
static uint32_t model_point(const vtk_model* m, const float* p) {
  for (uint32_t k = 0; k < m->point_count; ++k)
    if ((float)m->points[3 * k] == p[0] && (float)m->points[3 * k + 1] == p[1] && (float)m->points[3 * k + 2] == p[2])
      return k;
  return UINT32_MAX;
}

/* Point field "pressure" as the importer must average it: the mean over the cells using a point. */
static void cell_means(const vtk_model* m, double* mean) {
  double* n = calloc(m->point_count, sizeof *n);
  memset(mean, 0, m->point_count * sizeof *mean);
  for (uint32_t c = 0; c < m->cell_count; ++c)
    for (uint32_t k = m->offsets[c]; k < m->offsets[c + 1]; ++k)
      mean[m->conn[k]] += m->fields[2].data[c], n[m->conn[k]] += 1;
  for (uint32_t p = 0; p < m->point_count; ++p)
    mean[p] /= n[p];
  free(n);
}

static const tlod_import_field* field_named(const tlod_import_result* r, const char* prefix) {
  for (uint32_t k = 0; k < r->field_count; ++k)
    if (strncmp(r->fields[k].name, prefix, strlen(prefix)) == 0) return &r->fields[k];
  return NULL;
}

/* Every boundary vertex's values against the model's (float rounding of a double). */
static void check_field_values(const vtk_model* m, const tlod_import_result* r) {
  double* mean = malloc(m->point_count * sizeof *mean);
  cell_means(m, mean);
  const tlod_import_field *t = field_named(r, "temperature"), *d = field_named(r, "displacement"),
                          *p = field_named(r, "pressure");
  uint32_t bad = 0, first = UINT32_MAX;
  for (uint32_t v = 0; v < r->vertex_count; ++v) {
    uint32_t q = model_point(m, r->positions + 3 * (size_t)v);
    bool ok = q != UINT32_MAX && fabs(t->data[v] - m->fields[0].data[q]) <= 1e-4 &&
              fabs(p->data[v] - mean[q]) <= 1e-5 * (1 + mean[q]);
    for (int k = 0; k < 3 && ok; ++k)
      ok = fabs(d->data[3 * v + k] - m->fields[1].data[3 * q + k]) <= 1e-6;
    if (!ok && first == UINT32_MAX) first = v;
    bad += !ok;
  }
  free(mean);
  CHECK_MSG(bad == 0, "%u vertices with values other than the file's (first: vertex %u)", bad, first);
}

TEST(test_box_fields) {
  vtk_model m;
  vtk_build_box(&m, 4, 3, 2, 2.0, 1.5, 1.0);
  snprintf(m.fields[0].name, sizeof m.fields[0].name, "temperature [K]");
  tlod_import_result* r = vtk_test_write_import(&m, work, "box_fields.vtu", VTK_XML_ASCII);
  CHECK(r);
  const tlod_import_field *t = field_named(r, "temperature"), *d = field_named(r, "displacement"),
                          *p = field_named(r, "pressure");
  CHECK_MSG(r->field_count == 3 && t && d && p, "%u fields", r->field_count);
  /* T = 100 + 10x - 5y + z^2 on [0,2]x[0,1.5]x[0,1]: 92.5 at (0, 1.5, 0), 121 at (2, 0, 1) */
  CHECK_MSG(t->components == 1 && !t->from_cells && strcmp(t->units, "K") == 0,
            "temperature: %u components, units "
            "'%s'",
            t->components, t->units);
  CHECK_MSG(t->min[0] == 92.5f && t->max[0] == 121.0f, "temperature range %.9g..%.9g (92.5..121)", t->min[0],
            t->max[0]);
  /* |(x, -2y, z/2)|: 0 at the origin, |(2, -3, 0.5)| at the far corner */
  CHECK_MSG(d->components == 3 && d->magnitude_min == 0.0f && fabsf(d->magnitude_max - (float)sqrt(13.25)) <= 1e-6f,
            "displacement: %u components, magnitude %.9g..%.9g", d->components, d->magnitude_min, d->magnitude_max);
  CHECK_MSG(p->from_cells && p->components == 1, "pressure: from_cells %d", p->from_cells);
  CALL(check_field_values(&m, r));
  /* through tessellation: attributes interpolate between corner values, corners exact */
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  tlod_mesh* mesh = vtk_test_mesh(ctx, r, 40, 3);
  tlod_surface* s = mesh ? vtk_test_surface(ctx, mesh, TLOD_SURFACE_PHONG) : NULL;
  tlod_cpu_mesh* cm = s ? vtk_test_tessellate(ctx, s, 3, false) : NULL;
  float lo = INFINITY, hi = -INFINITY;
  uint32_t ta = UINT32_MAX;
  for (uint32_t a = 0; mesh && a < tlod_mesh_attribute_count(mesh); ++a)
    if (strncmp(tlod_mesh_query_attribute(mesh, a).name, "temperature", 11) == 0) ta = a;
  for (uint32_t v = 0; cm && ta != UINT32_MAX && v < cm->vertex_count; ++v) {
    float x = cm->attributes[(size_t)v * cm->attribute_count + ta][0];
    lo = fminf(lo, x), hi = fmaxf(hi, x);
  }
  bool ok = cm && ta != UINT32_MAX;
  tlod_cpu_mesh_destroy(ctx, cm);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  CHECK_MSG(ok && lo == t->min[0] && hi == t->max[0], "tessellated temperature %.9g..%.9g, field %.9g..%.9g", lo, hi,
            t->min[0], t->max[0]);
  tlod_import_free(r);
  vtk_model_free(&m);
}

/* Binary data is data: a legacy binary field whose bytes spell a POINTS header (an importer of
 * a4669f9 refused the file: "POINTS: declares 999999999999 x 3 values, more than the 38 bytes left"). */
TEST(test_binary_payload_is_data) {
  vtk_model m;
  vtk_build_payload_box(&m);
  tlod_import_result* r = vtk_test_write_import(&m, work, "payload.vtk", VTK_LEGACY_BINARY);
  CHECK_MSG(r, "a valid file refused (see above)");
  const tlod_import_field* f = field_named(r, "payload");
  bool ok = f && r->vtk && r->vtk->boundary_quads == 6 && r->vertex_count == 8;
  for (uint32_t v = 0; ok && v < r->vertex_count; ++v) {
    uint32_t q = model_point(&m, r->positions + 3 * (size_t)v);
    ok = q != UINT32_MAX && f->data[v] == (float)m.fields[0].data[q];
  }
  tlod_import_free(r);
  vtk_model_free(&m);
  CHECK_MSG(ok, "payload field or boundary not as written");
}

/* ---- tet sphere ---- */

TEST(test_tet_sphere) {
  vtk_model m;
  vtk_build_tet_sphere(&m, 3, 1.0);
  tlod_import_result* r = vtk_test_write_import(&m, work, "sphere.vtk", VTK_LEGACY_BINARY);
  CHECK(r);
  /* one tet per surface triangle; its three faces through the centre are shared with neighbours */
  expect e = {1280, 1280, 0, 1280 * 3 / 2, m.inverted};
  CALL(check_counts(r, &e, "sphere.vtk"));
  const double A = 4 * M_PI, V = 4 * M_PI / 3;
  measured flat = measure(r, TLOD_SURFACE_FLAT, 0, 0), phong = measure(r, TLOD_SURFACE_PHONG, 3, 0);
  tlod_import_free(r);
  vtk_model_free(&m);
  printf("  sphere r = 1: flat area %.6f volume %.6f, Phong level 3 area %.6f volume %.6f (4 pi = %.6f, 4/3 pi = "
         "%.6f)\n",
         flat.area, flat.volume, phong.area, phong.volume, A, V);
  CHECK_MSG(flat.closed && phong.closed, "flat closed %d, Phong closed %d", flat.closed, phong.closed);
  CHECK_MSG(fabs(flat.area - A) < 0.02 * A && fabs(flat.volume - V) < 0.02 * V, "flat: area %.6f volume %.6f",
            flat.area, flat.volume);
  CHECK_MSG(fabs(phong.area - A) < fabs(flat.area - A) && fabs(phong.volume - V) < fabs(flat.volume - V),
            "Phong no closer to the sphere than flat: area %.6f volume %.6f", phong.area, phong.volume);
}

/* ---- mixed ---- */

TEST(test_mixed) {
  vtk_model m;
  vtk_build_mixed(&m);
  tlod_import_result* r = vtk_test_write_import(&m, work, "mixed.vtu", VTK_XML_ASCII);
  CHECK(r);
  /* 91 cell faces, 25 on the boundary of [0,4]x[0,1]x[0,1] */
  expect e = {20, 14, 11, 33, 0};
  CALL(check_counts(r, &e, "mixed.vtu"));
  const tlod_import_vtk_info* v = r->vtk;
  CHECK_MSG(cells_of(v, VTK_HEXAHEDRON) == 1 && cells_of(v, VTK_WEDGE) == 2 && cells_of(v, VTK_PYRAMID) == 7 &&
                cells_of(v, VTK_TETRA) == 10,
            "cells by type: hex %llu wedge %llu pyramid %llu tet %llu", (unsigned long long)cells_of(v, 12),
            (unsigned long long)cells_of(v, 13), (unsigned long long)cells_of(v, 14),
            (unsigned long long)cells_of(v, 10));
  measured f = measure(r, TLOD_SURFACE_FLAT, 2, 0);
  tlod_import_free(r);
  vtk_model_free(&m);
  CHECK_MSG(f.closed && f.info.closed, "not closed");
  CHECK_MSG(fabs(f.area - 18) <= 1e-5 * 18 && fabs(f.volume - 4) <= 1e-5 * 4, "area %.9g (18), volume %.9g (4)", f.area,
            f.volume);
}

/* ---- hex cylinder: Phong quads against the true cylinder ---- */

typedef struct cyl_error {
  double side_max, side_rms, cap_max;
  uint32_t side_patches;
} cyl_error;

/* Samples every patch on a 9x9 grid: side patches (corners on the circle) by | |xy| - R |, cap
 * patches (corners at z = 0 or H) by |z - cap|. */
static cyl_error cylinder_error(const tlod_surface* s, double R, double H) {
  cyl_error e = {0};
  const tlod_mesh* mesh = tlod_surface_mesh(s);
  double sum = 0;
  uint32_t n = 0;
  for (uint32_t p = 0; p < tlod_surface_patch_count(s); ++p) {
    uint32_t c[4], nc = tlod_mesh_face_corners(mesh, p, c);
    bool side = nc == 4, cap0 = true, cap1 = true;
    for (uint32_t k = 0; k < nc; ++k) {
      float q[3], nn[3];
      tlod_mesh_vertex(mesh, c[k], q, nn);
      side = side && fabs(hypot(q[0], q[1]) - R) < 1e-5;
      cap0 = cap0 && q[2] == 0.0f, cap1 = cap1 && q[2] == (float)H;
    }
    e.side_patches += side;
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        tlod_surface_point pt;
        if (tlod_surface_eval(s, p, i / 8.0f, j / 8.0f, &pt) != TLOD_SUCCESS) continue;
        if (side) {
          double d = fabs(hypot(pt.position[0], pt.position[1]) - R);
          e.side_max = fmax(e.side_max, d), sum += d * d, n++;
        } else if (cap0 || cap1) {
          e.cap_max = fmax(e.cap_max, fabs(pt.position[2] - (cap1 ? H : 0)));
        }
      }
  }
  e.side_rms = n ? sqrt(sum / n) : 0;
  return e;
}

TEST(test_hex_cylinder_phong) {
  const double R = 1, H = 2;
  vtk_model m;
  vtk_build_hex_cylinder(&m, R, H, 2);
  tlod_import_result* r = vtk_test_write_import(&m, work, "cylinder.vtu", VTK_XML_ASCII);
  vtk_model_free(&m);
  CHECK(r);
  /* 2 layers of 21 cells: 12 x 2 side quads, 21 per cap; inner faces: (42 * 6 - 66) / 2 */
  expect e = {42, 0, 66, 93, 0};
  CALL(check_counts(r, &e, "cylinder.vtu"));
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS);
  /* 45 degrees: the 30 degree turns around the side stay smooth, the 90 degree rims are creases */
  tlod_mesh* mesh = vtk_test_mesh(ctx, r, 45, 0);
  tlod_surface* flat = mesh ? vtk_test_surface(ctx, mesh, TLOD_SURFACE_FLAT) : NULL;
  tlod_surface* phong = mesh ? vtk_test_surface(ctx, mesh, TLOD_SURFACE_PHONG) : NULL;
  cyl_error ef = {0}, ep = {0};
  if (flat && phong) ef = cylinder_error(flat, R, H), ep = cylinder_error(phong, R, H);
  tlod_surface_destroy(flat);
  tlod_surface_destroy(phong);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  tlod_import_free(r);
  printf("  hex cylinder (12 around): distance to the cylinder max / rms: flat %.5f / %.5f, Phong %.5f / %.5f; "
         "caps off their plane by %.3g (Phong)\n",
         ef.side_max, ef.side_rms, ep.side_max, ep.side_rms, ep.cap_max);
  CHECK_MSG(ep.side_patches == 24 && ef.side_patches == 24, "%u side patches (24)", ep.side_patches);
  /* flat: R (1 - cos 15 deg) = 0.0341 at the middle of each quad */
  CHECK_MSG(fabs(ef.side_max - R * (1 - cos(M_PI / 12))) < 1e-5, "flat max %.6f", ef.side_max);
  CHECK_MSG(ep.side_max < 0.6 * ef.side_max && ep.side_rms < 0.6 * ef.side_rms,
            "Phong quads not closer: max %.5f rms "
            "%.5f",
            ep.side_max, ep.side_rms);
  CHECK_MSG(ep.cap_max <= 1e-6, "Phong caps bent by %.3g (the rim is a crease)", ep.cap_max);
}

int main(int argc, char** argv) {
  if (argc > 1) work = argv[1];
  RUN(test_box_all_formats);
  RUN(test_box_fields);
  RUN(test_binary_payload_is_data);
  RUN(test_tet_sphere);
  RUN(test_mixed);
  RUN(test_hex_cylinder_phong);
  TEST_END();
}
