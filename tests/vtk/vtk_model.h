/* vtk_model.h -- volume meshes of known size built by the VTK end-to-end tests (issue 14) and
 * written as VTK files at test time (legacy ASCII, legacy binary, XML .vtu), so that the tests
 * know every count, area, volume, node and field value independently of the importer.
 *
 * Cell types and node orders are VTK's (vtkCellType.h; the natural coordinates of each node as
 * VTK's GetParametricCoords() gives them, see vtk_hex_node_coords()). Orientation as VTK's
 * vtkCellValidator checks it: tet, hex, pyramid: the base's right-hand normal points towards the
 * apex / top; wedge: the base (0, 1, 2) faces away from (3, 4, 5) (the opposite of its parametric
 * coordinates). Builders flip chosen cells on purpose and count them in `inverted`. */
#ifndef TLOD_TESTS_VTK_MODEL_H
#define TLOD_TESTS_VTK_MODEL_H

#include <stdbool.h>
#include <stdint.h>

#ifndef M_PI /* strict C11 <math.h> has none */
#define M_PI 3.14159265358979323846
#endif

enum {
  VTK_TRIANGLE = 5,
  VTK_QUAD = 9,
  VTK_TETRA = 10,
  VTK_HEXAHEDRON = 12,
  VTK_WEDGE = 13,
  VTK_PYRAMID = 14,
  VTK_QUADRATIC_TETRA = 24,
  VTK_QUADRATIC_WEDGE = 26,
  VTK_QUADRATIC_HEXAHEDRON = 25,
  VTK_TRIQUADRATIC_HEXAHEDRON = 29
};

#define VTK_MODEL_MAX_FIELDS 4

typedef struct vtk_model_field {
  char name[64];       /* may hold units: "temperature [K]" (XML only: legacy names have no spaces) */
  uint32_t components; /* 1 or 3 */
  bool cells;          /* cell data (else point data) */
  double* data;        /* components per point (or cell) */
} vtk_model_field;

typedef struct vtk_model {
  uint32_t point_count, point_capacity;
  double* points; /* xyz */
  uint32_t cell_count, cell_capacity;
  uint8_t* types;
  uint32_t* offsets; /* cell_count + 1: cell c's nodes are conn[offsets[c] .. offsets[c + 1]) */
  uint32_t conn_count, conn_capacity;
  uint32_t* conn;
  uint32_t inverted; /* cells written with negative orientation on purpose */
  uint32_t field_count;
  vtk_model_field fields[VTK_MODEL_MAX_FIELDS];
} vtk_model;

/* Growing arrays (abort on out of memory: test code). */
uint32_t vtk_model_point(vtk_model* m, double x, double y, double z);
void vtk_model_cell(vtk_model* m, uint8_t type, const uint32_t* nodes, uint32_t count);
/* A field of m's current points (or cells), zeroed; returns its data. */
double* vtk_model_field_add(vtk_model* m, const char* name, uint32_t components, bool cells);
void vtk_model_free(vtk_model* m);

typedef enum vtk_format { VTK_LEGACY_ASCII, VTK_LEGACY_BINARY, VTK_XML_ASCII } vtk_format;
/* Writes m to path; false (and a message on stderr) when the file cannot be written. */
bool vtk_model_write(const vtk_model* m, const char* path, vtk_format format);

/* ---- builders (vtk_models.c) ---- */

/* nx x ny x nz hexahedra filling [0,a]x[0,b]x[0,c]; every fifth cell inverted (top and bottom
 * swapped). Fields: "temperature" (point, 100 + 10x - 5y + z^2), "displacement" (point vector
 * (x, -2y, z/2)), "pressure" (cell: the cell's index). */
void vtk_build_box(vtk_model* m, uint32_t nx, uint32_t ny, uint32_t nz, double a, double b, double c);
/* One unit hexahedron whose point field "payload" holds, as big-endian doubles in a legacy binary
 * file, the bytes of the text "\nPOINTS 999999999999     double\n" (values finite as floats): a reader
 * that scans binary data as words would take it for a header. */
void vtk_build_payload_box(vtk_model* m);
/* A unit-radius disc of height 1 as 12 pie sectors, each a hexahedron collapsed at the axis (nodes
 * 0 and 3, 4 and 7 repeated: how many FE exporters write wedges); VTK draws it, 36 boundary faces. */
void vtk_build_collapsed_pie(vtk_model* m);
/* An icosphere of radius r (20 * 4^subdivisions triangles, vertices on the sphere) filled by one
 * tetrahedron per surface triangle with its apex at the centre; odd tets inverted. */
void vtk_build_tet_sphere(vtk_model* m, uint32_t subdivisions, double r);
/* A solid cylinder, axis z, radius R, height H, `layers` layers of 21 hexahedra each: an O-grid of
 * a 3x3 block in the middle and a ring of 12 cells around it, so the side is 12 quads around
 * (corners exactly on the circle) and the caps 21 quads each. */
void vtk_build_hex_cylinder(vtk_model* m, double R, double H, uint32_t layers);
/* Two quadratic hexahedra side by side ([0,2]x[0,1]x[0,1] warped by vtk_warp()): VTK type 25
 * (20 nodes) or 29 (27 nodes), nodes shared; face-centre nodes (27) are warped too, so they differ
 * from the serendipity centre. */
void vtk_build_quadratic_pair(vtk_model* m, uint8_t type);
void vtk_warp(const double in[3], double out[3]);
/* vtk_build_quadratic_pair() (20 nodes) and a linear hexahedron on [2,3]x[0,1]x[0,1] (warped corners)
 * against the second one's x+ face: the linear faces' four edges at x = 2 have no node of their own
 * and must take the quadratic neighbour's (tlod_mesh_info.nodes_shared). */
void vtk_build_mixed_order(vtk_model* m);
/* Two 10-node tetrahedra (VTK type 24) sharing a face, (0,0,0) (1,0,0) (0,1,0) (0,0,1) and that face
 * with (1,1,1), nodes at the straight edges' midpoints, all warped by vtk_warp(). */
void vtk_build_quadratic_tet_pair(vtk_model* m);
/* Two 15-node wedges (VTK type 26) filling [1,2]x[0,1]x[0,1] split by the plane x + y = 2 (as in
 * vtk_build_mixed()), VTK-positive, nodes at the straight edges' midpoints, all warped. */
void vtk_build_quadratic_wedge_pair(vtk_model* m);
/* [0,4]x[0,1]x[0,1]: a hexahedron, two wedges, six pyramids around a centre point, and one
 * pyramid plus ten tetrahedra around another centre point; conforming. Boundary: 11 quads and
 * 14 triangles. */
void vtk_build_mixed(vtk_model* m);

/* The natural coordinates in [0,1]^3 of node k (0..26) of a VTK quadratic / triquadratic
 * hexahedron (VTK 9.1's vtkTriQuadraticHexahedron::GetParametricCoords(); nodes 0..19 are
 * vtkQuadraticHexahedron's). Note that the mid-face order is x-, x+, y-, y+, z-, z+. */
void vtk_hex_node_coords(uint32_t k, double out[3]);
/* The same for node k (0..9) of a VTK quadratic tetrahedron (vtkQuadraticTetra): corners, then the
 * edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3). */
void vtk_tet_node_coords(uint32_t k, double out[3]);
/* Node k (0..14) of a VTK quadratic wedge (vtkQuadraticWedge): corners 0..5, then the edges (0,1)
 * (1,2) (2,0), (3,4) (4,5) (5,3), (0,3) (1,4) (2,5); (r, s) in the triangle, t along the extrusion. */
void vtk_wedge_node_coords(uint32_t k, double out[3]);

#endif
