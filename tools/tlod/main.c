/* tlod -- the tesslod command: play, tessellate, info, bench. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "tesslod/core.h"

static bool is_help(const char* a) { return !strcmp(a, "-h") || !strcmp(a, "--help") || !strcmp(a, "help"); }

int main(int argc, char** argv) {
  if (argc < 2) {
    commands_usage(stderr);
    return CLI_USAGE;
  }
  if (is_help(argv[1])) {
    commands_usage(stdout);
    return CLI_OK;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("tlod %d.%d.%d\n", TLOD_VERSION / 1000, TLOD_VERSION / 10 % 100, TLOD_VERSION % 10);
    return CLI_OK;
  }
  const tlod_command* c = command_find(argv[1]);
  if (c) return c->run(argc - 2, argv + 2);
  return cli_error(CLI_USAGE, "unknown command '%s' (see tlod --help)", argv[1]);
}
