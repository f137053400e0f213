/* tlod play --serve: what the server's files share (play_serve.c: the
 * daemon and its requests; play_serve_addr.c: --serve and the socket;
 * play_serve_publish.c: what the play loop hands over; play_serve_stream.c: the per-stream queues and
 * the event stream; play_serve_page.c: the page). */
#ifndef TLOD_TOOLS_PLAY_SERVE_INTERNAL_H
#define TLOD_TOOLS_PLAY_SERVE_INTERNAL_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h> /* ssize_t */

#include "play_serve.h"

/* A record shared by the queues holding it: refs counted under the lock. */
typedef enum serve_kind { SERVE_FRAME, SERVE_RUN } serve_kind;
typedef struct serve_record {
  uint32_t refs;
  serve_kind kind;
  size_t len;
  char text[]; /* FRAME: the record, one line of JSON; RUN: the whole event */
} serve_record;

#define SERVE_RING (PLAY_SERVE_QUEUE_FRAMES + PLAY_MAX_MODES) /* run events always fit */

typedef struct serve_stream {
  play_server* s;
  serve_record* ring[SERVE_RING];
  uint32_t head, count, frames;
  size_t bytes;
  uint64_t dropped, sent;
  char* out; /* the event being sent: out_off of out_len bytes gone */
  size_t out_len, out_off, out_cap;
  bool end_sent;
} serve_stream;

struct play_server {
  struct MHD_Daemon* daemon;
  pthread_mutex_t lock;
  pthread_cond_t wake;
  bool ended, stopping; /* "end" due; connections closing */
  serve_stream* streams[PLAY_SERVE_MAX_STREAMS];
  uint32_t stream_count;
  serve_record* run; /* the current mode's "run" event; NULL before the first */
  char* run_json;    /* /run.json */
  size_t run_json_len;
  char* page;
  size_t page_len;
  play_serve_stats stats;
};

/* A stream for a new /events client: NULL when PLAY_SERVE_MAX_STREAMS are open
 * (counted as refused) or out of memory. */
serve_stream* serve_stream_open(play_server* s);
/* MHD's content reader and its free callback for a stream. */
ssize_t serve_stream_read(void* cls, uint64_t pos, char* buf, size_t max);
void serve_stream_close(void* cls);
/* A record of len bytes (text copied, refs 0); NULL when out of memory. */
serve_record* serve_record_new(serve_kind kind, const char* text, size_t len);
void serve_record_release(serve_record* r);
/* Hands r to every stream (under the lock): a full queue drops a frame. */
void serve_publish(play_server* s, serve_record* r);
/* A listening socket on a (text: as given, for errors) and its URL; -1 with
 * the error printed. */
int serve_listen(const play_serve_addr* a, const char* text, char* url, size_t url_size);
/* Frees s and what it holds (the daemon stopped or never started). */
void serve_free(play_server* s);
/* The page served at / (malloc'd, *len bytes); NULL when out of memory. */
char* serve_page(size_t* len);

#endif
