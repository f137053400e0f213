/* export_api_test.c -- tlod_export_file() attributes and tlod_export_scene_file() on hand-made scenes:
 * what each format writes (read back as text or bytes here, not through the importer), glTF names and
 * renormalised tangents, JSON escaping of file-given names, refusals naming the element, and the OBJ merge
 * of instances (mirroring nodes keep front faces). Scratch files go to the working directory. */
#include <stdint.h>

#include "test.h"
#include "tlod_import.h"

static char g_err[512];

/* One triangle: positions, normals; attributes given per test. */
static const float k_pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const float k_nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
static const uint32_t k_idx[3] = {0, 1, 2};

static tlod_export_mesh triangle(const tlod_export_attribute* a, uint32_t count) {
  return (tlod_export_mesh){3, k_pos, k_nrm, 1, k_idx, count, a};
}

TEST(obj_writes_vt_flipped_from_strided_uvs) {
  /* vec4 rows as the cpu tessellator gives them: uv in the first two floats */
  const float rows[12] = {0.25f, 0.125f, 9, 9, 1, 0, 9, 9, 0, 1, 9, 9};
  const tlod_export_attribute uv = {"TEXCOORD_0", 2, rows, 16};
  tlod_export_mesh m = triangle(&uv, 1);
  CHECK(tlod_export_file("attr.obj", &m, g_err, sizeof g_err) == TLOD_SUCCESS);
  char* s = test_read_file("attr.obj", NULL);
  CHECK_MSG(s && strstr(s, "vt 0.25 0.875\nvt 1 1\nvt 0 0\n"), "%s", s ? s : "(none)");
  CHECK(s && strstr(s, "f 1/1/1 2/2/2 3/3/3\n"));
  free(s);
}

TEST(ply_writes_uv_and_rgba) {
  const float uv[6] = {0, 0.25f, 1, 0, 0, 1};
  const float rgb[9] = {1, 0, 0, 0, 0.5f, 0, 0, 0, 2};
  const tlod_export_attribute a[2] = {{"COLOR_0", 3, rgb, 0}, {"TEXCOORD_0", 2, uv, 0}};
  tlod_export_mesh m = triangle(a, 2);
  CHECK(tlod_export_file("attr.ply", &m, g_err, sizeof g_err) == TLOD_SUCCESS);
  size_t n = 0;
  char* s = test_read_file("attr.ply", &n);
  char* body = s ? strstr(s, "end_header\n") : NULL;
  CHECK(s && strstr(s, "property float u\nproperty float v\nproperty uchar red\nproperty uchar green\n"
                       "property uchar blue\nproperty uchar alpha\n"));
  if (!body) return;
  body += strlen("end_header\n");
  float v0[8];
  memcpy(v0, body, sizeof v0); /* x y z nx ny nz u v of vertex 0 */
  CHECK(v0[6] == 0.0f && v0[7] == 0.25f);
  const unsigned char* c1 = (const unsigned char*)body + 36 + 32; /* vertex 1's colour */
  CHECK_MSG(c1[0] == 0 && c1[1] == 128 && c1[2] == 0 && c1[3] == 255, "%u %u %u %u", c1[0], c1[1], c1[2], c1[3]);
  const unsigned char* c2 = (const unsigned char*)body + 2 * 36 + 32;
  CHECK(c2[2] == 255); /* 2.0 clamped */
  free(s);
}

TEST(gltf_names_attributes_and_renormalises_tangents) {
  const float temp[3] = {1, 2, 3};
  const float uvw[9] = {0};
  const float tan[12] = {2, 0, 0, 0.5f, 0, 3, 0, -0.2f, 0, 0, 1, 1};
  const tlod_export_attribute a[4] = {
      {"temperature", 1, temp, 0}, {"TEXCOORD_0", 3, uvw, 0}, {"TANGENT", 4, tan, 0}, {NULL, 1, temp, 0}};
  tlod_export_mesh m = triangle(a, 4);
  CHECK(tlod_export_file("attr.glb", &m, g_err, sizeof g_err) == TLOD_SUCCESS);
  size_t n = 0;
  char* s = test_read_file("attr.glb", &n);
  CHECK(s && strstr(s + 20, "\"_temperature\":2") && strstr(s + 20, "\"_TEXCOORD_0\":3") &&
        strstr(s + 20, "\"TANGENT\":4") && strstr(s + 20, "\"_ATTRIBUTE_3\":5"));
  if (!s) return;
  uint32_t json = 0;
  memcpy(&json, s + 12, 4);
  /* BIN: positions 36, normals 36, temperature 12, uvw 36, then the tangents */
  float t[12];
  memcpy(t, s + 20 + json + 8 + 36 + 36 + 12 + 36, sizeof t);
  CHECK(t[0] == 1 && t[3] == 1 && t[5] == 1 && t[7] == -1 && t[10] == 1 && t[11] == 1);
  free(s);
}

TEST(non_finite_attribute_refused_naming_it) {
  const float uv[6] = {0, 0, NAN, 0, 0, 1};
  const tlod_export_attribute a = {"TEXCOORD_0", 2, uv, 0};
  tlod_export_mesh m = triangle(&a, 1);
  CHECK(tlod_export_file("bad.gltf", &m, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(g_err, "bad.gltf: mesh: attribute 0: vertex 1 is not finite"), "%s", g_err);
  const tlod_export_attribute five = {"X", 5, uv, 0};
  m = triangle(&five, 1);
  CHECK(tlod_export_file("bad.gltf", &m, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
}

/* A source of one mesh (two parts) at two nodes: root (with a quote and a cut UTF-8 character in its
 * name) and a mirrored child. */
typedef struct fixture {
  tlod_import_result r;
  tlod_import_part parts[2];
  tlod_import_mesh mesh;
  tlod_import_node nodes[2];
  tlod_import_material material;
  tlod_export_mesh out[2]; /* the parts as written: one triangle each */
} fixture;

static void node_at(tlod_import_node* n, const char* name, uint32_t parent, float sx) {
  memset(n, 0, sizeof *n);
  snprintf(n->name, sizeof n->name, "%s", name);
  n->parent = parent, n->mesh = 0, n->skin = TLOD_IMPORT_NONE;
  n->rotation[3] = 1, n->scale[0] = sx, n->scale[1] = n->scale[2] = 1;
  n->local[0] = n->world[0] = sx;
  n->local[5] = n->local[10] = n->local[15] = n->world[5] = n->world[10] = n->world[15] = 1;
}

static void fixture_init(fixture* f) {
  memset(f, 0, sizeof *f);
  for (int p = 0; p < 2; ++p)
    f->parts[p] = (tlod_import_part){.mesh = 0, .material = p ? TLOD_IMPORT_NONE : 0, .node = TLOD_IMPORT_NONE};
  f->mesh = (tlod_import_mesh){"tri", 0, 2};
  node_at(&f->nodes[0], "a\"b\xC3", TLOD_IMPORT_NONE, 1);
  node_at(&f->nodes[1], "mirror", 0, -1);
  f->material = (tlod_import_material){
      "m", {1, 0.5f, 0, 1}, TLOD_IMPORT_NONE, TLOD_IMPORT_NONE, TLOD_IMPORT_ALPHA_BLEND, 0.5f, true, 0.0f, 1.0f};
  f->r.part_count = 2, f->r.parts = f->parts, f->r.mesh_count = 1, f->r.meshes = &f->mesh;
  f->r.node_count = 2, f->r.nodes = f->nodes, f->r.material_count = 1, f->r.materials = &f->material;
  f->out[0] = f->out[1] = triangle(NULL, 0);
}

TEST(scene_gltf_keeps_nodes_escapes_names) {
  fixture f;
  fixture_init(&f);
  const tlod_export_mesh* parts = f.out;
  CHECK(tlod_export_scene_file("scene.gltf", &f.r, parts, g_err, sizeof g_err) == TLOD_SUCCESS);
  char* s = test_read_file("scene.gltf", NULL);
  CHECK_MSG(s && strstr(s, "\"nodes\":[{\"name\":\"a\\\"b?\",\"children\":[1],\"mesh\":0},"
                           "{\"name\":\"mirror\",\"mesh\":0,\"scale\":[-1,1,1]}]"),
            "%.400s", s ? s : "");
  CHECK(s && strstr(s, "\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,\"mode\":4,"
                       "\"material\":0},{\"attributes\":{\"POSITION\":3,\"NORMAL\":4},\"indices\":5,\"mode\":4}]"));
  CHECK(s && strstr(s, "\"alphaMode\":\"BLEND\",\"doubleSided\":true") && !strstr(s, "alphaCutoff"));
  free(s);
}

TEST(scene_refusals_name_the_element) {
  fixture f;
  fixture_init(&f);
  const tlod_export_mesh* parts = f.out;
  f.parts[1].material = 7;
  CHECK(tlod_export_scene_file("s.glb", &f.r, parts, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(g_err, "s.glb: part 1: material out of range"), "%s", g_err);
  f.parts[1].material = TLOD_IMPORT_NONE;
  f.parts[0].node = 1; /* flattened (world-space) parts cannot be instanced again */
  CHECK(tlod_export_scene_file("s.glb", &f.r, parts, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(g_err, "keep_scene"), "%s", g_err);
  f.parts[0].node = TLOD_IMPORT_NONE;
  f.nodes[1].mesh = 3;
  CHECK(tlod_export_scene_file("s.obj", &f.r, parts, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(g_err, "node 1: mesh 3 out of range"), "%s", g_err);
}

TEST(scene_obj_merges_instances_mirrored_front_facing) {
  fixture f;
  fixture_init(&f);
  const tlod_export_mesh* parts = f.out;
  CHECK(tlod_export_scene_file("scene.obj", &f.r, parts, g_err, sizeof g_err) == TLOD_SUCCESS);
  char* s = test_read_file("scene.obj", NULL);
  /* 2 nodes x 2 parts: 12 vertices; the mirrored ones at x = -1 with winding reversed, normals still +z */
  CHECK(s && strstr(s, "# tesslod export: 12 vertices, 4 triangles"));
  CHECK(s && strstr(s, "v -1 0 0\n") && strstr(s, "f 7//7 9//9 8//8\n") && !strstr(s, "vn 0 0 -1"));
  free(s);
}

/* What the importer reads back: the exporter's flips and its are inverses
 * (uvs chosen so 1 - (1 - v) is exact). */
TEST(obj_and_ply_uvs_read_back_through_the_importer) {
  const float uv[6] = {0.25f, 0.125f, 1, 0, 0.5f, 1};
  const tlod_export_attribute a = {"TEXCOORD_0", 2, uv, 0};
  tlod_export_mesh m = triangle(&a, 1);
  const char* const files[2] = {"rt.obj", "rt.ply"};
  for (int f = 0; f < 2; ++f) {
    tlod_import_result* r = NULL;
    CHECK(tlod_export_file(files[f], &m, g_err, sizeof g_err) == TLOD_SUCCESS);
    CHECK_MSG(tlod_import_file(files[f], NULL, &r, g_err, sizeof g_err) == TLOD_SUCCESS, "%s", g_err);
    if (!r) continue;
    CHECK_MSG(r->attribute_count >= 1 && !strcmp(r->attributes[0].name, "TEXCOORD_0") && r->vertex_count == 3 &&
                  !memcmp(r->attributes[0].data, uv, sizeof uv),
              "%s: %u attributes", files[f], r->attribute_count);
    tlod_import_free(r);
  }
}

int main(void) {
  RUN(obj_and_ply_uvs_read_back_through_the_importer);
  RUN(obj_writes_vt_flipped_from_strided_uvs);
  RUN(ply_writes_uv_and_rgba);
  RUN(gltf_names_attributes_and_renormalises_tangents);
  RUN(non_finite_attribute_refused_naming_it);
  RUN(scene_gltf_keeps_nodes_escapes_names);
  RUN(scene_refusals_name_the_element);
  RUN(scene_obj_merges_instances_mirrored_front_facing);
  TEST_END();
}
