/* tlod play --serve: the options and the listening socket. */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "cli.h"
#include "common/strict_number.h"
#include "play_serve_internal.h"

const char* play_serve_parse(const char* text, play_serve_addr* a) {
  const char* colon = strrchr(text, ':');
  const char* port = colon ? colon + 1 : text;
  char host[64];
  snprintf(host, sizeof(host), "%.*s", colon ? (int)(colon - text) : 0, text);
  if (!colon || !strcmp(host, "localhost")) snprintf(host, sizeof(host), "%s", PLAY_SERVE_DEFAULT_ADDR);
  uint32_t p = 0;
  if (!*port || number_parse_u32(port, NULL, 0, 65535, &p) != NUMBER_OK) return "expected [ADDR:]PORT, PORT 0..65535";
  struct in_addr in;
  if ((colon && (size_t)(colon - text) >= sizeof(host)) || inet_pton(AF_INET, host, &in) != 1)
    return "ADDR must be an IPv4 address or localhost";
  a->ipv4 = ntohl(in.s_addr);
  a->port = (uint16_t)p;
  return NULL;
}

int play_serve_option(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  if (!strcmp(a, "--serve-linger"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 0.0, 3600.0, &o->serve_linger));
  if (strcmp(a, "--serve")) return CLI_NOT_MINE;
  if (!(o->serve = cli_value(argc, argv, i))) return CLI_USAGE;
  play_serve_addr addr;
  const char* problem = play_serve_parse(o->serve, &addr);
  return problem ? cli_error(CLI_USAGE, "--serve: %s: %s", o->serve, problem) : CLI_OK;
}

/* The port the kernel chose for port 0. */
static unsigned bound_port(int fd) {
  struct sockaddr_in sa;
  socklen_t n = sizeof(sa);
  return getsockname(fd, (struct sockaddr*)&sa, &n) == 0 ? ntohs(sa.sin_port) : 0;
}

int serve_listen(const play_serve_addr* a, const char* text, char* url, size_t url_size) {
  int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0), on = 1;
  if (fd < 0) return cli_error(CLI_FAILED, "--serve %s: cannot make a socket: %s", text, strerror(errno)), -1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof(on)); /* a restart right after a run may bind */
  struct sockaddr_in sa = {.sin_family = AF_INET, .sin_port = htons(a->port), .sin_addr.s_addr = htonl(a->ipv4)};
  if (bind(fd, (struct sockaddr*)&sa, sizeof(sa)) != 0 || listen(fd, 16) != 0) {
    int e = errno;
    close(fd);
    return cli_error(CLI_FAILED, "--serve %s: cannot listen: %s", text, strerror(e)), -1;
  }
  char host[INET_ADDRSTRLEN];
  inet_ntop(AF_INET, &sa.sin_addr, host, sizeof(host));
  snprintf(url, url_size, "http://%s:%u/", host, bound_port(fd));
  return fd;
}
