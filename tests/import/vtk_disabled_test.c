/* vtk_disabled_test.c -- a build with TLOD_WITH_VTK=OFF refuses VTK's formats with
 * TLOD_ERROR_UNSUPPORTED naming the file, the extension and the option (docs/vtk.md section 1),
 * and still reads the other formats. Owned by the import/export layer. */
#include "test.h"
#include "tlod_import.h"

TEST(vtk_formats_name_the_build_option) {
  static const char* const names[] = {"model.vtk", "model.vtu", "model.vtp", "model.pvtu", "model.pvd", "model.stl"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
    char err[256], want[128];
    tlod_import_result* r = NULL;
    const tlod_result res = tlod_import_memory(names[i], "x", 1, NULL, &r, err, sizeof err);
    snprintf(want, sizeof want, "%s: %s files need VTK: this build has TLOD_WITH_VTK=OFF", names[i],
             strchr(names[i], '.'));
    CHECK_MSG(res == TLOD_ERROR_UNSUPPORTED && r == NULL && strcmp(err, want) == 0, "%s", err);
  }
  const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  tlod_import_result* r = NULL;
  CHECK(tlod_import_memory("tri.obj", obj, strlen(obj), NULL, &r, NULL, 0) == TLOD_SUCCESS);
  tlod_import_free(r);
}

int main(void) {
  RUN(vtk_formats_name_the_build_option);
  TEST_END();
}
