/* tlod play --serve: the HTTP server (libmicrohttpd, a thread per
 * connection, at most PLAY_SERVE_MAX_CONNECTIONS) and its requests. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <microhttpd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "cli.h"
#include "play_serve_internal.h"

/* A stream's socket send buffer: what the kernel holds for a stuck client
 * is bounded too (the kernel doubles it). */
#define SERVE_SNDBUF 32768
/* Idle connections (a client that sends half a request) are closed after this. */
#define SERVE_IDLE_S 30

/* The headers every answer carries: nothing cached, nothing sniffed, the
 * page may fetch only from this server (its charting library is inlined). */
static void common_headers(struct MHD_Response* r, const char* type) {
  MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, type);
  MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
  MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
  MHD_add_response_header(r, "Content-Security-Policy",
                          "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                          "img-src data:; connect-src 'self'");
}

static enum MHD_Result answer(struct MHD_Connection* c, unsigned status, const char* type, const char* body, size_t len,
                              enum MHD_ResponseMemoryMode mode) {
  struct MHD_Response* r = MHD_create_response_from_buffer(len, (void*)body, mode);
  if (!r) return MHD_NO;
  common_headers(r, type);
  if (status == MHD_HTTP_METHOD_NOT_ALLOWED) MHD_add_response_header(r, MHD_HTTP_HEADER_ALLOW, "GET, HEAD");
  enum MHD_Result ok = MHD_queue_response(c, status, r);
  MHD_destroy_response(r);
  return ok;
}

static enum MHD_Result error(struct MHD_Connection* c, unsigned status, const char* text) {
  return answer(c, status, "text/plain; charset=utf-8", text, strlen(text), MHD_RESPMEM_PERSISTENT);
}

/* /events: a stream of this client's own queue. */
static enum MHD_Result events(play_server* s, struct MHD_Connection* c) {
  serve_stream* q = serve_stream_open(s);
  if (!q) return error(c, MHD_HTTP_SERVICE_UNAVAILABLE, "503 too many event streams\n");
  struct MHD_Response* r =
      MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 16384, serve_stream_read, q, serve_stream_close);
  if (!r) {
    serve_stream_close(q);
    return MHD_NO;
  }
  common_headers(r, "text/event-stream");
  const union MHD_ConnectionInfo* info = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
  int size = SERVE_SNDBUF;
  if (info) setsockopt(info->connect_fd, SOL_SOCKET, SO_SNDBUF, &size, sizeof(size));
  enum MHD_Result ok = MHD_queue_response(c, MHD_HTTP_OK, r);
  MHD_destroy_response(r);
  return ok;
}

/* /run.json: a copy taken under the lock (a new mode replaces it). */
static enum MHD_Result run_json(play_server* s, struct MHD_Connection* c) {
  pthread_mutex_lock(&s->lock);
  static const char starting[] = "{\"status\":\"starting\"}"; /* before the first mode */
  const char* text = s->run_json ? s->run_json : starting;
  size_t len = s->run_json ? s->run_json_len : sizeof(starting) - 1;
  char* body = malloc(len + 1);
  if (body) memcpy(body, text, len);
  pthread_mutex_unlock(&s->lock);
  if (!body) return MHD_NO;
  return answer(c, MHD_HTTP_OK, "application/json", body, len, MHD_RESPMEM_MUST_FREE);
}

static enum MHD_Result route(play_server* s, struct MHD_Connection* c, const char* url, bool head) {
  if (!strcmp(url, "/") || !strcmp(url, "/index.html"))
    return answer(c, MHD_HTTP_OK, "text/html; charset=utf-8", s->page, s->page_len, MHD_RESPMEM_PERSISTENT);
  if (!strcmp(url, "/run.json")) return run_json(s, c);
  if (!strcmp(url, "/events"))
    return head ? answer(c, MHD_HTTP_OK, "text/event-stream", "", 0, MHD_RESPMEM_PERSISTENT) : events(s, c);
  return error(c, MHD_HTTP_NOT_FOUND, "404 not found\n");
}

/* MHD calls this once with the headers, then per piece of body, then once
 * more: a body is refused (read-only), as are an HTTP/1.1 request without
 * Host (RFC 9112 3.2) and a target that is not a path; then the answer. */
static enum MHD_Result on_request(void* cls, struct MHD_Connection* c, const char* url, const char* method,
                                  const char* version, const char* upload, size_t* upload_size, void** state) {
  (void)upload;
  static int seen, with_body;
  if (!*state) {
    *state = &seen;
    return MHD_YES;
  }
  if (*upload_size) {
    *upload_size = 0;
    *state = &with_body;
    return MHD_YES;
  }
  bool get = !strcmp(method, MHD_HTTP_METHOD_GET), head = !strcmp(method, MHD_HTTP_METHOD_HEAD);
  if (!get && !head) return error(c, MHD_HTTP_METHOD_NOT_ALLOWED, "405 read-only: GET and HEAD only\n");
  bool no_host = !strcmp(version, MHD_HTTP_VERSION_1_1) && !MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host");
  if (*state == &with_body || url[0] != '/' || no_host) return error(c, MHD_HTTP_BAD_REQUEST, "400 bad request\n");
  return route(cls, c, url, head);
}

static struct MHD_Daemon* start_daemon(play_server* s, int fd) {
  /* No MHD_USE_ERROR_LOG: a bad request is answered, not logged on the play's stderr. */
  unsigned flags = MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD;
  return MHD_start_daemon(flags, 0, NULL, NULL, on_request, s, MHD_OPTION_LISTEN_SOCKET, fd,
                          MHD_OPTION_CONNECTION_LIMIT, (unsigned)PLAY_SERVE_MAX_CONNECTIONS,
                          MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)SERVE_IDLE_S, MHD_OPTION_CONNECTION_MEMORY_LIMIT,
                          (size_t)65536, MHD_OPTION_END);
}

void serve_free(play_server* s) {
  serve_record_release(s->run);
  free(s->run_json);
  free(s->page);
  pthread_cond_destroy(&s->wake);
  pthread_mutex_destroy(&s->lock);
  free(s);
}

int play_server_start(const play_options* o, play_server** out) {
  *out = NULL;
  if (!o->serve) return CLI_OK;
  play_serve_addr a;
  play_serve_parse(o->serve, &a); /* checked by play_parse */
  play_server* s = calloc(1, sizeof(*s));
  if (!s) return cli_error(CLI_FAILED, "--serve %s: out of memory", o->serve);
  pthread_mutex_init(&s->lock, NULL);
  pthread_cond_init(&s->wake, NULL);
  int fd = serve_listen(&a, o->serve, s->stats.url, sizeof(s->stats.url));
  if (fd < 0 || !(s->page = serve_page(&s->page_len)) || !(s->daemon = start_daemon(s, fd))) {
    int rc = fd < 0 ? CLI_FAILED : cli_error(CLI_FAILED, "--serve %s: cannot start the server", o->serve);
    if (fd >= 0) close(fd);
    serve_free(s);
    return rc;
  }
  fprintf(stderr, "tlod: live dashboard at %s\n", s->stats.url);
  *out = s;
  return CLI_OK;
}
