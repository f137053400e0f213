/* import_budget_test.c -- tlod_import_desc.memory_limit, tlod_import_memory() and the overflow-checked
 * accessor ranges, through the public API (tlod_import.h). Owned by the import/export layer. */
#include <stdint.h>

#include "test.h"
#include "tlod_import.h"

static char g_err[1024];

/* A glTF whose POSITION accessor has `count` elements without a bufferView
 * (zeros by the glTF rule), so a 400-byte file asks for count x 12 bytes and
 * more; `buffer` is the "buffers" entry. */
static size_t zero_filled_gltf(char* out, size_t size, unsigned count, const char* buffer) {
  return (size_t)snprintf(out, size,
                          "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":"
                          "{\"POSITION\":0}}]}],\"accessors\":[{\"componentType\":5126,\"count\":%u,"
                          "\"type\":\"VEC3\"}],\"buffers\":[%s]}",
                          count, buffer);
}

static tlod_result import_text(const char* name, const char* text, size_t limit, tlod_import_result** r) {
  const tlod_import_desc desc = {.memory_limit = limit};
  return tlod_import_memory(name, text, strlen(text), &desc, r, g_err, sizeof g_err);
}

TEST(default_budget_imports_from_memory) {
  char text[1024];
  zero_filled_gltf(text, sizeof text, 3000,
                   "{\"byteLength\":4,\"uri\":\"data:application/octet-stream;base64,AAAAAA==\"}");
  tlod_import_result* r = NULL;
  CHECK_MSG(import_text("zeros.gltf", text, 0, &r) == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->vertex_count == 3000 && r->face_count == 1000 && r->positions[8999] == 0.0f;
  tlod_import_free(r);
  CHECK(ok);
}

/* The same file under a limit it needs more than: refused, naming the accessor and the field to raise. */
TEST(memory_limit_refuses_naming_the_asker) {
  char text[1024];
  zero_filled_gltf(text, sizeof text, 100000,
                   "{\"byteLength\":4,\"uri\":\"data:application/octet-stream;base64,AAAAAA==\"}");
  tlod_import_result* r = NULL;
  CHECK(import_text("zeros.gltf", text, 1u << 20, &r) == TLOD_ERROR_OUT_OF_MEMORY && r == NULL);
  CHECK_MSG(strstr(g_err, "zeros.gltf: mesh 0 primitive 0: POSITION: accessor 0: needs 1200000 bytes") &&
                strstr(g_err, "memory_limit"),
            "%s", g_err);
  CHECK_MSG(import_text("zeros.gltf", text, 64u << 20, &r) == TLOD_SUCCESS, "%s", g_err);
  const int ok = r->vertex_count == 100000;
  tlod_import_free(r);
  CHECK(ok);
}

/* A limit smaller than the file itself: refused before anything is parsed. */
TEST(memory_limit_smaller_than_the_file) {
  const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  tlod_import_result* r = NULL;
  CHECK(import_text("tri.obj", obj, 16, &r) == TLOD_ERROR_OUT_OF_MEMORY && r == NULL);
  CHECK_MSG(strstr(g_err, "tri.obj: ") == g_err && strstr(g_err, "memory budget"), "%s", g_err);
  CHECK_MSG(import_text("tri.obj", obj, 0, &r) == TLOD_SUCCESS, "%s", g_err);
  tlod_import_free(r);
}

TEST(memory_import_refuses_external_files) {
  char text[1024];
  zero_filled_gltf(text, sizeof text, 3, "{\"byteLength\":36,\"uri\":\"tri.bin\"}");
  tlod_import_result* r = NULL;
  CHECK(import_text("ext.gltf", text, 0, &r) == TLOD_ERROR_IO && r == NULL);
  CHECK_MSG(strstr(g_err, "ext.gltf: buffers[0].uri 'tri.bin': refused"), "%s", g_err);
  CHECK(import_text("ext.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 0, &r) == TLOD_ERROR_IO);
  CHECK_MSG(strstr(g_err, "ext.obj: mtllib 'a.mtl': refused"), "%s", g_err);
}

/* count 2^62 + 1 with stride 16: count x stride wraps to 0 in 64 bits; the
 * range check must see that it does not fit, not that it "fits". */
TEST(accessor_count_overflow_refused) {
  const char* text =
      "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4611686018427387905,\"type\":\"VEC3\"}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteLength\":32,\"byteStride\":16}],"
      "\"buffers\":[{\"byteLength\":32,\"uri\":\"data:application/octet-stream;base64,"
      "AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA=\"}]}";
  tlod_import_result* r = NULL;
  const tlod_result res = import_text("wrap.gltf", text, 0, &r);
  CHECK_MSG(res != TLOD_SUCCESS && r == NULL && strstr(g_err, "wrap.gltf: ") == g_err, "%s", g_err);
}

TEST(null_desc_is_the_default) {
  const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  tlod_import_result* r = NULL;
  CHECK_MSG(tlod_import_memory("tri.obj", obj, strlen(obj), NULL, &r, g_err, sizeof g_err) == TLOD_SUCCESS, "%s",
            g_err);
  const int ok = r->face_count == 1;
  tlod_import_free(r);
  CHECK(ok);
  CHECK(tlod_import_memory("tri.obj", NULL, 5, NULL, &r, g_err, sizeof g_err) == TLOD_ERROR_INVALID_ARGUMENT &&
        r == NULL);
}

int main(void) {
  RUN(default_budget_imports_from_memory);
  RUN(memory_limit_refuses_naming_the_asker);
  RUN(memory_limit_smaller_than_the_file);
  RUN(memory_import_refuses_external_files);
  RUN(accessor_count_overflow_refused);
  RUN(null_desc_is_the_default);
  TEST_END();
}
