/* fuzz_common.h -- what every fuzz target shares (fuzz/, docs/fuzzing.md): the input as a
 * file for readers that take a path, and the contract checks whose failure is a finding.
 *
 * A target is a libFuzzer entry point, LLVMFuzzerTestOneInput(data, size). The same source
 * links either with libFuzzer (TLOD_FUZZ, preset "fuzz") or with replay_main.c (the ctest
 * replay of tests/data/fuzz in a normal build), so a saved crash replays through exactly
 * the code that found it.
 *
 * A finding is a crash, a sanitizer report, a leak, a timeout or memory past libFuzzer's
 * limits (fuzz/run sets them) -- or a broken contract that fuzz_check() turns into abort():
 * a failure without a message naming the file, a result code the header does not list, or a
 * "successful" result whose arrays do not hold what the header promises. */
#ifndef TLOD_FUZZ_COMMON_H
#define TLOD_FUZZ_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "tesslod/core.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* Writes data to <private temp folder>/input<ext> and returns that path (owned here, valid
 * until the next call). The folder is made once per process with mkdtemp, in /dev/shm when
 * it exists (no disk I/O per input), else $TMPDIR or /tmp, and removed at exit. The file is
 * alone in its folder, so relative references in it (glTF buffers, OBJ mtllib) find nothing
 * but the input itself. Aborts if the file cannot be written (a broken harness, not a
 * finding in the reader). */
const char* fuzz_input_file(const char* ext, const uint8_t* data, size_t size);

/* abort()s with "fuzz_check: <what>" on stderr when ok is false (also under NDEBUG). */
void fuzz_check(int ok, const char* what);

/* The error contract of the readers: a failure leaves a message that starts with
 * "<file name>: " (file name without folders) and says more than that. */
void fuzz_check_error(const char* error, const char* file_name);

/* The file name (no folders) of a path. */
const char* fuzz_base_name(const char* path);

#endif
