/* tlod -- the tesslod command: play, tessellate, info, bench. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "tesslod/core.h"

typedef struct command {
  const char* name;
  int (*run)(int argc, char** argv);
  void (*usage)(FILE* f);
  const char* summary;
} command;

static const command commands[] = {
    {"play", cmd_play, play_usage, "play a scene along a camera path and record per-frame timings"},
    {"tessellate", cmd_tessellate, tessellate_usage, "tessellate a mesh on the CPU and write it out"},
    {"info", cmd_info, info_usage, "print mesh statistics and validation findings"},
    {"bench", cmd_bench, bench_usage, "measure preprocessing and CPU evaluation rates"},
};
enum { COMMAND_COUNT = sizeof(commands) / sizeof(commands[0]) };

static void usage(FILE* f) {
  fprintf(f, "usage: tlod COMMAND [options]   (tlod COMMAND --help for its options)\n\ncommands:\n");
  for (int i = 0; i < COMMAND_COUNT; i++)
    fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
  fprintf(f, "\nInputs are .gltf .glb .obj .ply files or built-in meshes: %s\n", cli_demo_names());
}

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return CLI_USAGE;
  }
  if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
    usage(stdout);
    return CLI_OK;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("tlod %d.%d.%d\n", TLOD_VERSION / 1000, TLOD_VERSION / 10 % 100, TLOD_VERSION % 10);
    return CLI_OK;
  }
  for (int i = 0; i < COMMAND_COUNT; i++) {
    if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 2, argv + 2);
  }
  return cli_error(CLI_USAGE, "unknown command '%s' (see tlod --help)", argv[1]);
}
