/* tlod_atomic_file.h -- every file the tools write goes through here: the
 * bytes go to a unique temporary NAME.tmp.XXXXXX (mkstemp) in the target's
 * folder, and only a complete file is renamed over NAME. Readers never see
 * half a file, two writers of one folder never share a temporary, and a
 * failure leaves nothing behind (the temporary is unlinked).
 *
 * STEP BY STEP
 *   tlod_atomic_file a;
 *   if (!tlod_atomic_file_begin(&a, "out/trace.json", err, sizeof err)) fail(err);
 *   fprintf(a.file, ...);                                // any stdio writes
 *   if (!tlod_atomic_file_end(&a, true, err, sizeof err)) fail(err);
 * or, with a function that writes the contents, tlod_atomic_file_write().
 *
 * ERRORS
 *   begin refuses a target that exists and is not a regular file (or a link
 *   to one): "cannot write 'out': Is a directory", "cannot write
 *   '/dev/full': not a regular file" -- the rename would replace it.
 *   Every write error is sticky in the FILE (ferror) and is checked at the
 *   end together with fflush, fsync (when asked) and fclose; the message
 *   names the file and the errno text: "cannot write 'out/trace.json': No
 *   space left on device".
 *
 * THREADING
 *   Different files may be written from different threads. begin reads the
 *   process umask (umask() set and reset) to give the file the mode fopen
 *   would: do not change the umask concurrently. */
#ifndef TLOD_TOOLS_ATOMIC_FILE_H
#define TLOD_TOOLS_ATOMIC_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tlod_atomic_file {
  FILE* file;       /* write here between begin and end */
  bool sync;        /* set before end: fsync the file before the rename */
  const char* path; /* the final name (the caller's string) */
  char* tmp;        /* the temporary's name (owned) */
} tlod_atomic_file;

/* Creates the temporary for path. False with one line in error (and a
 * zeroed a) when it cannot be created. */
bool tlod_atomic_file_begin(tlod_atomic_file* a, const char* path, char* error, size_t error_size);

/* keep true: checks every write, flushes (fsync if a->sync), closes and
 * renames over the final name; false with one line in error on any failure.
 * keep false (the caller's own failure): discards the temporary and returns
 * false, leaving error as it is. Either way the temporary is gone after a
 * false return and a is closed. */
bool tlod_atomic_file_end(tlod_atomic_file* a, bool keep, char* error, size_t error_size);

/* Writes the contents: fill returns false on its own failure. begin, fill, end. */
typedef bool (*tlod_atomic_file_fill)(FILE* f, const void* data);
bool tlod_atomic_file_write(const char* path, tlod_atomic_file_fill fill, const void* data, char* error,
                            size_t error_size);

#ifdef __cplusplus
}
#endif
#endif
