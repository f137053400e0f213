/* tlod bench --peers -- tesslod side by side with OpenSubdiv (peers_*.c,
 * peers_osd.cpp): preprocessing, evaluation rates, accuracy, one process. */
#ifndef TLOD_TOOLS_BENCH_PEERS_H
#define TLOD_TOOLS_BENCH_PEERS_H

#include <stdio.h>

#include "bench_options.h"
#include "common/json_writer.h"

/* Runs the peers suite on o->peer_faces (0: 100k and 1M faces), writes a
 * "peers" object into json (NULL: none; the caller has an object open) and
 * one row per case into csv (may be NULL). Without OpenSubdiv built in it
 * says so, and how to get it, and answers CLI_FAILED. */
int bench_peers(const bench_options* o, json_writer* json, FILE* csv);

#endif
