/* tlod play --serve: what the play loop hands the server (the run's
 * settings, each frame's record: trace.json's own writers, so the live
 * records are the file's), and the end of the server. */
#define _POSIX_C_SOURCE 200809L /* open_memstream, nanosleep */
#include <microhttpd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "play_run.h"
#include "play_serve_internal.h"
#include "play_trace_format.h"

/* The writer's output on one line (its line breaks are layout only:
 * strings carry control characters escaped), malloc'd, *len bytes. */
typedef void (*json_piece)(json_writer* w, const play_trace* t);
static char* json_line(const play_trace* t, json_piece piece, size_t* len) {
  char* text = NULL;
  size_t size = 0;
  FILE* f = open_memstream(&text, &size);
  if (!f) return NULL;
  json_writer w;
  json_begin(&w, f);
  piece(&w, t);
  bool ok = json_end(&w);
  if (fclose(f) != 0 || !ok) {
    free(text);
    return NULL;
  }
  size_t n = 0;
  for (size_t i = 0; i < size; i++)
    if (text[i] != '\n')
      text[n++] = text[i];
    else
      while (i + 1 < size && text[i + 1] == ' ')
        i++;
  text[n] = '\0';
  *len = n;
  return text;
}

static void frame_piece(json_writer* w, const play_trace* t) { trace_json_frame(w, t, t->window_count - 1); }

static void run_piece(json_writer* w, const play_trace* t) {
  json_object_begin(w, NULL);
  json_string(w, "schema", PLAY_TRACE_SCHEMA);
  trace_json_settings(w, t);
  json_object_end(w);
}

/* The "run" event of t: /run.json's text after "data: ". */
static serve_record* run_event(const char* json, size_t len) {
  static const char head[] = "event: run\ndata: ";
  char* text = malloc(sizeof(head) + len + 2);
  if (!text) return NULL;
  snprintf(text, sizeof(head) + len + 2, "%s%s\n\n", head, json);
  serve_record* r = serve_record_new(SERVE_RUN, text, sizeof(head) - 1 + len + 2);
  free(text);
  return r;
}

void play_server_run(play_server* s, const play_trace* t) {
  if (!s) return;
  size_t len = 0;
  char* json = json_line(t, run_piece, &len);
  serve_record* r = json ? run_event(json, len) : NULL;
  if (!json || !r) { /* out of memory: the streams go on without this run's settings */
    free(json);
    free(r);
    return;
  }
  pthread_mutex_lock(&s->lock);
  free(s->run_json);
  s->run_json = json;
  s->run_json_len = len;
  serve_record_release(s->run);
  s->run = r;
  r->refs++; /* the server's own, for late streams */
  serve_publish(s, r);
  pthread_mutex_unlock(&s->lock);
}

/* Nothing is built while no client listens: a --serve without clients
 * costs the loop a lock per frame. */
void play_server_frame(play_server* s, const play_trace* t) {
  if (!s) return;
  pthread_mutex_lock(&s->lock);
  s->stats.frames++;
  uint32_t listeners = s->stream_count;
  pthread_mutex_unlock(&s->lock);
  if (!listeners) return;
  size_t len = 0;
  char* json = json_line(t, frame_piece, &len);
  serve_record* r = json ? serve_record_new(SERVE_FRAME, json, len) : NULL;
  free(json);
  pthread_mutex_lock(&s->lock);
  if (r)
    serve_publish(s, r);
  else
    for (uint32_t k = 0; k < s->stream_count; k++)
      s->streams[k]->dropped++, s->stats.dropped++;
  pthread_mutex_unlock(&s->lock);
}

void play_server_end(play_server* s, float linger_s) {
  if (!s) return;
  pthread_mutex_lock(&s->lock);
  s->ended = true;
  pthread_cond_broadcast(&s->wake);
  pthread_mutex_unlock(&s->lock);
  struct timespec tick = {0, 50 * 1000000L};
  for (double waited = 0.0; waited < linger_s && !play_interrupted; waited += 0.05)
    nanosleep(&tick, NULL);
}

void play_server_stop(play_server* s, play_serve_stats* stats) {
  if (!s) return;
  pthread_mutex_lock(&s->lock);
  s->stopping = true;
  pthread_cond_broadcast(&s->wake);
  pthread_mutex_unlock(&s->lock);
  MHD_stop_daemon(s->daemon); /* closes the connections and joins their threads: every stream is freed */
  if (stats) *stats = s->stats;
  serve_free(s);
}

void play_serve_stats_json(json_writer* w, const char* key, const play_serve_stats* st) {
  json_object_begin(w, key);
  json_string(w, "url", st->url);
  json_uint(w, "streams", st->streams);
  json_uint(w, "refused", st->refused);
  json_uint(w, "frames", st->frames);
  json_uint(w, "dropped", st->dropped);
  json_uint(w, "max_dropped_per_stream", st->max_dropped);
  json_object_end(w);
}
