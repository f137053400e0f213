/* tlod play --serve: the per-stream queues and the event stream of
 * /events. The play loop publishes (serve_publish: a pointer into each
 * queue under the lock, never a wait on a client); each stream's own
 * connection thread turns its queue into text/event-stream events. */
#define _POSIX_C_SOURCE 200809L /* pthread_cond_timedwait's clock */
#include <microhttpd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "play_serve_internal.h"

/* An idle stream sends a comment this often: a closed client is noticed
 * (the write fails) and the thread ends. */
#define SERVE_KEEPALIVE_S 2

serve_record* serve_record_new(serve_kind kind, const char* text, size_t len) {
  serve_record* r = malloc(sizeof(*r) + len + 1);
  if (!r) return NULL;
  *r = (serve_record){.refs = 0, .kind = kind, .len = len};
  memcpy(r->text, text, len);
  r->text[len] = '\0';
  return r;
}

void serve_record_release(serve_record* r) {
  if (r && --r->refs == 0) free(r);
}

/* r at the end of q, or dropped (frames only) when q is full. */
static void stream_push(serve_stream* q, serve_record* r) {
  bool frame = r->kind == SERVE_FRAME;
  if (frame && (q->frames == PLAY_SERVE_QUEUE_FRAMES || q->bytes + r->len > PLAY_SERVE_QUEUE_BYTES)) {
    q->dropped++;
    q->s->stats.dropped++;
    return;
  }
  if (q->count == SERVE_RING) return; /* only run events past the frames: cannot happen (PLAY_MAX_MODES) */
  q->ring[(q->head + q->count++) % SERVE_RING] = r;
  r->refs++;
  q->bytes += r->len;
  q->frames += frame;
}

void serve_publish(play_server* s, serve_record* r) {
  r->refs++; /* held while handing out */
  for (uint32_t k = 0; k < s->stream_count; k++)
    stream_push(s->streams[k], r);
  pthread_cond_broadcast(&s->wake);
  serve_record_release(r);
}

serve_stream* serve_stream_open(play_server* s) {
  serve_stream* q = calloc(1, sizeof(*q));
  pthread_mutex_lock(&s->lock);
  if (!q || s->stream_count == PLAY_SERVE_MAX_STREAMS || s->stopping) {
    s->stats.refused += q != NULL;
    pthread_mutex_unlock(&s->lock);
    free(q);
    return NULL;
  }
  q->s = s;
  s->streams[s->stream_count++] = q;
  s->stats.streams++;
  if (s->run) stream_push(q, s->run); /* a late client learns the settings first */
  pthread_mutex_unlock(&s->lock);
  return q;
}

void serve_stream_close(void* cls) {
  serve_stream* q = cls;
  play_server* s = q->s;
  pthread_mutex_lock(&s->lock);
  for (uint32_t k = 0; k < s->stream_count; k++)
    if (s->streams[k] == q) s->streams[k] = s->streams[--s->stream_count];
  if (q->dropped > s->stats.max_dropped) s->stats.max_dropped = q->dropped;
  for (; q->count; q->count--, q->head = (q->head + 1) % SERVE_RING)
    serve_record_release(q->ring[q->head]);
  pthread_mutex_unlock(&s->lock);
  free(q->out);
  free(q);
}

/* Room for n more bytes in the event being built. */
static bool out_reserve(serve_stream* q, size_t n) {
  if (q->out_len + n <= q->out_cap) return true;
  size_t cap = q->out_len + n + 256;
  char* p = realloc(q->out, cap);
  if (!p) return false;
  q->out = p;
  q->out_cap = cap;
  return true;
}

static bool out_add(serve_stream* q, const char* text, size_t n) {
  if (!out_reserve(q, n)) return false;
  memcpy(q->out + q->out_len, text, n);
  q->out_len += n;
  return true;
}

/* A frame's event: its record with "dropped" (this stream's count so far) first. */
static bool out_frame(serve_stream* q, const serve_record* r) {
  char head[64];
  int n = snprintf(head, sizeof(head), "data: {\"dropped\":%llu,", (unsigned long long)q->dropped);
  return out_add(q, head, (size_t)n) && out_add(q, r->text + 1, r->len - 1) && out_add(q, "\n\n", 2);
}

/* The next event into q->out: the queue's head, else "end" when due; false: nothing to send. */
static bool next_event(serve_stream* q) {
  q->out_len = q->out_off = 0;
  if (q->count) {
    serve_record* r = q->ring[q->head];
    q->head = (q->head + 1) % SERVE_RING;
    q->count--;
    q->bytes -= r->len;
    q->frames -= r->kind == SERVE_FRAME;
    bool ok = r->kind == SERVE_FRAME ? out_frame(q, r) : out_add(q, r->text, r->len);
    q->sent += ok && r->kind == SERVE_FRAME;
    serve_record_release(r);
    return ok;
  }
  if (!q->s->ended || q->end_sent) return false;
  char end[64];
  int n = snprintf(end, sizeof(end), "event: end\ndata: {\"dropped\":%llu}\n\n", (unsigned long long)q->dropped);
  q->end_sent = true;
  return out_add(q, end, (size_t)n);
}

/* Waits (under the lock) for an event; false on a quiet interval (send a
 * keep-alive) or when the server stops. */
static bool wait_event(serve_stream* q) {
  struct timespec until;
  clock_gettime(CLOCK_REALTIME, &until);
  until.tv_sec += SERVE_KEEPALIVE_S;
  while (!q->s->stopping) {
    if (next_event(q)) return true;
    if (pthread_cond_timedwait(&q->s->wake, &q->s->lock, &until)) return false;
  }
  return false;
}

/* MHD asks for the next bytes of the stream (on this stream's own thread:
 * waiting here holds up nobody else). */
ssize_t serve_stream_read(void* cls, uint64_t pos, char* buf, size_t max) {
  (void)pos;
  serve_stream* q = cls;
  play_server* s = q->s;
  pthread_mutex_lock(&s->lock);
  if (q->out_off == q->out_len && !wait_event(q)) {
    bool stop = s->stopping;
    pthread_mutex_unlock(&s->lock);
    if (stop) return MHD_CONTENT_READER_END_OF_STREAM;
    static const char keepalive[] = ": keep-alive\n\n";
    size_t n = sizeof(keepalive) - 1 < max ? sizeof(keepalive) - 1 : max;
    memcpy(buf, keepalive, n);
    return (ssize_t)n;
  }
  size_t n = q->out_len - q->out_off < max ? q->out_len - q->out_off : max;
  memcpy(buf, q->out + q->out_off, n);
  q->out_off += n;
  pthread_mutex_unlock(&s->lock);
  return (ssize_t)n;
}
