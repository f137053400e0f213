/* tlod bench -- usage and option parsing. */
#include "bench_options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_bandwidth.h"
#include "cli.h"
#include "commands.h"
#include "common/gpu_target.h"
#include "tesslod/backend.h"
#include "tesslod/lod.h"
#include "tool_names.h"

void bench_usage(FILE* f) {
  fprintf(f,
          "usage: tlod bench [IN] [options]\n"
          "Measures, on IN (default demo:torus-320x160, 102,400 triangles; quads are split):\n"
          "  preprocessing: mesh validation + adjacency + normals, and patch setup per surface (patches/s);\n"
          "  CPU evaluation: tlod_cpu_tessellate per surface, level and thread count (output vertices/s),\n"
          "  the Phong/flat and PN/flat time ratios, and output bytes/s against memcpy bandwidth.\n"
          "  --levels L,L       levels to evaluate (default 3,5)\n"
          "  --threads N,N      thread counts (default 1,2)\n"
          "  --repeat N         timed runs per case (default 3)\n"
          "  --warmup N         untimed runs first (default 1)\n"
          "  --csv FILE         also write one CSV row per case\n"
          "  --suite S          eval (default) | build | scheduler | table1 | gl | skin | objects | draw |\n"
          "                     vkstart | figures | peers | all\n"
          "                     build: tlod_surface_create on one thread, CPU time per 100k patches of IN\n"
          "                     with measured error tables against closed-form ones, per surface type\n"
          "                     (flat, Phong one alpha, Phong per-vertex alpha, PN), --repeat interleaved\n"
          "                     rounds (min, median), and the bytes per patch of the tables\n"
          "                     scheduler: tlod_scheduler_update per frame on 10k, 100k, 1M patches (Phong\n"
          "                     torus quads), a refining camera above the tube (levels 0-6, contours, strips,\n"
          "                     culling) moving and still: process CPU and wall ms (min, median), stages,\n"
          "                     level histogram, culled share, strip triangles, memory bound\n"
          "                     table1: Schwarz et al.'s Table 1 (PN, 1600x1144, 0.5 px): base, adaptive per\n"
          "                     policy, uniform at the worst patch's level, strip overhead\n"
          "                     gl: frame times of --backend (llvmpipe / lavapipe, wall clock): flat, adaptive,\n"
          "                     uniform, hardware tessellation per model; Phong against flat at equal triangles\n"
          "                     skin: skinning, tlod_mesh_update, tlod_surface_refresh per frame on a generated\n"
          "                     two-joint cylinder (10k, 40k, 160k vertices), per 10k vertices, min/median of\n"
          "                     --repeat frames, at --threads and the machine's thread count (not in all)\n"
          "                     objects: 50 instances of one mesh (a scheduler and draw item each) against\n"
          "                     the same triangles merged into one object, cpu and --backend, --frames frames\n"
          "                     draw: backend CPU time per frame (recording / GL calls, no GPU wait) for about\n"
          "                     100k visible patches on --backend, uniform:1 and adaptive, min/median of --frames\n"
          "                     figures: issue 15's headline figures and their cases: the scheduler's\n"
          "                     refining cases on --scheduler-mesh, CPU evaluation of IN at level 5 (flat,\n"
          "                     Phong, PN), Table 1 strip overhead on the --model scenes (default the cow,\n"
          "                     the Duck and fran_cut)\n"
          "                     peers: tesslod against OpenSubdiv (needs a build with OpenSubdiv; --peers)\n"
          "                     vkstart: vulkan device start (create + first frame): shader stages compiled,\n"
          "                     loaded from the cache and their ms, without a cache, with an empty one and\n"
          "                     with the one the empty start filled; --repeat rounds (not in all)\n"
          "  --json FILE        the run as one JSON document (processor, simd, memory rates, every case,\n"
          "                     scheduler_1m_ms, eval_bandwidth_fraction, strip_triangle_overhead)\n"
          "  --scheduler-mesh IN  figures: the scheduler mesh (default demo:torus-1000x1000)\n"
          "  --bandwidth-mib N  memory-rate buffers, MiB (default 640: past this machine's 300 MB cache)\n"
          "  --frames N         frames per case: scheduler, objects (default 20), gl, draw (default 60)\n"
          "  --model IN         a table1 model (repeatable; default demo:cow)\n"
          "  --backend B        gl (default) | vulkan: the GPU backend of gl, objects and draw (this build\n"
          "                     has: %s)\n"
          "  --shader-cache D   vulkan: SPIR-V cache folder or off (default $XDG_CACHE_HOME/tesslod, else\n"
          "                     $HOME/.cache/tesslod); vkstart uses folders of its own\n"
          "  --peers            the peers suite: tesslod (Phong) side by side with OpenSubdiv 3.5 (Loop for\n"
          "                     triangles, Catmull-Clark otherwise) on torus meshes of triangles, quads and both,\n"
          "                     one thread each, alternating: preprocessing time (cold: pages first touched;\n"
          "                     warm: pages reused; ours also with the scheduler's error tables) and peak\n"
          "                     heap, output\n"
          "                     vertices/s at levels 1-4 for positions (PrimvarRefiner) and positions + normals\n"
          "                     (limit evaluation), static and deforming, input-vertex distance, volume change;\n"
          "                     needs a tlod built with OpenSubdiv (scripts/bootstrap --peers)\n"
          "                     (== --suite peers; with --json its figures go under the key \"peers\")\n"
          "  --peer-faces N     --peers on meshes of about N faces (default: 100000 and 1000000)\n"
          "  --peer-mesh KIND   --peers on one mesh: triangle | quad | mixed (default: all three)\n"
          "  --peer-levels L,L  --peers at these levels, 1-4 (default: 1,2,3,4)\n",
          tlod_backend_names());
}

static bool parse_list(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out, uint32_t* count) {
  char buf[128];
  snprintf(buf, sizeof(buf), "%s", text);
  *count = 0;
  for (char* tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    if (*count == 8 || !cli_parse_uint(option, tok, lo, hi, &out[*count])) return false;
    (*count)++;
  }
  return *count > 0 || (cli_error(CLI_USAGE, "%s: empty list", option), false);
}

int bench_parse(int argc, char** argv, bench_options* o) {
  *o = (bench_options){.in = "demo:torus-320x160",
                       .levels = {3, 5},
                       .level_count = 2,
                       .threads = {1, 2},
                       .thread_count = 2,
                       .repeat = 3,
                       .warmup = 1,
                       .frames = 20,
                       .suite = "eval",
                       .backend = "gl",
                       .scheduler_mesh = "demo:torus-1000x1000",
                       .bandwidth_mib = BENCH_BANDWIDTH_MIB};
  for (int i = 0; i < argc; i++) {
    const char* a = argv[i];
    const char* v = NULL;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      bench_usage(stdout);
      exit(0);
    } else if (!strcmp(a, "--levels")) {
      if (!(v = cli_value(argc, argv, &i)) || !parse_list(a, v, 0, TLOD_MAX_LEVEL, o->levels, &o->level_count))
        return CLI_USAGE;
    } else if (!strcmp(a, "--threads")) {
      if (!(v = cli_value(argc, argv, &i)) || !parse_list(a, v, 1, 64, o->threads, &o->thread_count)) return CLI_USAGE;
    } else if (!strcmp(a, "--repeat")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 1000, &o->repeat)) return CLI_USAGE;
    } else if (!strcmp(a, "--warmup")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 0, 1000, &o->warmup)) return CLI_USAGE;
    } else if (!strcmp(a, "--suite")) {
      static const char* const suites[] = {"eval", "build",   "scheduler", "table1", "gl",  "skin", "objects",
                                           "draw", "vkstart", "figures",   "peers",  "all", NULL};
      if (!(v = cli_value(argc, argv, &i)) || cli_parse_enum(a, v, suites) < 0) return CLI_USAGE;
      o->suite = v;
    } else if (!strcmp(a, "--frames")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 100000, &o->frames)) return CLI_USAGE;
      o->frames_given = true;
    } else if (!strcmp(a, "--model")) {
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (o->table1_count == 16) return cli_error(CLI_USAGE, "--model: at most 16 models");
      o->table1[o->table1_count++] = v;
    } else if (!strcmp(a, "--backend")) {
      int e;
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, tool_backend_options())) < 0) return CLI_USAGE;
      o->backend = tool_backend_options()[e];
      if (!gpu_backend(o->backend))
        return cli_error(CLI_USAGE, "--backend: %s: the suites that draw need a GPU backend, gl or vulkan", v);
    } else if (!strcmp(a, "--shader-cache")) {
      if (!(o->shader_cache = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--json")) {
      if (!(o->json = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--scheduler-mesh")) {
      if (!(o->scheduler_mesh = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--bandwidth-mib")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 65536, &o->bandwidth_mib)) return CLI_USAGE;
    } else if (!strcmp(a, "--peers")) {
      o->suite = "peers";
    } else if (!strcmp(a, "--peer-faces")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 16, 4000000, &o->peer_faces)) return CLI_USAGE;
    } else if (!strcmp(a, "--peer-mesh")) {
      if (!(o->peer_mesh = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (strcmp(o->peer_mesh, "triangle") && strcmp(o->peer_mesh, "quad") && strcmp(o->peer_mesh, "mixed"))
        return cli_error(CLI_USAGE, "bench: --peer-mesh '%s': triangle, quad or mixed", o->peer_mesh);
    } else if (!strcmp(a, "--peer-levels")) {
      if (!(v = cli_value(argc, argv, &i)) || !parse_list(a, v, 1, 4, o->peer_levels, &o->peer_level_count))
        return CLI_USAGE;
    } else if (!strcmp(a, "--csv")) {
      if (!(o->csv = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (a[0] == '-' && a[1]) {
      return cli_error(CLI_USAGE, "bench: unknown option '%s' (see tlod bench --help)", a);
    } else {
      o->in = a;
    }
  }
  return CLI_OK;
}
