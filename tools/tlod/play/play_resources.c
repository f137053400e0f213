/* tlod play -- resource use during a run, for soak tests (scripts/soak):
 * the process's peak and current resident memory, and with GL the objects
 * the context holds. Sampled after frame 1, 10, 100, ... and after the last:
 * a leak grows from one sample to the next. */
#include <stdio.h>
#include <string.h>

#include "common/strict_number.h"
#include "play_trace.h"

#if TLOD_HAS_GL
#include <GL/gl.h>
#include <GL/glext.h>
#endif

/* The kB figure of a "Name:   1234 kB" line of /proc/self/status, or 0. */
static uint64_t status_kib(const char* line, const char* name) {
  size_t n = strlen(name);
  if (strncmp(line, name, n)) return 0;
  const char* p = line + n + strspn(line + n, " \t");
  const char* end = NULL;
  int64_t v = 0;
  return number_parse_int(p, &end, 0, INT64_MAX, &v) == NUMBER_OK ? (uint64_t)v : 0;
}

static void read_memory(play_resources* r) {
  FILE* f = fopen("/proc/self/status", "r");
  if (!f) return; /* not Linux: left 0 (unknown) */
  char line[256];
  while (fgets(line, sizeof(line), f)) {
    uint64_t v;
    if ((v = status_kib(line, "VmHWM:"))) r->peak_rss_kib = v;
    if ((v = status_kib(line, "VmRSS:"))) r->rss_kib = v;
  }
  fclose(f);
}

#if TLOD_HAS_GL
/* GL names are small integers handed out from 1: counting the live ones
 * among the first few thousand sees every object a device of this size
 * makes (docs/play.md, "Soak"). */
enum { NAMES_SCANNED = 4096 };

static uint32_t count_live(GLboolean (*is)(GLuint)) {
  uint32_t n = 0;
  for (GLuint name = 1; name <= NAMES_SCANNED; name++)
    n += is(name) ? 1u : 0u;
  return n;
}

static void count_gl(play_resources* r) {
  r->gl = true;
  r->gl_buffers = count_live(glIsBuffer);
  r->gl_textures = count_live(glIsTexture);
  r->gl_renderbuffers = count_live(glIsRenderbuffer);
  r->gl_framebuffers = count_live(glIsFramebuffer);
  r->gl_vertex_arrays = count_live(glIsVertexArray);
  r->gl_programs = count_live(glIsProgram);
  r->gl_shaders = count_live(glIsShader);
  r->gl_queries = count_live(glIsQuery);
}
#else
static void count_gl(play_resources* r) { (void)r; }
#endif

void play_resources_sample(play_trace* t, bool gl) {
  if (t->sample_count == PLAY_MAX_SAMPLES) return;
  play_resources* r = &t->samples[t->sample_count++];
  memset(r, 0, sizeof(*r));
  r->frame = t->frame_count;
  read_memory(r);
  if (gl) count_gl(r);
}
