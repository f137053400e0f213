/* fuzz_mesh.c -- core on hostile but parseable geometry: whatever an importer accepts goes
 * through tlod_mesh_create() and tlod_surface_create(), and a few patches are evaluated.
 *
 * Input: one option byte, then the file.
 *   bits 0-1  format: .obj, .ply, .glb, .gltf
 *   bits 2-3  surface: FLAT, PHONG, PN, PHONG with TRUE shading normals
 *   bits 4-5  normal mode: DEFAULT, KEEP, ANGLE, AREA
 *   bit 6     crease angle 30 degrees (else none)
 *   bit 7     weld epsilon 1e-3 (else bitwise-equal positions only)
 * A file that starts as VTK's do ("# vtk DataFile", or "<?xml" / "<VTKFile" with a
 * VTKFile tag in its first 256 bytes) is read as .vtk, or .vtp (type "PolyData") / .vtu,
 * whatever bits 0-1 say: none of the other four formats can start so, so older inputs keep
 * their meaning. For those, bits 2-3 pick FLAT, PHONG, QUADRATIC, QUADRATIC with TRUE
 * shading normals, and the import's face_nodes go into the mesh, so core's node validation
 * and sharing see the nodes of hostile second-order cells.
 * Meshes past kMaxFaces are left out: the surface build does work per patch (error tables),
 * so a big mesh is slow by design, not a finding; fuzz_obj & co. still read them. */

#include <string.h>

#include "fuzz_common.h"
#include "import_contract.h"

enum { kMaxFaces = 4096, kEvalPatches = 8 };

static const char* const kExt[4] = {".obj", ".ply", ".glb", ".gltf"};
static const tlod_surface_type kSurface[4] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN,
                                              TLOD_SURFACE_PHONG};
static const tlod_surface_type kVtkSurface[4] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_QUADRATIC,
                                                 TLOD_SURFACE_QUADRATIC};

static int starts_with(const uint8_t* d, size_t n, const char* s) {
  const size_t k = strlen(s);
  return n >= k && memcmp(d, s, k) == 0;
}

static int contains(const uint8_t* d, size_t n, const char* s) {
  for (size_t i = 0; i < n; ++i)
    if (starts_with(d + i, n - i, s)) return 1;
  return 0;
}

/* The VTK extension the file's first bytes call for, or NULL (see the top). */
static const char* vtk_ext(const uint8_t* d, size_t n) {
  if (starts_with(d, n, "# vtk DataFile")) return ".vtk";
  const size_t head = n < 256 ? n : 256;
  if (!(starts_with(d, n, "<?xml") || starts_with(d, n, "<VTKFile")) || !contains(d, head, "<VTKFile")) return NULL;
  return contains(d, head, "\"PolyData\"") ? ".vtp" : ".vtu";
}

static tlod_mesh* make_mesh(tlod_context* ctx, const tlod_import_result* r, uint8_t opt) {
  tlod_mesh_desc desc = {
      .positions = r->positions,
      .normals = r->normals,
      .vertex_count = r->vertex_count,
      .indices = r->indices,
      .index_count = r->index_count,
      .face_type = r->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
      .face_sizes = r->face_sizes,
      .face_count = r->face_sizes ? r->face_count : 0,
      .normal_mode = (tlod_normal_mode)((opt >> 4) & 3u),
      .crease_angle_deg = (opt & 0x40u) ? 30.0f : 0.0f,
      .weld_epsilon = (opt & 0x80u) ? 1e-3f : 0.0f,
      .face_nodes = r->face_nodes,
  };
  tlod_mesh* mesh = NULL;
  if (tlod_mesh_create(ctx, &desc, &mesh) != TLOD_SUCCESS) {
    fuzz_check(mesh == NULL, "a failed tlod_mesh_create left a mesh");
    fuzz_check(tlod_context_last_error(ctx)[0] != 0, "tlod_mesh_create failed without a message");
    return NULL;
  }
  return mesh;
}

static void surface(tlod_context* ctx, const tlod_mesh* mesh, uint8_t opt, int vtk) {
  tlod_surface_desc desc = {.type = (vtk ? kVtkSurface : kSurface)[(opt >> 2) & 3u]};
  if (((opt >> 2) & 3u) == 3u) desc.shading_normal = TLOD_SHADING_NORMAL_TRUE;
  tlod_surface* s = NULL;
  if (tlod_surface_create(ctx, mesh, &desc, &s) != TLOD_SUCCESS) {
    fuzz_check(s == NULL, "a failed tlod_surface_create left a surface");
    fuzz_check(tlod_context_last_error(ctx)[0] != 0, "tlod_surface_create failed without a message");
    return;
  }
  uint32_t n = tlod_surface_patch_count(s);
  for (uint32_t p = 0; p < n && p < kEvalPatches; ++p) {
    tlod_patch_info info = tlod_surface_patch(s, p);
    fuzz_check(info.corner_count == 3 || info.corner_count == 4, "a patch with neither 3 nor 4 corners");
    tlod_surface_point pt;
    tlod_surface_eval(s, p, 0.25f, 0.25f, &pt);
    (void)tlod_patch_error_bound(&info, 4);
  }
  tlod_surface_destroy(s);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t opt = data[0];
  const char* vtk = vtk_ext(data + 1, size - 1);
  const char* path = fuzz_input_file(vtk ? vtk : kExt[opt & 3u], data + 1, size - 1);
  char error[256];
  tlod_import_result* r = NULL;
  tlod_result res = tlod_import_file(path, NULL, &r, error, sizeof error);
  fuzz_check_import(res, r, error, path);
  if (res != TLOD_SUCCESS || r->face_count > kMaxFaces) {
    tlod_import_free(r);
    return 0;
  }
  tlod_context* ctx = NULL;
  fuzz_check(tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS,
             "tlod_context_create failed");
  tlod_mesh* mesh = make_mesh(ctx, r, opt);
  if (mesh) surface(ctx, mesh, opt, vtk != NULL);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  tlod_import_free(r);
  return 0;
}
