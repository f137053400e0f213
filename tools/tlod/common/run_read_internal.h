/* What the run reader's files share (run_read.c, run_read_dir.c). */
#ifndef TLOD_TOOLS_RUN_READ_INTERNAL_H
#define TLOD_TOOLS_RUN_READ_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "run_read.h"

/* Formats err; returns false. */
bool run_fail(char* err, size_t err_size, const char* fmt, ...) __attribute__((format(printf, 3, 4)));
/* malloc'd copy, NULL when out of memory. */
char* run_strdup(const char* s);
/* Reads DIR/objects.csv into r->object_counts, or sets r->object_counts_note
 * (never fails the run: the counts are optional). */
void run_read_object_counts(run* r);

#endif
