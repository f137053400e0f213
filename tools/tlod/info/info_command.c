/* tlod info -- mesh statistics and validation findings. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "common/mesh_load.h"
#include "tool_names.h"

void info_usage(FILE* f) {
  fprintf(f,
          "usage: tlod info IN [--normals keep|angle|area] [--crease DEG] [--findings N]\n"
          "Prints counts, bounds, topology (boundary, non-manifold and crease edges) and what\n"
          "validation found and repaired (the first N findings, default 10). IN: a .gltf .glb .obj .ply\n"
          "file, a VTK file (.vtk .vtu .vtp .pvtu .pvd .stl, or a numbered series NAME_*.vtu) or %s.\n"
          "VTK files also get: cells by type, the boundary faces kept (triangle and quad patches,\n"
          "curved second-order faces), the result fields (name, components, range, units, point or\n"
          "cell data), the time steps, what the import repaired, and its timings. Their crease\n"
          "angle defaults to %.0f degrees (--crease 0: none).\n",
          cli_demo_names(), (double)CLI_VTK_CREASE_DEG);
}

/* A mesh's validation findings as text, at most limit of them (the mesh
 * keeps the first TLOD_MAX_FINDINGS), and how many more there are. */
static void print_findings(FILE* f, const tlod_mesh* mesh, uint32_t limit) {
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  uint32_t shown = info.finding_count < limit ? info.finding_count : limit;
  for (uint32_t i = 0; i < shown; i++) {
    tlod_finding fd = tlod_mesh_query_finding(mesh, i);
    fprintf(f, "  finding: %s\n", fd.message);
  }
  uint32_t more = info.finding_count - shown + info.findings_dropped;
  if (more) fprintf(f, "  ... and %u more findings (tlod info --findings N shows more)\n", more);
}

static void print_cells(const tlod_import_vtk_info* v) {
  printf("  vtk:       %llu points, %llu cells:", (unsigned long long)v->points, (unsigned long long)v->cells);
  for (uint32_t c = 0; c < v->cell_type_count && c < TLOD_IMPORT_MAX_CELL_TYPES; c++)
    printf("%s %llu %s (type %u)", c ? "," : "", (unsigned long long)v->cell_types[c].count, v->cell_types[c].name,
           v->cell_types[c].vtk_type);
  printf("\n");
  printf("  boundary:  %llu triangles, %llu quads (%llu second-order) of %llu volume cells; %llu interior faces "
         "dropped\n",
         (unsigned long long)v->boundary_triangles, (unsigned long long)v->boundary_quads,
         (unsigned long long)v->second_order_faces, (unsigned long long)v->volume_cells,
         (unsigned long long)v->interior_faces);
  printf("  vtk fixes: %llu cells reoriented, %llu collapsed cells kept, %llu degenerate cells dropped, %llu "
         "non-manifold faces, %llu polygons triangulated, %llu strips converted, %llu vertex/line cells ignored\n",
         (unsigned long long)v->cells_reoriented, (unsigned long long)v->cells_collapsed,
         (unsigned long long)v->degenerate_cells, (unsigned long long)v->non_manifold_faces,
         (unsigned long long)v->polygons_triangulated, (unsigned long long)v->strips_converted,
         (unsigned long long)v->cells_ignored);
  printf("  vtk time:  read %.1f ms, boundary %.1f ms, fields %.1f ms\n", v->read_ms, v->boundary_ms, v->fields_ms);
}

static void print_fields(const tlod_import_result* r) {
  printf("  fields:    %u%s\n", r->field_count, r->field_count ? ":" : "");
  for (uint32_t i = 0; i < r->field_count; i++) {
    const tlod_import_field* f = &r->fields[i];
    printf("    %s: %u component%s, %s data, range", f->name, f->components, f->components == 1 ? "" : "s",
           f->from_cells ? "cell (averaged to points)" : "point");
    for (uint32_t c = 0; c < f->components && c < TLOD_IMPORT_MAX_FIELD_COMPONENTS; c++)
      printf(" [%g, %g]", (double)f->min[c], (double)f->max[c]);
    if (f->components > 1) printf(", magnitude [%g, %g]", (double)f->magnitude_min, (double)f->magnitude_max);
    printf("%s%s\n", f->units[0] ? ", units " : "", f->units);
  }
  if (r->step_count >= 2 && r->step_times)
    printf("  series:    %u steps, t = %g .. %g s\n", r->step_count, (double)r->step_times[0],
           (double)r->step_times[r->step_count - 1]);
}

/* VTK input: its cells, boundary, fields and what the import did. */
static void print_vtk(const cli_mesh* m, const tlod_mesh_info* i) {
  const tlod_import_result* r = m->source;
  print_cells(r->vtk);
  printf("  patches:   %u triangles, %u quads; %u curved (second-order) faces, %u edge nodes taken from a neighbour\n",
         i->triangle_count, i->quad_count, i->curved_faces, i->nodes_shared);
  printf("  surface:   auto draws %s\n", tool_surface_name(cli_resolve_surface(TLOD_SURFACE_DEFAULT, m)));
  print_fields(r);
}

static void print_info(const char* in, const cli_mesh* m, const tlod_mesh* mesh, uint32_t findings) {
  tlod_mesh_info i = tlod_mesh_query_info(mesh);
  printf("%s\n", in);
  printf("  input:     %u vertices, %u faces\n", i.input_vertex_count, i.input_face_count);
  printf("  kept:      %u faces (%u triangles, %u quads)\n", i.face_count, i.triangle_count, i.quad_count);
  printf("  welded:    %u distinct positions, %u edges\n", i.welded_vertex_count, i.edge_count);
  printf("  topology:  %s; %u boundary, %u non-manifold, %u crease edges\n", i.closed ? "closed" : "open",
         i.boundary_edges, i.non_manifold_edges, i.crease_edges);
  printf("  bounds:    [%g %g %g] .. [%g %g %g]\n", i.bbox_min[0], i.bbox_min[1], i.bbox_min[2], i.bbox_max[0],
         i.bbox_max[1], i.bbox_max[2]);
  printf("  normals:   %s, %u computed, %u repaired\n", m->normals ? "given" : "none given", i.normals_computed,
         i.normals_repaired);
  printf("  repairs:   %u degenerate faces dropped, %u unused vertices\n", i.degenerate_faces_dropped,
         i.unused_vertices);
  if (cli_mesh_is_vtk(m)) print_vtk(m, &i);
  print_findings(stdout, mesh, findings);
  if (m->warnings[0]) printf("  import warnings:\n%s\n", m->warnings);
}

int cmd_info(int argc, char** argv) {
  const char* in = NULL;
  float crease = -1.0f; /* the input's default (cli_resolve_crease) */
  uint32_t findings = 10;
  tlod_normal_mode normals = TLOD_NORMALS_KEEP;
  for (int i = 0; i < argc; i++) {
    const char* v;
    int e;
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      info_usage(stdout);
      return CLI_OK;
    } else if (!strcmp(argv[i], "--findings")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint("--findings", v, 0, TLOD_MAX_FINDINGS, &findings))
        return CLI_USAGE;
    } else if (!strcmp(argv[i], "--crease")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float("--crease", v, 0.0, 180.0, &crease)) return CLI_USAGE;
    } else if (!strcmp(argv[i], "--normals")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum("--normals", v, tool_normal_options)) < 0)
        return CLI_USAGE;
      normals = (tlod_normal_mode)(TLOD_NORMALS_KEEP + e);
    } else if (argv[i][0] == '-' && argv[i][1]) {
      return cli_error(CLI_USAGE, "info: unknown option '%s' (see tlod info --help)", argv[i]);
    } else if (!in) {
      in = argv[i];
    } else {
      return cli_error(CLI_USAGE, "info: unexpected argument '%s'", argv[i]);
    }
  }
  if (!in) return cli_error(CLI_USAGE, "info: no input (see tlod info --help)");
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 1, .label = "tlod"}, &ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  cli_mesh m;
  tlod_mesh* mesh = NULL;
  int rc = cli_load(in, &m);
  if (rc == CLI_OK && (rc = cli_create_mesh(ctx, &m, normals, cli_resolve_crease(crease, &m), &mesh)) == CLI_OK)
    print_info(in, &m, mesh, findings);
  tlod_mesh_destroy(mesh);
  cli_mesh_free(&m);
  tlod_context_destroy(ctx);
  return rc;
}
