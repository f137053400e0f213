/* The tlod sub-commands: each takes the arguments after its name. */
#ifndef TLOD_TOOLS_COMMANDS_H
#define TLOD_TOOLS_COMMANDS_H

#include <stdio.h>

typedef struct tlod_command {
  const char* name;
  int (*run)(int argc, char** argv);
  void (*usage)(FILE* f);
  const char* summary;
} tlod_command;

/* The command called name, or NULL. */
const tlod_command* command_find(const char* name);
/* "usage: tlod COMMAND ..." and the list of commands. */
void commands_usage(FILE* f);

int cmd_play(int argc, char** argv);
int cmd_tessellate(int argc, char** argv);
int cmd_info(int argc, char** argv);
int cmd_bench(int argc, char** argv);
int cmd_compare(int argc, char** argv);
int cmd_dashboard(int argc, char** argv);
void play_usage(FILE* f);
void tessellate_usage(FILE* f);
void info_usage(FILE* f);
void bench_usage(FILE* f);
void compare_usage(FILE* f);
void dashboard_usage(FILE* f);

#endif
