/* tlod play -- the run folder and the paths in it. */
#ifndef TLOD_TOOLS_PLAY_RUN_FOLDER_H
#define TLOD_TOOLS_PLAY_RUN_FOLDER_H

#include <stdbool.h>
#include <stddef.h>

#include "play_options.h"

/* "a/b" into buf; false (and "") when it does not fit. */
bool play_path_join(char* buf, size_t size, const char* a, const char* b);
/* mkdir -p; true when path is a folder afterwards. */
bool play_mkdir_p(const char* path);
/* --out DIR, or a new runs/YYYYmmdd-HHMMSS[-N]; prints the error. */
int play_make_run_folder(const play_options* o, char* out, size_t size);

#endif
