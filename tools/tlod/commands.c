/* tlod -- the table of sub-commands. */
#include "commands.h"

#include <string.h>

#include "common/mesh_load.h"

static const tlod_command commands[] = {
    {"play", cmd_play, play_usage, "play a scene along a camera path and record per-frame timings"},
    {"tessellate", cmd_tessellate, tessellate_usage, "tessellate a mesh on the CPU and write it out"},
    {"info", cmd_info, info_usage, "print mesh statistics and validation findings"},
    {"bench", cmd_bench, bench_usage, "measure preprocessing and CPU evaluation rates"},
    {"compare", cmd_compare, compare_usage, "compare two play runs; exit 1 when the new one regressed"},
    {"dashboard", cmd_dashboard, dashboard_usage, "write play runs as one self-contained HTML page of charts"},
};
enum { COMMAND_COUNT = sizeof(commands) / sizeof(commands[0]) };

const tlod_command* command_find(const char* name) {
  for (int i = 0; i < COMMAND_COUNT; i++) {
    if (!strcmp(name, commands[i].name)) return &commands[i];
  }
  return NULL;
}

void commands_usage(FILE* f) {
  fprintf(f, "usage: tlod COMMAND [options]   (tlod COMMAND --help for its options)\n\ncommands:\n");
  for (int i = 0; i < COMMAND_COUNT; i++)
    fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
  fprintf(f,
          "\nInputs are .gltf .glb .obj .ply files, VTK files (.vtk .vtu .vtp .pvtu .stl, a .pvd series or\n"
          "numbered files NAME_*.vtu) or built-in meshes: %s\n",
          cli_demo_names());
}
