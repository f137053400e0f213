/* tlod play --serve [ADDR:]PORT: the live dashboard. An HTTP server
 * (libmicrohttpd, a thread per connection) serves the dashboard page at /,
 * the run's settings at /run.json and every frame's trace record as a
 * server-sent event at /events (docs/play.md "Live dashboard").
 *
 * The play loop only hands records over: each stream has its own bounded
 * queue (PLAY_SERVE_QUEUE_FRAMES records, PLAY_SERVE_QUEUE_BYTES bytes);
 * a full queue drops the frame for that stream and counts it (the next
 * event's "dropped"), so a slow or stuck client never holds the loop up.
 * Read-only: GET and HEAD; other methods 405, unknown paths 404, a request
 * with a body or a malformed one 400, more than PLAY_SERVE_MAX_STREAMS
 * streams 503. Every function takes a NULL server (no --serve) and does
 * nothing then. */
#ifndef TLOD_TOOLS_PLAY_SERVE_H
#define TLOD_TOOLS_PLAY_SERVE_H

#include <stdint.h>

#include "common/json_writer.h"
#include "play_options.h"
#include "play_trace.h"

#define PLAY_SERVE_MAX_STREAMS 16u
#define PLAY_SERVE_MAX_CONNECTIONS 32u /* streams, page loads and the 503s; beyond: closed at once */
#define PLAY_SERVE_QUEUE_FRAMES 256u
#define PLAY_SERVE_QUEUE_BYTES (1u << 20)
#define PLAY_SERVE_DEFAULT_ADDR "127.0.0.1"

/* A parsed --serve: IPv4 address (host order) and port (0: any free one). */
typedef struct play_serve_addr {
  uint32_t ipv4;
  uint16_t port;
} play_serve_addr;

/* What the server did, for summary.json's "serve" (play_serve_stats_json). */
typedef struct play_serve_stats {
  char url[48];              /* "http://127.0.0.1:8080/" */
  uint32_t streams, refused; /* /events clients served, turned away (503) */
  uint64_t frames;           /* records handed to the server */
  uint64_t dropped;          /* frames dropped over all streams */
  uint64_t max_dropped;      /* by the stream that dropped most */
} play_serve_stats;

typedef struct play_server play_server;

/* "[ADDR:]PORT": NULL, or what is wrong with text. ADDR: an IPv4 address
 * or "localhost" (default 127.0.0.1); PORT 0..65535. */
const char* play_serve_parse(const char* text, play_serve_addr* a);
/* --serve ADDR:PORT and --serve-linger S at argv[*i]: CLI_OK, CLI_USAGE or CLI_NOT_MINE. */
int play_serve_option(int argc, char** argv, int* i, play_options* o);

/* Listens on o->serve and starts the server threads; prints the URL on
 * stderr. CLI_OK with *out (NULL when o->serve is NULL), or CLI_FAILED with
 * one error line ("--serve 127.0.0.1:8080: cannot listen: Address already
 * in use"). */
int play_server_start(const play_options* o, play_server** out);
/* A mode starts playing into t: /run.json becomes its settings and every
 * stream gets an "run" event with them. */
void play_server_run(play_server* s, const play_trace* t);
/* The frame just committed to t (its window's last): one event per stream. */
void play_server_frame(play_server* s, const play_trace* t);
/* Playing is over: every stream gets an "end" event; then, unless
 * interrupted, waits linger_s seconds (Ctrl-C stops the wait) so pages can
 * read what is queued. */
void play_server_end(play_server* s, float linger_s);
/* Closes every connection, joins the threads and frees everything; the
 * counts into *stats (may be NULL). */
void play_server_stop(play_server* s, play_serve_stats* stats);
/* summary.json's "serve" object. */
void play_serve_stats_json(json_writer* w, const char* key, const play_serve_stats* st);

#endif
