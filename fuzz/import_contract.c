/* import_contract.c -- tlod_import_file()'s promises (tools/import/tlod_import.h). */
#include "import_contract.h"

#include <math.h>
#include <string.h>

#include "fuzz_common.h"

static void check_arrays(const tlod_import_result* r) {
  for (size_t i = 0; i < (size_t)r->vertex_count * 3u; ++i)
    fuzz_check(isfinite(r->positions[i]), "a successful import has a non-finite position");
  for (uint32_t i = 0; i < r->index_count; ++i)
    fuzz_check(r->indices[i] < r->vertex_count, "a successful import has an index out of range");
  if (!r->face_sizes) {
    fuzz_check((uint64_t)r->face_count * 3u == r->index_count, "face_count * 3 != index_count (all triangles)");
    return;
  }
  uint64_t sum = 0;
  for (uint32_t f = 0; f < r->face_count; ++f) {
    fuzz_check(r->face_sizes[f] == 3 || r->face_sizes[f] == 4, "a face size other than 3 or 4");
    sum += r->face_sizes[f];
  }
  fuzz_check(sum == r->index_count, "the face sizes do not add up to index_count");
}

static void check_parts(const tlod_import_result* r) {
  for (uint32_t p = 0; p < r->part_count; ++p) {
    const tlod_import_part* part = &r->parts[p];
    fuzz_check((uint64_t)part->first_face + part->face_count <= r->face_count, "a part's faces run past the faces");
    fuzz_check((uint64_t)part->first_vertex + part->vertex_count <= r->vertex_count,
               "a part's vertices run past the vertices");
    fuzz_check(memchr(part->name, 0, sizeof part->name) != NULL, "a part name is not terminated");
  }
  fuzz_check(memchr(r->warnings, 0, sizeof r->warnings) != NULL, "the warnings are not terminated");
}

void fuzz_check_import(tlod_result res, const tlod_import_result* r, const char* error, const char* path) {
  fuzz_check(res >= TLOD_SUCCESS && res <= TLOD_ERROR_PARSE && res != TLOD_ERROR_BACKEND,
             "a result code tlod_import_file() does not list");
  if (res != TLOD_SUCCESS) {
    fuzz_check(r == NULL, "a failed import left a result");
    fuzz_check_error(error, fuzz_base_name(path));
    return;
  }
  fuzz_check(r != NULL, "a successful import left no result");
  fuzz_check(error[0] == 0, "a successful import left an error message");
  fuzz_check(r->vertex_count == 0 || r->positions != NULL, "vertices without positions");
  fuzz_check(r->index_count == 0 || r->indices != NULL, "index_count without indices");
  check_arrays(r);
  check_parts(r);
}
