/* tlod play -- the run folder and the paths in it. */
#ifndef TLOD_TOOLS_PLAY_RUN_FOLDER_H
#define TLOD_TOOLS_PLAY_RUN_FOLDER_H

#include <stdbool.h>
#include <stddef.h>

#include "common/folder.h"
#include "play_options.h"

/* "a/b" into buf; false (and "") when it does not fit. */
bool play_path_join(char* buf, size_t size, const char* a, const char* b);
/* --out DIR, or a new runs/YYYYmmdd-HHMMSS[-N], locked for this process
 * (play_lock_run_folder; *lock_fd >= 0 means it already is); prints the error. */
int play_make_run_folder(const play_options* o, char* out, size_t size, int* lock_fd);

/* The lock file inside a run folder: flock(2), exclusive, non-blocking. */
#define PLAY_LOCK_FILE ".tlod.lock"
/* Locks folder dir (which exists) into *lock_fd; CLI_FAILED with the error
 * printed when another process holds it: a second tlod play on one --out
 * fails at once instead of interleaving its files with the first's. */
int play_lock_run_folder(const char* dir, int* lock_fd);
/* Removes the lock file and releases the lock (lock_fd < 0: nothing). */
void play_unlock_run_folder(const char* dir, int lock_fd);

#endif
