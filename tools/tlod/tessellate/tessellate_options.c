/* tlod tessellate -- usage and option parsing. */
#include "tessellate_options.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "common/mesh_load.h"
#include "tool_names.h"

void tessellate_usage(FILE* f) {
  fprintf(f,
          "usage: tlod tessellate IN -o OUT [options]\n"
          "Tessellates every face of IN at one level and writes the result.\n"
          "  IN                  .gltf .glb .obj .ply file, a VTK file (.vtk .vtu .vtp .pvtu .stl; a series, .pvd\n"
          "                      or numbered files NAME_*.vtu: its first step), or a built-in mesh (%s)\n"
          "  -o, --output OUT    .obj .ply .gltf .glb (format from the extension); attributes (UVs, colours)\n"
          "                      are kept; .gltf/.glb of a file keep its nodes, meshes, materials, textures\n"
          "  --surface S         auto (default) | phong | pn | flat | quadratic; auto: quadratic for VTK files\n"
          "                      with second-order faces, else phong; pn splits quads into triangles and\n"
          "                      ignores second-order nodes; quadratic on linear faces is their Phong surface\n"
          "  --alpha A           Phong shape factor in [0, 1] (default 0.75)\n"
          "  --level L           refinement level 0..%d: 2^L - 1 inserted vertices per edge (default 3)\n"
          "  --normals M         keep (given normals, normalised; default) | angle | area (recompute)\n"
          "  --crease DEG        with computed normals, split normals across edges sharper than DEG\n"
          "                      (default: none; VTK files %.0f, so machined edges stay sharp)\n"
          "  --no-weld           keep each patch's own vertices, as a GPU draws them\n"
          "  --threads N         worker threads (default: all CPUs)\n"
          "  --stats FILE.json   write counts, repairs and timings (adaptive: levels per input face, ...)\n"
          "  -q, --quiet         print nothing on success\n"
          "Adaptive (view-dependent) when a camera is given:\n"
          "  --eye X,Y,Z         camera position\n"
          "  --target X,Y,Z      point looked at (default: the mesh's bounding-box centre)\n"
          "  --up X,Y,Z          up direction (default 0,1,0; not along the view direction)\n"
          "  --fovy DEG          vertical field of view (default 45; 0: orthographic, see --ortho-height)\n"
          "  --ortho-height H    orthographic view height in world units\n"
          "  --size WxH          viewport in pixels (default 1280x720)\n"
          "  --epsilon PX        screen-space error bound in pixels (default 0.5)\n"
          "  --policy P          error | silhouette | hybrid (default hybrid)\n"
          "  --max-level L       finest level allowed, 1..%d (default 6)\n"
          "  --no-stitch         leave out connection strips (shows the cracks)\n",
          cli_demo_names(), TLOD_MAX_LEVEL, (double)CLI_VTK_CREASE_DEG, TLOD_MAX_LEVEL);
}

static int parse_vec3(int argc, char** argv, int* i, float* dst) {
  const char* a = argv[*i];
  const char* v = cli_value(argc, argv, i);
  if (!v) return CLI_USAGE;
  return cli_usage_unless(cli_parse_vec3(a, v, dst));
}

static int parse_size(int argc, char** argv, int* i, adaptive_options* ad) {
  const char* a = argv[*i];
  const char* v = cli_value(argc, argv, i);
  return cli_usage_unless(v && cli_parse_size(a, v, 65536, &ad->width, &ad->height));
}

static int parse_camera(int argc, char** argv, int* i, adaptive_options* ad) {
  const char* a = argv[*i];
  const char* v = NULL;
  if (!strcmp(a, "--eye")) {
    ad->on = true;
    return parse_vec3(argc, argv, i, ad->cam.eye);
  }
  if (!strcmp(a, "--target")) return parse_vec3(argc, argv, i, ad->cam.target);
  if (!strcmp(a, "--up")) return parse_vec3(argc, argv, i, ad->cam.up);
  if (!strcmp(a, "--fovy"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 0.0, 179.0, &ad->cam.fovy_deg));
  if (!strcmp(a, "--ortho-height"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) &&
                            cli_parse_float(a, v, 1e-30, 1e30, &ad->cam.ortho_height));
  if (!strcmp(a, "--size")) return parse_size(argc, argv, i, ad);
  return CLI_NOT_MINE;
}

/* One option of adaptive mode at argv[*i]: CLI_OK, CLI_USAGE or CLI_NOT_MINE. */
static int parse_adaptive(int argc, char** argv, int* i, adaptive_options* ad) {
  const char* a = argv[*i];
  int rc = cli_parse_lod_option(argc, argv, i, &ad->epsilon, &ad->policy, &ad->max_level);
  if (rc != CLI_NOT_MINE) return rc;
  if (!strcmp(a, "--no-stitch")) {
    ad->no_stitch = true;
    return CLI_OK;
  }
  return parse_camera(argc, argv, i, ad);
}

static int parse_surface(int argc, char** argv, int* i, tess_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  int e;
  if (!strcmp(a, "--surface")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, tool_surface_auto_options)) < 0) return CLI_USAGE;
    o->surface = (tlod_surface_type)e;
    return CLI_OK;
  }
  if (!strcmp(a, "--normals")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, tool_normal_options)) < 0) return CLI_USAGE;
    o->normals = (tlod_normal_mode)(TLOD_NORMALS_KEEP + e);
    return CLI_OK;
  }
  if (!strcmp(a, "--alpha"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 0.0, 1.0, &o->alpha));
  if (!strcmp(a, "--crease"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 0.0, 180.0, &o->crease));
  if (!strcmp(a, "--level"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_uint(a, v, 0, TLOD_MAX_LEVEL, &o->level));
  return CLI_NOT_MINE;
}

static int parse_run(int argc, char** argv, int* i, tess_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  if (!strcmp(a, "-o") || !strcmp(a, "--output")) return cli_usage_unless((o->out = cli_value(argc, argv, i)) != NULL);
  if (!strcmp(a, "--stats")) return cli_usage_unless((o->stats = cli_value(argc, argv, i)) != NULL);
  if (!strcmp(a, "--threads"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_uint(a, v, 1, 64, &o->threads));
  if (!strcmp(a, "--no-weld")) {
    o->no_weld = true;
    return CLI_OK;
  }
  if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
    o->quiet = true;
    return CLI_OK;
  }
  return CLI_NOT_MINE;
}

static int parse_argument(int argc, char** argv, int* i, tess_options* o) {
  const char* a = argv[*i];
  if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
    tessellate_usage(stdout);
    exit(0);
  }
  int rc = parse_run(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = parse_surface(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = parse_adaptive(argc, argv, i, &o->ad);
  if (rc != CLI_NOT_MINE) return rc;
  if (a[0] == '-' && a[1])
    return cli_error(CLI_USAGE, "tessellate: unknown option '%s' (see tlod tessellate --help)", a);
  if (o->in) return cli_error(CLI_USAGE, "tessellate: unexpected argument '%s'", a);
  o->in = a;
  return CLI_OK;
}

static void set_defaults(tess_options* o) {
  *o = (tess_options){
      .surface = TLOD_SURFACE_DEFAULT, .alpha = 0.75f, .level = 3, .normals = TLOD_NORMALS_KEEP, .crease = -1.0f};
  o->ad = (adaptive_options){.cam = {.up = {0, 1, 0}, .fovy_deg = 45.0f, .target = {NAN, NAN, NAN}},
                             .width = 1280,
                             .height = 720,
                             .max_level = 6,
                             .epsilon = 0.5f,
                             .policy = TLOD_POLICY_HYBRID};
}

int tessellate_parse(int argc, char** argv, tess_options* o) {
  set_defaults(o);
  for (int i = 0; i < argc; i++) {
    int rc = parse_argument(argc, argv, &i, o);
    if (rc != CLI_OK) return rc;
  }
  if (!o->in) return cli_error(CLI_USAGE, "tessellate: no input (see tlod tessellate --help)");
  if (!o->out) return cli_error(CLI_USAGE, "tessellate: no output: give -o OUT");
  if (o->ad.on && o->ad.cam.fovy_deg == 0.0f && o->ad.cam.ortho_height == 0.0f)
    return cli_error(CLI_USAGE, "tessellate: --fovy 0 (orthographic) needs --ortho-height");
  return CLI_OK;
}
