/* vtk_test_util.h -- shared by the VTK end-to-end tests: write a model, import it through
 * tlod_import_file(), make the core mesh the way the tools do, and measure tessellated output
 * (area, divergence-theorem volume, exact closedness: tests/unit/shapes.h). */
#ifndef TLOD_TESTS_VTK_TEST_UTIL_H
#define TLOD_TESTS_VTK_TEST_UTIL_H

#include <stdbool.h>
#include <stdint.h>

#include "tesslod/core.h"
#include "tesslod/cpu.h"
#include "tlod_import.h"
#include "vtk_model.h"

/* WORK/NAME (the test's scratch folder in the build tree). */
void vtk_test_path(char* out, size_t size, const char* work, const char* name);

/* Writes m to WORK/name in format and imports it; NULL (reason on stderr) on failure. */
tlod_import_result* vtk_test_write_import(const vtk_model* m, const char* work, const char* name, vtk_format format);

/* The core mesh of an import result: faces as imported (quads kept), face_nodes, normals
 * computed with crease_deg (the file has none), the first `attributes` fields as attributes
 * (at most 4 components each). NULL (reason on stderr) on failure. */
tlod_mesh* vtk_test_mesh(tlod_context* ctx, const tlod_import_result* r, float crease_deg, uint32_t attributes);

/* Surface of a mesh; NULL (reason on stderr) on failure. */
tlod_surface* vtk_test_surface(tlod_context* ctx, const tlod_mesh* mesh, tlod_surface_type type);

/* Uniform level tessellation (cpu backend); NULL (reason on stderr) on failure. */
tlod_cpu_mesh* vtk_test_tessellate(tlod_context* ctx, const tlod_surface* s, uint32_t level, bool no_weld);

/* Sum of triangle areas, and the enclosed volume by the divergence theorem (sum of signed
 * tetrahedra against the origin: positive when the triangles face outward), in double. */
void vtk_test_area_volume(const tlod_cpu_mesh* m, double* area, double* volume);

/* Welded by exact position: a closed consistently oriented 2-manifold (shape_closed_manifold). */
bool vtk_test_closed(const tlod_cpu_mesh* m, char* why, size_t why_size);

/* Imported faces of each size (face_sizes NULL: all triangles). */
void vtk_test_face_sizes(const tlod_import_result* r, uint32_t* triangles, uint32_t* quads);

#endif
