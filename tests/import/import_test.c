/* import_test.c -- tlod_import_file() / tlod_export_file() on the shared corpus and hostile input.
 * Owned by the import/export layer. Scratch files go to the working folder
 * (ctest runs this in the build tree). Meant to run under ASan: the sweeps
 * check "no crash, no out-of-bounds read", the rest checks results. */
#define _POSIX_C_SOURCE 200809L /* dirent, unlink */

#include <dirent.h>
#include <stdint.h>
#include <unistd.h>

#include "test.h"
#include "tlod_import.h"

/* ------------------------------------------------------------------------ */
/* Helpers                                                                  */
/* ------------------------------------------------------------------------ */

static const char* data_path(const char* rel) {
  static char buf[4][1024];
  static int slot;
  char* p = buf[slot++ % 4];
  snprintf(p, 1024, "%s/%s", TLOD_TEST_DATA_DIR, rel);
  return p;
}

static const char* base_name(const char* path) {
  const char* s = strrchr(path, '/');
  return s ? s + 1 : path;
}

static char g_err[1024];

/* Imports a file below tests/data (NULL allocator). */
static tlod_result load(const char* rel, tlod_import_result** r) {
  return tlod_import_file(data_path(rel), NULL, r, g_err, sizeof g_err);
}

static unsigned char* read_all(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  unsigned char* d = NULL;
  size_t cap = 0, n = 0, got;
  do {
    if (n == cap) {
      cap = cap ? cap * 2 : 65536;
      unsigned char* q = realloc(d, cap);
      if (!q) break;
      d = q;
    }
    got = fread(d + n, 1, cap - n, f);
    n += got;
  } while (got > 0);
  fclose(f);
  *size = n;
  return d;
}

static int write_all(const char* path, const void* data, size_t size) {
  FILE* f = fopen(path, "wb");
  if (!f) return 0;
  int ok = fwrite(data, 1, size, f) == size;
  return fclose(f) == 0 && ok;
}

static int file_exists(const char* path) {
  FILE* f = fopen(path, "rb");
  if (f) fclose(f);
  return f != NULL;
}

/* Imports path: "loaded or failed cleanly"; a failure must carry a message
 * naming the file, a success must have in-range indices. */
static int clean_outcome(const char* path) {
  tlod_import_result* r = NULL;
  const tlod_result res = tlod_import_file(path, NULL, &r, g_err, sizeof g_err);
  if (res == TLOD_SUCCESS) {
    int ok = r && r->vertex_count > 0 && r->index_count > 0;
    for (uint32_t i = 0; ok && i < r->index_count; ++i)
      ok = r->indices[i] < r->vertex_count;
    tlod_import_free(r);
    return ok;
  }
  return r == NULL && strstr(g_err, base_name(path)) != NULL;
}

static uint32_t load_u32(const unsigned char* p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void store_u32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8), p[2] = (unsigned char)(v >> 16),
  p[3] = (unsigned char)(v >> 24);
}

static int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  return c == '+' ? 62 : c == '/' ? 63 : -1;
}

/* Decodes the first data-URI buffer of a .gltf text (test oracle). */
static size_t decode_data_uri(const char* text, unsigned char* out, size_t cap) {
  const char* s = strstr(text, "base64,");
  size_t n = 0;
  uint32_t acc = 0;
  int bits = 0;
  for (s = s ? s + 7 : ""; base64_value(*s) >= 0 && n < cap; ++s) {
    acc = acc << 6 | (uint32_t)base64_value(*s);
    bits += 6;
    if (bits >= 8) out[n++] = (unsigned char)(acc >> (bits -= 8));
  }
  return n;
}

static size_t base64_encode(const unsigned char* in, size_t n, char* out) {
  static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  size_t o = 0;
  for (size_t i = 0; i < n; i += 3) {
    uint32_t v = (uint32_t)in[i] << 16 | (uint32_t)(i + 1 < n ? in[i + 1] : 0) << 8 | (i + 2 < n ? in[i + 2] : 0);
    out[o++] = a[v >> 18 & 63], out[o++] = a[v >> 12 & 63];
    out[o++] = i + 1 < n ? a[v >> 6 & 63] : '=';
    out[o++] = i + 2 < n ? a[v & 63] : '=';
  }
  out[o] = 0;
  return o;
}

static float f32_at(const unsigned char* p) {
  uint32_t u = load_u32(p);
  float f;
  memcpy(&f, &u, 4);
  return f;
}

static int same_bits(const void* a, const void* b, size_t n) {
  return (a == NULL) == (b == NULL) && (!a || !memcmp(a, b, n));
}

/* ------------------------------------------------------------------------ */
/* Valid glTF                                                               */
/* ------------------------------------------------------------------------ */

/* Box.gltf: its parent node turns Y-up into Z-up, (x, y, z) -> (x, z, -y);
 * compared against the raw buffer decoded here. */
TEST(box_gltf) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("glTF-Sample-Models/Box/Box.gltf", &r) == TLOD_SUCCESS, "%s", g_err);
  CHECK(r->vertex_count == 24 && r->index_count == 36 && r->face_count == 12);
  CHECK(r->face_sizes == NULL && r->normals != NULL && r->part_count == 1);
  CHECK(r->parts[0].had_normals && r->parts[0].face_count == 12 && r->parts[0].vertex_count == 24);
  CHECK_NEAR(r->parts[0].base_color[0], 0.8, 1e-6);
  CHECK(r->parts[0].base_color[1] == 0.0f && r->parts[0].base_color[3] == 1.0f);
  size_t size = 0;
  unsigned char* text = read_all(data_path("glTF-Sample-Models/Box/Box.gltf"), &size);
  CHECK(text);
  unsigned char* buf = malloc(1024);
  text = realloc(text, size + 1);
  text[size] = 0;
  size_t n = decode_data_uri((const char*)text, buf, 1024);
  free(text);
  int ok = n == 648;
  for (uint32_t i = 0; ok && i < 24; ++i) {
    const float x = f32_at(buf + 288 + 12 * i), y = f32_at(buf + 292 + 12 * i), z = f32_at(buf + 296 + 12 * i);
    const float nx = f32_at(buf + 12 * i), ny = f32_at(buf + 4 + 12 * i), nz = f32_at(buf + 8 + 12 * i);
    const float* p = r->positions + 3 * i;
    const float* q = r->normals + 3 * i;
    ok = p[0] == x && p[1] == z && p[2] == -y && q[0] == nx && q[1] == nz && q[2] == -ny;
    if (!ok) fprintf(stderr, "vertex %u: (%g %g %g) from (%g %g %g)\n", i, p[0], p[1], p[2], x, y, z);
  }
  free(buf);
  /* Spot check one known corner: (-0.5, -0.5, 0.5) stored first -> (-0.5, 0.5, 0.5). */
  CHECK(r->positions[0] == -0.5f && r->positions[1] == 0.5f && r->positions[2] == 0.5f);
  tlod_import_free(r);
  CHECK_MSG(ok, "transformed positions/normals differ from the raw buffer");
}

static int same_mesh(const tlod_import_result* a, const tlod_import_result* b) {
  return a->vertex_count == b->vertex_count && a->index_count == b->index_count &&
         same_bits(a->positions, b->positions, (size_t)a->vertex_count * 12) &&
         same_bits(a->normals, b->normals, (size_t)a->vertex_count * 12) &&
         same_bits(a->indices, b->indices, (size_t)a->index_count * 4);
}

TEST(box_interleaved_glb_matches_box_gltf) {
  tlod_import_result *a = NULL, *b = NULL;
  CHECK_MSG(load("glTF-Sample-Models/Box/Box.gltf", &a) == TLOD_SUCCESS, "%s", g_err);
  tlod_result res = load("glTF-Sample-Models/BoxInterleaved/BoxInterleaved.glb", &b);
  int same = res == TLOD_SUCCESS && same_mesh(a, b);
  tlod_import_free(a);
  tlod_import_free(b);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  CHECK(same);
}

TEST(duck_glb_matches_duck_gltf) {
  tlod_import_result *a = NULL, *b = NULL;
  CHECK_MSG(load("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb", &a) == TLOD_SUCCESS, "%s", g_err);
  tlod_result res = load("glTF-Sample-Models/Duck/glTF/Duck.gltf", &b);
  int same = res == TLOD_SUCCESS && same_mesh(a, b);
  float hi[3] = {-1e30f, -1e30f, -1e30f}, lo[3] = {1e30f, 1e30f, 1e30f};
  for (uint32_t i = 0; i < a->vertex_count; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = a->positions[3 * i + (uint32_t)c];
      hi[c] = v > hi[c] ? v : hi[c];
      lo[c] = v < lo[c] ? v : lo[c];
    }
  const uint32_t verts = a->vertex_count, tris = a->face_count;
  const int has_normals = a->normals != NULL;
  tlod_import_free(a);
  tlod_import_free(b);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  CHECK(same);
  CHECK(verts == 2399 && tris == 4212 && has_normals);
  /* Raw POSITION max x 96.1799, min y 9.92937: the root node scales by 0.01. */
  CHECK_NEAR(hi[0], 0.961799, 1e-5);
  CHECK_NEAR(lo[1], 0.0992937, 1e-5);
}

TEST(sparse_accessor_substituted) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("glTF-Sample-Models/SimpleSparseAccessor/SimpleSparseAccessor.gltf", &r) == TLOD_SUCCESS, "%s", g_err);
  const float expect[3][4] = {{8, 1, 2, 0}, {10, 3, 3, 0}, {12, 5, 4, 0}}; /* index, x y z */
  int ok = r->vertex_count == 14 && r->face_count == 12 && r->normals == NULL;
  for (int i = 0; ok && i < 3; ++i) {
    const float* p = r->positions + 3 * (int)expect[i][0];
    ok = p[0] == expect[i][1] && p[1] == expect[i][2] && p[2] == expect[i][3];
  }
  /* An untouched neighbour keeps its dense value (vertex 9 = (2, 1, 0)). */
  ok = ok && r->positions[27] == 2.0f && r->positions[28] == 1.0f;
  tlod_import_free(r);
  CHECK(ok);
}

TEST(skinned_mesh_bind_pose) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("glTF-Sample-Models/SimpleSkin/SimpleSkin.gltf", &r) == TLOD_SUCCESS, "%s", g_err);
  int ok = r->vertex_count == 10 && r->face_count == 8 && r->normals == NULL && strstr(r->warnings, "skinned");
  tlod_import_free(r);
  CHECK(ok);
}

/* Signed area of triangle t in the z = 0 plane (positive: counter-clockwise). */
static float area_z(const tlod_import_result* r, uint32_t t) {
  const float* a = r->positions + 3 * r->indices[3 * t];
  const float* b = r->positions + 3 * r->indices[3 * t + 1];
  const float* c = r->positions + 3 * r->indices[3 * t + 2];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

TEST(primitive_modes) {
  static const struct {
    const char* nn;
    uint32_t converted;
  } cases[] = {{"04", 1}, {"05", 1}, {"06", 0}, {"11", 1}, {"12", 1}, {"14", 0}, {"15", 0}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char rel[128];
    snprintf(rel, sizeof rel, "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_%s.gltf", cases[i].nn);
    tlod_import_result* r = NULL;
    CHECK_MSG(load(rel, &r) == TLOD_SUCCESS, "%s: %s", cases[i].nn, g_err);
    const int ok = r->face_count == 2 && r->index_count == 6 && r->strips_fans_converted == cases[i].converted &&
                   area_z(r, 0) > 0 && area_z(r, 1) > 0 && fabsf(area_z(r, 0)) + fabsf(area_z(r, 1)) == 2.0f;
    tlod_import_free(r);
    CHECK_MSG(ok, "mode file %s: faces or winding wrong", cases[i].nn);
  }
}

TEST(lines_rejected) {
  tlod_import_result* r = NULL;
  tlod_result res = load("glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf", &r);
  CHECK(res != TLOD_SUCCESS && r == NULL);
  CHECK_MSG(strstr(g_err, "LINES") && strstr(g_err, "Mesh_PrimitiveMode_01.gltf"), "%s", g_err);
}

/* ------------------------------------------------------------------------ */
/* Hand-made glTF: transforms, winding, mixed modes                         */
/* ------------------------------------------------------------------------ */

/* One triangle (0,0,0) (1,0,0) (0,1,0) with u16 indices, written as a
 * .gltf with the caller's nodes and extra primitives, then imported. */
static tlod_result load_triangle_gltf(const char* nodes, const char* extra_prims, tlod_import_result** r) {
  unsigned char bin[48] = {0};
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  memcpy(bin, pos, 36);     /* little-endian host (x86-64), as glTF */
  bin[38] = 1, bin[40] = 2; /* u16 indices 0 1 2 */
  char b64[128];
  base64_encode(bin, 44, b64);
  char* json = malloc(8192);
  snprintf(json, 8192,
           "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":%s,"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}%s]}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
           "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
           "\"buffers\":[{\"byteLength\":44,\"uri\":\"data:application/octet-stream;base64,%s\"}]}",
           nodes, extra_prims, b64);
  const int written = write_all("triangle.gltf", json, strlen(json));
  free(json);
  if (!written) return TLOD_ERROR_IO;
  return tlod_import_file("triangle.gltf", NULL, r, g_err, sizeof g_err);
}

TEST(trs_transform) {
  tlod_import_result* r = NULL;
  /* Parent translates (1,2,3); child rotates 90 degrees about z and scales by 2:
   * (1,0,0) -> S (2,0,0) -> R (0,2,0) -> T (1,4,3). */
  tlod_result res =
      load_triangle_gltf("[{\"translation\":[1,2,3],\"children\":[1]},"
                         "{\"mesh\":0,\"rotation\":[0,0,0.70710678118654752,0.70710678118654752],\"scale\":[2,2,2]}]",
                         "", &r);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  const float* p = r->positions;
  const float got[6] = {p[0], p[1], p[2], p[3], p[4], p[5]};
  const uint32_t i1 = r->indices[1];
  tlod_import_free(r);
  CHECK(got[0] == 1.0f && got[1] == 2.0f && got[2] == 3.0f);
  CHECK_NEAR(got[3], 1.0, 1e-6);
  CHECK_NEAR(got[4], 4.0, 1e-6);
  CHECK_NEAR(got[5], 3.0, 1e-6);
  CHECK(i1 == 1); /* positive determinant: winding kept */
}

TEST(mirror_flips_winding) {
  tlod_import_result* r = NULL;
  tlod_result res = load_triangle_gltf("[{\"mesh\":0,\"scale\":[-1,1,1]}]", "", &r);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  const int ok =
      r->positions[3] == -1.0f && r->indices[0] == 0 && r->indices[1] == 2 && r->indices[2] == 1 && area_z(r, 0) > 0;
  tlod_import_free(r);
  CHECK_MSG(ok, "mirrored triangle must stay counter-clockwise");
}

TEST(lines_next_to_triangles_warn) {
  tlod_import_result* r = NULL;
  tlod_result res = load_triangle_gltf("[{\"mesh\":0}]",
                                       ",{\"attributes\":{\"POSITION\":0},\"mode\":1},"
                                       "{\"attributes\":{\"POSITION\":0},\"mode\":3}",
                                       &r);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->face_count == 1 && r->primitives_skipped == 2 && strstr(r->warnings, "LINES") != NULL;
  tlod_import_free(r);
  CHECK(ok);
}

TEST(node_cycle_rejected) {
  tlod_import_result* r = NULL;
  tlod_result res = load_triangle_gltf("[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]", "", &r);
  CHECK(res != TLOD_SUCCESS && r == NULL);
  CHECK_MSG(strstr(g_err, "reached twice"), "%s", g_err);
}

/* nlohmann::json and tinygltf recurse per nesting level: a deep "extras"
 * must be refused, not overflow the stack. */
TEST(deep_json_rejected) {
  const size_t depth = 100000;
  char* json = malloc(2 * depth + 64);
  size_t n = (size_t)sprintf(json, "{\"asset\":{\"version\":\"2.0\",\"extras\":");
  memset(json + n, '[', depth);
  memset(json + n + depth, ']', depth);
  n += 2 * depth;
  n += (size_t)sprintf(json + n, "}}");
  const int written = write_all("deep.gltf", json, n);
  free(json);
  CHECK(written);
  tlod_import_result* r = NULL;
  const tlod_result res = tlod_import_file("deep.gltf", NULL, &r, g_err, sizeof g_err);
  unlink("deep.gltf");
  CHECK(res == TLOD_ERROR_UNSUPPORTED && r == NULL);
  CHECK_MSG(strstr(g_err, "deep.gltf") && strstr(g_err, "nested deeper"), "%s", g_err);
}

/* ------------------------------------------------------------------------ */
/* Broken and edge-case glTF                                                */
/* ------------------------------------------------------------------------ */

/* SOURCES.md section 3: what a loader should do with each validator file.
 * expect: 0 reject, >0 load with that many triangles. */
static const struct {
  const char* file;
  uint32_t triangles;
} validator_cases[] = {
    {"glb/invalid_magic.glb", 0},
    {"glb/invalid_version.glb", 0},
    {"glb/length_mismatch.glb", 0},
    {"glb/chunk_too_big.glb", 0},
    {"glb/truncated_chunk_header.glb", 0},
    {"glb/truncated_chunk_data.glb", 0},
    {"glb/empty_file.glb", 0},
    {"json/invalid_syntax.gltf", 0},
    {"json/bom.gltf", 0}, /* BOM tolerated (warning), but the file has no mesh */
    {"mesh_data/index_buffer_oob.gltf", 0},
    {"mesh_data/index_buffer_degenerate_triangle.gltf", 3},
    {"mesh_data/normals_tangents_non_unit_invalid_sign.gltf", 1},
    {"mesh/primitive_no_position.gltf", 0},
    {"mesh/unresolved_indices.gltf", 0},
    {"mesh/position_accessor_invalid_format.gltf", 0},
    {"mesh/primitive_incompatible_mode.gltf", 1}, /* 4 vertices: last one dropped */
    {"mesh/accessor_unequal_count.gltf", 0},
    {"buffer/not_found.gltf", 0},
    {"buffer/invalid_uri_data_bytelength.gltf", 0},
    {"buffer_view/invalid_length.gltf", 0},
};

TEST(validator_corpus_expectations) {
  for (size_t i = 0; i < sizeof validator_cases / sizeof validator_cases[0]; ++i) {
    char rel[256];
    snprintf(rel, sizeof rel, "glTF-Validator/%s", validator_cases[i].file);
    tlod_import_result* r = NULL;
    tlod_result res = load(rel, &r);
    const uint32_t want = validator_cases[i].triangles;
    if (want == 0) {
      CHECK_MSG(res != TLOD_SUCCESS && r == NULL, "%s loaded but must be rejected", rel);
      CHECK_MSG(strstr(g_err, base_name(rel)) != NULL, "%s: message lacks the file name: %s", rel, g_err);
    } else {
      CHECK_MSG(res == TLOD_SUCCESS, "%s: %s", rel, g_err);
      const int ok = r->face_count == want;
      tlod_import_free(r);
      CHECK_MSG(ok, "%s: wrong triangle count", rel);
    }
  }
}

/* Every file in the folder (also ones added later): no crash, clean outcome. */
static int sweep_folder(const char* rel_dir) {
  char dir[1024];
  snprintf(dir, sizeof dir, "%s", data_path(rel_dir));
  DIR* d = opendir(dir);
  if (!d) return -1;
  int bad = 0;
  for (struct dirent* e; (e = readdir(d)) != NULL;) {
    const char* n = e->d_name;
    const size_t len = strlen(n);
    const int gltf = (len > 5 && !strcmp(n + len - 5, ".gltf")) || (len > 4 && !strcmp(n + len - 4, ".glb"));
    if (!gltf) {
      if (n[0] != '.' && !strchr(n, '.')) { /* a sub-folder */
        char sub[512];
        snprintf(sub, sizeof sub, "%s/%s", rel_dir, n);
        const int b = sweep_folder(sub);
        bad += b > 0 ? b : 0;
      }
      continue;
    }
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, n);
    if (!clean_outcome(path)) {
      fprintf(stderr, "unclean outcome for %s: %s\n", path, g_err);
      bad++;
    }
  }
  closedir(d);
  return bad;
}

TEST(validator_and_assimp_folders_sweep) {
  CHECK(sweep_folder("glTF-Validator") == 0);
  CHECK(sweep_folder("assimp") == 0);
}

TEST(index_buffer_oob_rejected) {
  tlod_import_result* r = NULL;
  CHECK(load("glTF-Validator/mesh_data/index_buffer_oob.gltf", &r) == TLOD_ERROR_INVALID_MESH);
  CHECK_MSG(strstr(g_err, "index_buffer_oob.gltf") && strstr(g_err, "out of range"), "%s", g_err);
}

TEST(degenerate_triangles_load) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("glTF-Validator/mesh_data/index_buffer_degenerate_triangle.gltf", &r) == TLOD_SUCCESS, "%s", g_err);
  int ok = r->face_count == 3 && r->vertex_count == 3;
  for (uint32_t i = 0; ok && i < 9; ++i)
    ok = r->positions[i] == 0.0f; /* no bufferView: zeros */
  tlod_import_free(r);
  CHECK(ok);
}

TEST(infinite_positions_rejected) {
  tlod_import_result* r = NULL;
  CHECK(load("assimp/BoxWithInfinites.glb", &r) == TLOD_ERROR_INVALID_MESH && r == NULL);
  CHECK_MSG(strstr(g_err, "BoxWithInfinites.glb") && strstr(g_err, "POSITION accessor 2") &&
                strstr(g_err, "not finite"),
            "%s", g_err);
}

TEST(bad_normals_pass_through) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("assimp/BoxBadNormals.glb", &r) == TLOD_SUCCESS, "%s", g_err);
  int zeros = 0;
  for (uint32_t i = 0; r->normals && i < r->vertex_count; ++i) {
    const float* n = r->normals + 3 * i;
    zeros += n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f;
  }
  const int ok = r->vertex_count == 24 && r->face_count == 12;
  tlod_import_free(r);
  CHECK(ok);
  CHECK_MSG(zeros == 4, "%d zero normals", zeros);
}

typedef struct counting {
  int allocs, frees;
} counting;

static void* counting_alloc(size_t size, void* user) {
  ((counting*)user)->allocs++;
  return malloc(size);
}

static void counting_free(void* p, void* user) {
  if (p) ((counting*)user)->frees++;
  free(p);
}

TEST(allocator_used_and_balanced) {
  counting c = {0, 0};
  tlod_allocator a = {counting_alloc, counting_free, &c};
  tlod_import_result* r = NULL;
  tlod_result res =
      tlod_import_file(data_path("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb"), &a, &r, g_err, sizeof g_err);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  const int during = c.allocs;
  tlod_import_free(r);
  CHECK(during >= 4 && c.allocs == c.frees);
  tlod_allocator half = {counting_alloc, NULL, &c};
  CHECK(tlod_import_file(data_path("glTF-Sample-Models/Box/Box.gltf"), &half, &r, g_err, sizeof g_err) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_import_file(NULL, NULL, &r, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_import_file(data_path("glTF-Sample-Models/Box/Box.gltf"), NULL, &r, NULL, 0) == TLOD_SUCCESS);
  tlod_import_free(r);
  tlod_import_free(NULL);
}

TEST(unknown_extension_unsupported) {
  tlod_import_result* r = NULL;
  CHECK(load("SOURCES.md", &r) == TLOD_ERROR_UNSUPPORTED && r == NULL);
  CHECK_MSG(strstr(g_err, "SOURCES.md"), "%s", g_err);
}

/* ------------------------------------------------------------------------ */
/* Hostile-input sweeps (run under ASan: any out-of-bounds read aborts)    */
/* ------------------------------------------------------------------------ */

/* Prefixes of a file: every length up to 2 KiB, then every 97th byte. With
 * patch, a GLB header is rewritten to agree with the shorter length, so the
 * prefix gets past the container check into JSON and buffer parsing. */
static int truncation_sweep_file(const char* path, const char* scratch, int patch) {
  const char* rel = path;
  size_t size = 0;
  unsigned char* data = read_all(path, &size);
  if (!data) return -1;
  unsigned char* copy = malloc(size + 1);
  int bad = 0;
  for (size_t len = 0; len < size; len += len < 2048 ? 1 : 97) {
    memcpy(copy, data, len);
    if (patch && len >= 12) store_u32(copy + 8, (uint32_t)len);
    if (patch && len >= 20 && load_u32(copy + 12) > len - 20) store_u32(copy + 12, (uint32_t)(len - 20));
    if (patch && len >= 20 && len >= 28 + (size_t)load_u32(copy + 12)) {
      const uint32_t j = load_u32(copy + 12);
      store_u32(copy + 20 + j, (uint32_t)((len - 28 - j) & ~(size_t)3));
    }
    if (!write_all(scratch, copy, len)) return -1;
    if (!clean_outcome(scratch)) {
      fprintf(stderr, "%s prefix %zu: unclean outcome: %s\n", rel, len, g_err);
      bad++;
    }
  }
  free(copy);
  free(data);
  unlink(scratch);
  return bad;
}

static int truncation_sweep(const char* rel, const char* scratch, int patch) {
  return truncation_sweep_file(data_path(rel), scratch, patch);
}

static int truncation_sweep_path(const char* path, const char* scratch) {
  return truncation_sweep_file(path, scratch, 0);
}

TEST(truncation_sweep_glb) {
  CHECK(truncation_sweep("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb", "trunc.glb", 0) == 0);
  CHECK(truncation_sweep("glTF-Sample-Models/BoxInterleaved/BoxInterleaved.glb", "trunc.glb", 0) == 0);
  CHECK(truncation_sweep("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb", "trunc.glb", 1) == 0);
  CHECK(truncation_sweep("glTF-Sample-Models/BoxInterleaved/BoxInterleaved.glb", "trunc.glb", 1) == 0);
}

TEST(truncation_sweep_text) {
  CHECK(truncation_sweep("glTF-Sample-Models/Box/Box.gltf", "trunc.gltf", 0) == 0);
  CHECK(truncation_sweep("obj/quad_cube.obj", "trunc.obj", 0) == 0);
  CHECK(truncation_sweep("obj/pentagon.obj", "trunc.obj", 0) == 0);
}

static uint32_t lcg(uint32_t* s) {
  *s = *s * 1664525u + 1013904223u;
  return *s >> 8;
}

/* One corrupted copy: byte at pos replaced by value. */
static int try_flip(const unsigned char* data, size_t size, unsigned char* copy, size_t pos, unsigned char value,
                    const char* scratch) {
  memcpy(copy, data, size);
  copy[pos] = value;
  if (!write_all(scratch, copy, size)) return 0;
  if (clean_outcome(scratch)) return 1;
  fprintf(stderr, "byte %zu -> 0x%02x: unclean outcome: %s\n", pos, value, g_err);
  return 0;
}

/* Digits in [begin, end) become '9' and '0' (offsets, counts and indices
 * grow past their buffers or collapse to zero), then random single-byte
 * corruptions anywhere. Deterministic. */
static int flip_sweep(const char* rel, const char* scratch, size_t begin, size_t end, int randoms, size_t skip_begin,
                      size_t skip_end) {
  static const unsigned char values[] = {'9', '0', '-', '"', '{', '}', '[', ']', ',', ':', ' ', 'e', '.', 0, 0xFF};
  size_t size = 0;
  unsigned char* data = read_all(data_path(rel), &size);
  if (!data) return -1;
  unsigned char* copy = malloc(size);
  int bad = 0;
  if (end > size) end = size;
  for (size_t i = begin; i < end; ++i) {
    if (i >= skip_begin && i < skip_end) continue;
    if (data[i] < '0' || data[i] > '9') continue;
    bad += !try_flip(data, size, copy, i, '9', scratch);
    bad += !try_flip(data, size, copy, i, '0', scratch);
  }
  uint32_t seed = 12345;
  for (int k = 0; k < randoms; ++k) {
    const size_t pos = lcg(&seed) % size;
    bad += !try_flip(data, size, copy, pos, values[lcg(&seed) % sizeof values], scratch);
  }
  free(copy);
  free(data);
  unlink(scratch);
  return bad;
}

TEST(byte_flip_sweep_box_gltf) {
  size_t size = 0;
  unsigned char* d = read_all(data_path("glTF-Sample-Models/Box/Box.gltf"), &size);
  CHECK(d);
  d = realloc(d, size + 1);
  d[size] = 0;
  const char* b64 = strstr((const char*)d, "base64,");
  const size_t skip_begin = b64 ? (size_t)(b64 - (const char*)d) : size;
  const char* quote = b64 ? strchr(b64, '"') : NULL;
  const size_t skip_end = quote ? (size_t)(quote - (const char*)d) : size;
  free(d);
  CHECK(flip_sweep("glTF-Sample-Models/Box/Box.gltf", "flip.gltf", 0, size, 400, skip_begin, skip_end) == 0);
}

TEST(byte_flip_sweep_duck_glb) {
  size_t size = 0;
  unsigned char* d = read_all(data_path("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb"), &size);
  CHECK(d && size > 20);
  const size_t json_end = 20 + load_u32(d + 12);
  free(d);
  /* JSON chunk digits (bufferView offsets, accessor counts, node matrices),
   * then random bytes anywhere (header, JSON, BIN: indices out of range). */
  CHECK(flip_sweep("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb", "flip.glb", 20, json_end, 300, 0, 0) == 0);
}

/* ------------------------------------------------------------------------ */
/* OBJ                                                                      */
/* ------------------------------------------------------------------------ */

TEST(obj_quad_cube) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("obj/quad_cube.obj", &r) == TLOD_SUCCESS, "%s", g_err);
  int ok = r->vertex_count == 24 && r->face_count == 6 && r->index_count == 24 && r->face_sizes && r->normals &&
           r->part_count == 1 && !strcmp(r->parts[0].name, "cube") && r->parts[0].had_normals;
  for (uint32_t f = 0; ok && f < r->face_count; ++f)
    ok = r->face_sizes[f] == 4;
  for (uint32_t i = 0; ok && i < r->vertex_count; ++i) {
    const float* n = r->normals + 3 * i;
    ok = fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]) == 1.0f;
  }
  tlod_import_free(r);
  CHECK(ok);
}

TEST(obj_mixed_tri_quad) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("obj/mixed.obj", &r) == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->vertex_count == 8 && r->face_count == 3 && r->index_count == 10 && r->face_sizes &&
                 r->face_sizes[0] == 4 && r->face_sizes[1] == 3 && r->face_sizes[2] == 3 && r->normals == NULL &&
                 r->part_count == 2 && !strcmp(r->parts[0].name, "wall") && !strcmp(r->parts[1].name, "roof") &&
                 r->parts[1].first_face == 1 && r->parts[1].face_count == 2 && r->parts[1].first_vertex == 4;
  /* Relative face "-3 -2 -1" after 6 vertices is (4, 5, 6): in the roof
   * part (sorted v 3 4 5 6 -> ids 4..7) that is 5, 6, 7. */
  const int rel = r->indices[7] == 5 && r->indices[8] == 6 && r->indices[9] == 7;
  tlod_import_free(r);
  CHECK(ok);
  CHECK(rel);
}

TEST(obj_pentagon_fan) {
  tlod_import_result* r = NULL;
  CHECK_MSG(load("obj/pentagon.obj", &r) == TLOD_SUCCESS, "%s", g_err);
  int ok = r->polygons_triangulated == 1 && r->face_count == 4 && r->index_count == 13 && r->face_sizes &&
           r->face_sizes[0] == 3 && r->face_sizes[1] == 3 && r->face_sizes[2] == 3 && r->face_sizes[3] == 4 &&
           r->vertex_count == 9 && r->normals;
  int zero = 0, unit = 0;
  for (uint32_t i = 0; ok && i < r->vertex_count; ++i) {
    const float* n = r->normals + 3 * i;
    zero += n[0] == 0 && n[1] == 0 && n[2] == 0;
    unit += n[2] == 1.0f;
  }
  tlod_import_free(r);
  CHECK(ok);
  CHECK_MSG(zero == 4 && unit == 5, "%d zero and %d unit normals", zero, unit);
}

TEST(obj_broken_files) {
  static const struct {
    const char* file;
    const char* must_contain;
  } cases[] = {
      {"index_out_of_range.obj", "line 4"},
      {"negative_past_start.obj", "line 4"},
      {"nan_coordinate.obj", "line 2"},
      {"overflow_coordinate.obj", "line 2"},
      {"two_corners.obj", "line 4"},
      {"garbage_line.obj", "unknown statement"},
      {"empty.obj", "no faces"},
      {"vn_out_of_range.obj", "line 6: normal index 5"},
      {"zero_index.obj", "line 4"},
      {"number_with_garbage.obj", "line 2"},
      {"does_not_exist.obj", "cannot open"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char rel[256];
    snprintf(rel, sizeof rel, "obj_bad/%s", cases[i].file);
    tlod_import_result* r = NULL;
    const tlod_result res = load(rel, &r);
    CHECK_MSG(res != TLOD_SUCCESS && r == NULL, "%s loaded", rel);
    CHECK_MSG(strstr(g_err, cases[i].file) && strstr(g_err, cases[i].must_contain), "%s: '%s'", rel, g_err);
  }
  tlod_import_result* r = NULL;
  CHECK(load("obj_bad/does_not_exist.obj", &r) == TLOD_ERROR_IO);
}

TEST(obj_byte_flip_sweep) {
  CHECK(flip_sweep("obj/quad_cube.obj", "flip.obj", 0, SIZE_MAX, 300, 0, 0) == 0);
  CHECK(flip_sweep("obj/pentagon.obj", "flip.obj", 0, SIZE_MAX, 300, 0, 0) == 0);
}

/* ------------------------------------------------------------------------ */
/* PLY                                                                      */
/* ------------------------------------------------------------------------ */

TEST(ply_ascii_mixed) {
  const char* text = "ply\nformat ascii 1.0\ncomment extra properties are skipped\nelement vertex 5\n"
                     "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                     "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\nend_header\n"
                     "0 0 0 255\n1 0 0 255\n1 1 0 255\n0 1 0 255\n0.5 2 0 255\n4 0 1 2 3 7\n3 3 2 4 7\n";
  CHECK(write_all("ascii.ply", text, strlen(text)));
  tlod_import_result* r = NULL;
  const tlod_result res = tlod_import_file("ascii.ply", NULL, &r, g_err, sizeof g_err);
  CHECK_MSG(res == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->vertex_count == 5 && r->face_count == 2 && r->index_count == 7 && r->face_sizes &&
                 r->face_sizes[0] == 4 && r->face_sizes[1] == 3 && !r->normals && r->positions[13] == 2.0f &&
                 r->indices[4] == 3 && r->indices[6] == 4;
  tlod_import_free(r);
  CHECK(ok);
  CHECK(truncation_sweep_path("ascii.ply", "trunc.ply") == 0);
  unlink("ascii.ply");
}

/* Big-endian doubles and a pentagon (fan-triangulated). */
static size_t make_be_ply(unsigned char* buf, uint32_t bad_index) {
  size_t n = (size_t)sprintf((char*)buf, "ply\nformat binary_big_endian 1.0\nelement vertex 5\nproperty double x\n"
                                         "property double y\nproperty double z\nelement face 1\n"
                                         "property list ushort uint vertex_indices\nend_header\n");
  const double v[15] = {0, 0, 0, 1, 0, 0, 1.5, 1, 0, 0.5, 2, 0, -0.5, 1, 0};
  for (int i = 0; i < 15; ++i) {
    uint64_t u;
    memcpy(&u, &v[i], 8);
    for (int b = 7; b >= 0; --b)
      buf[n++] = (unsigned char)(u >> (8 * b));
  }
  buf[n++] = 0, buf[n++] = 5;
  for (uint32_t i = 0; i < 5; ++i) {
    const uint32_t x = i == 4 ? bad_index : i;
    buf[n++] = (unsigned char)(x >> 24), buf[n++] = (unsigned char)(x >> 16), buf[n++] = (unsigned char)(x >> 8),
    buf[n++] = (unsigned char)x;
  }
  return n;
}

TEST(ply_big_endian_polygon) {
  unsigned char buf[1024];
  CHECK(write_all("be.ply", buf, make_be_ply(buf, 4)));
  tlod_import_result* r = NULL;
  CHECK_MSG(tlod_import_file("be.ply", NULL, &r, g_err, sizeof g_err) == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->vertex_count == 5 && r->face_count == 3 && r->face_sizes == NULL && r->polygons_triangulated == 1 &&
                 r->positions[6] == 1.5f && r->positions[12] == -0.5f && r->indices[0] == 0 && r->indices[8] == 4;
  tlod_import_free(r);
  CHECK(ok);
  CHECK(truncation_sweep_path("be.ply", "trunc.ply") == 0);
  CHECK(write_all("be.ply", buf, make_be_ply(buf, 9)));
  CHECK(tlod_import_file("be.ply", NULL, &r, g_err, sizeof g_err) == TLOD_ERROR_INVALID_MESH);
  CHECK_MSG(strstr(g_err, "be.ply: face 0: index 9 out of range (5 vertices)"), "%s", g_err);
  unlink("be.ply");
}

/* ------------------------------------------------------------------------ */
/* Export                                                                   */
/* ------------------------------------------------------------------------ */

static int no_temp_files_left(void) {
  DIR* d = opendir(".");
  int clean = 1;
  for (struct dirent* e; d && (e = readdir(d)) != NULL;)
    if (strstr(e->d_name, ".tmp")) clean = 0;
  if (d) closedir(d);
  return clean;
}

/* Export src, import it again: positions, normals and indices bitwise equal. */
static int round_trip(const tlod_import_result* src, const char* out) {
  tlod_export_mesh m = {src->vertex_count, src->positions, src->normals, src->face_count, src->indices, 0, NULL};
  if (tlod_export_file(out, &m, g_err, sizeof g_err) != TLOD_SUCCESS) {
    fprintf(stderr, "export %s: %s\n", out, g_err);
    return 0;
  }
  tlod_import_result* r = NULL;
  if (tlod_import_file(out, NULL, &r, g_err, sizeof g_err) != TLOD_SUCCESS) {
    fprintf(stderr, "re-import %s: %s\n", out, g_err);
    return 0;
  }
  const int ok = same_mesh(src, r) && r->face_sizes == NULL;
  if (!ok) fprintf(stderr, "%s: %u/%u vertices, mesh differs\n", out, r->vertex_count, src->vertex_count);
  tlod_import_free(r);
  unlink(out);
  return ok;
}

TEST(export_round_trip) {
  static const char* const names[] = {"rt.obj", "rt.ply", "rt.gltf", "rt.glb", "RT.GLB"};
  tlod_import_result* duck = NULL;
  tlod_import_result* sparse = NULL;
  CHECK_MSG(load("glTF-Sample-Models/Duck/glTF-Binary/Duck.glb", &duck) == TLOD_SUCCESS, "%s", g_err);
  CHECK_MSG(load("glTF-Sample-Models/SimpleSparseAccessor/SimpleSparseAccessor.gltf", &sparse) == TLOD_SUCCESS, "%s",
            g_err);
  int ok = 1;
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
    ok &= round_trip(duck, names[i]);   /* with normals */
    ok &= round_trip(sparse, names[i]); /* without */
  }
  tlod_import_free(duck);
  tlod_import_free(sparse);
  CHECK(ok);
  CHECK(no_temp_files_left());
}

TEST(export_failures_leave_no_file) {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t good[3] = {0, 1, 2}, bad[3] = {0, 1, 3};
  tlod_export_mesh m = {3, p, NULL, 1, good, 0, NULL};
  CHECK(tlod_export_file("no_such_dir/out.obj", &m, g_err, sizeof g_err) == TLOD_ERROR_IO);
  CHECK_MSG(strstr(g_err, "out.obj"), "%s", g_err);
  CHECK(!file_exists("no_such_dir/out.obj"));
  CHECK(tlod_export_file("out.stl", &m, g_err, sizeof g_err) == TLOD_ERROR_UNSUPPORTED);
  CHECK(!file_exists("out.stl"));
  /* A rejected mesh leaves an existing file as it was. */
  CHECK(write_all("keep.obj", "original\n", 9));
  m.indices = bad;
  CHECK(tlod_export_file("keep.obj", &m, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(g_err, "triangle 0: index 3"), "%s", g_err);
  size_t size = 0;
  unsigned char* d = read_all("keep.obj", &size);
  const int same = d && size == 9 && !memcmp(d, "original\n", 9);
  free(d);
  CHECK(same);
  /* A good export replaces it. */
  m.indices = good;
  CHECK(tlod_export_file("keep.obj", &m, g_err, sizeof g_err) == TLOD_SUCCESS);
  tlod_import_result* r = NULL;
  CHECK(tlod_import_file("keep.obj", NULL, &r, g_err, sizeof g_err) == TLOD_SUCCESS);
  const int tri = r->face_count == 1;
  tlod_import_free(r);
  unlink("keep.obj");
  CHECK(tri);
  CHECK(no_temp_files_left());
}

TEST(export_glb_layout) {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t idx[3] = {0, 1, 2};
  tlod_export_mesh m = {3, p, NULL, 1, idx, 0, NULL};
  CHECK(tlod_export_file("layout.glb", &m, g_err, sizeof g_err) == TLOD_SUCCESS);
  size_t size = 0;
  unsigned char* d = read_all("layout.glb", &size);
  unlink("layout.glb");
  CHECK(d);
  const uint32_t json = load_u32(d + 12), bin = size >= 28 + json ? load_u32(d + 20 + json) : 0;
  const int ok = !memcmp(d, "glTF", 4) && load_u32(d + 4) == 2 && load_u32(d + 8) == size && json % 4 == 0 &&
                 bin % 4 == 0 && 28 + json + bin == size && bin == 48 &&
                 strstr((const char*)d + 20, "\"min\":[0,0,0],\"max\":[1,1,0]") != NULL;
  free(d);
  CHECK(ok);
}

int main(void) {
  RUN(box_gltf);
  RUN(box_interleaved_glb_matches_box_gltf);
  RUN(duck_glb_matches_duck_gltf);
  RUN(sparse_accessor_substituted);
  RUN(skinned_mesh_bind_pose);
  RUN(primitive_modes);
  RUN(lines_rejected);
  RUN(trs_transform);
  RUN(mirror_flips_winding);
  RUN(lines_next_to_triangles_warn);
  RUN(node_cycle_rejected);
  RUN(deep_json_rejected);
  RUN(validator_corpus_expectations);
  RUN(validator_and_assimp_folders_sweep);
  RUN(index_buffer_oob_rejected);
  RUN(degenerate_triangles_load);
  RUN(infinite_positions_rejected);
  RUN(bad_normals_pass_through);
  RUN(allocator_used_and_balanced);
  RUN(unknown_extension_unsupported);
  RUN(truncation_sweep_glb);
  RUN(truncation_sweep_text);
  RUN(byte_flip_sweep_box_gltf);
  RUN(byte_flip_sweep_duck_glb);
  RUN(obj_quad_cube);
  RUN(obj_mixed_tri_quad);
  RUN(obj_pentagon_fan);
  RUN(obj_broken_files);
  RUN(obj_byte_flip_sweep);
  RUN(ply_ascii_mixed);
  RUN(ply_big_endian_polygon);
  RUN(export_round_trip);
  RUN(export_failures_leave_no_file);
  RUN(export_glb_layout);
  unlink("triangle.gltf");
  TEST_END();
}
