/* tlod bench --peers -- tesslod side by side with OpenSubdiv (the library
 * users would pick instead), both in one process on the same meshes
 * (peers_*.c/.cpp, only when the build has OpenSubdiv: TLOD_HAS_OPENSUBDIV).
 * Without it, tlod bench --peers says so and how to install it, and fails. */
#ifndef TLOD_TOOLS_BENCH_PEERS_H
#define TLOD_TOOLS_BENCH_PEERS_H

#include <stdio.h>

#include "bench_options.h"
#include "common/json_writer.h"

/* Runs the peers suite on o (o->peer_faces: the face count of its meshes,
 * 0 for the default sizes), printing its figures; json (NULL without
 * --json) gets them as the value of the key "peers", written by this
 * function (json_object_begin(json, "peers") ... end); csv (may be NULL)
 * one row per case. CLI_OK, or an error code with the error printed. */
int bench_peers(const bench_options* o, json_writer* json, FILE* csv);

#endif
