/* tlod play -- plays a scene along a camera path with a fixed time step and
 * records per-frame scheduler and backend timings (docs/play.md). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "camera.h"
#include "camera_path.h"
#include "cli.h"
#include "commands.h"
#include "play_trace.h"
#include "tesslod/backend.h"
#include "tlod_import.h"

#if TLOD_HAS_GL
#include "tlod_platform.h"

#include <GL/gl.h>
#if defined(__SANITIZE_ADDRESS__)
#endif
#else
typedef struct tlod_platform tlod_platform;
#endif

#define PLAY_MAX_MODES 8
#define PLAY_MAX_OBJECTS 4
#define PLAY_MAX_FRAMES 1000000u
#define PLAY_PATH_MAX 1024 /* the run folder's name, and then some */
#define PLAY_DEFAULT_FRAMES_NOTE "the path's length at --fps (orbit: 240)"

typedef enum mode_kind { MODE_ADAPTIVE, MODE_UNIFORM, MODE_FLAT } mode_kind;

typedef struct play_mode {
  mode_kind kind;
  uint32_t level; /* uniform */
  char name[24];  /* "adaptive", "uniform:3", "flat" */
  char dir[24];   /* "adaptive", "uniform-3", "flat" */
} play_mode;

typedef struct play_options {
  const char* scene;   /* NULL: the built-in demo scene */
  const char* backend; /* NULL: gl when a context can be made, else cpu */
  play_mode modes[PLAY_MAX_MODES];
  uint32_t mode_count;
  bool compare, mode_given;
  tlod_surface_type surface;
  float epsilon;
  tlod_lod_policy policy;
  uint32_t max_level;
  uint32_t width, height;
  uint32_t frames; /* 0: from --duration or the path */
  float duration;  /* 0: not given */
  float fps;
  const char* path;
  bool loop;
  uint32_t screenshot_every;
  bool window;
  const char* out;
  bool quiet;
} play_options;

typedef struct play_object {
  play_object_info info;
  cli_mesh in;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_scheduler* scheduler;
  tlod_backend* backend;
} play_object;

typedef struct play_scene {
  char name[256];
  tlod_context* ctx;
  play_object objects[PLAY_MAX_OBJECTS];
  play_object_info infos[PLAY_MAX_OBJECTS];
  uint32_t count;
  tlod_patterns* patterns;
  float bmin[3], bmax[3];
} play_scene;

static const char* const surface_names[] = {"phong", "pn", NULL};
static const char* const policy_names[] = {"error", "silhouette", "hybrid", NULL};
static const char* const backend_names[] = {"cpu", "gl", "vulkan", NULL};

/* Set by the SIGINT handler, read between frames; nothing else happens in the handler. */
static volatile sig_atomic_t g_interrupted = 0;

static void on_sigint(int sig) {
  (void)sig;
  g_interrupted = 1;
}

void play_usage(FILE* f) {
  fprintf(
      f,
      "usage: tlod play [SCENE] [options]\n"
      "Plays SCENE along a camera path with a fixed time step and records per-frame timings.\n"
      "  SCENE               .gltf .glb .obj .ply file, a built-in mesh (%s), or nothing /\n"
      "                      demo:scene for the built-in demo scene (the VTK cow beside a creased cylinder)\n"
      "  --backend B         gl (default when a GL context can be made, else cpu) | cpu | vulkan\n"
      "  --mode M            adaptive (default) | uniform:L (every visible patch at level L, 0..%d) | flat (level 0)\n"
      "  --compare M,M[,..]  play the same path once per mode (output per mode in subfolders)\n"
      "  --surface S         phong (default) | pn (splits quads into triangles)\n"
      "  --epsilon PX        adaptive: screen-space error bound in pixels (default 0.5)\n"
      "  --policy P          adaptive: error | silhouette | hybrid (default hybrid)\n"
      "  --max-level L       adaptive: finest level, 1..%d (default 6)\n"
      "  --size WxH          viewport in pixels (default 1280x720)\n"
      "  --path P            orbit (default) | flyby | zoom | FILE.json (keyframes, see docs/play.md)\n"
      "                      | gltf[:N] (camera N of the glTF scene, with its animation)\n"
      "  --frames N          frames to play (default: " PLAY_DEFAULT_FRAMES_NOTE ")\n"
      "  --duration S        seconds of path time to play (frames = S * fps); not with --frames\n"
      "  --fps F             fixed time step 1/F s per frame (default 60): runs are repeatable\n"
      "  --loop              start the path over at its end (default: hold the last keyframe)\n"
      "  --screenshot-every N  gl: write screenshots/frame_NNNNN.png every N frames (from frame 0)\n"
      "  --window            draw into a GLFW window (needs DISPLAY) instead of headless EGL\n"
      "  --out DIR           run folder (default runs/YYYYmmdd-HHMMSS)\n"
      "  -q, --quiet         no progress bar and no summary\n"
      "Writes trace.json, trace.csv, chrome_trace.json, summary.json and summary.txt into the run folder.\n"
      "Ctrl-C stops after the current frame, writes what was played and exits with 130.\n",
      cli_demo_names(), TLOD_MAX_LEVEL, TLOD_MAX_LEVEL);
}

/* ---- options ------------------------------------------------------------- */

static bool parse_mode(const char* text, play_mode* m) {
  memset(m, 0, sizeof(*m));
  char tail;
  unsigned level = 0;
  if (!strcmp(text, "adaptive")) {
    m->kind = MODE_ADAPTIVE;
    snprintf(m->name, sizeof(m->name), "adaptive");
  } else if (!strcmp(text, "flat")) {
    m->kind = MODE_FLAT;
    snprintf(m->name, sizeof(m->name), "flat");
  } else if (!strncmp(text, "uniform:", 8) && text[8] >= '0' && text[8] <= '9' &&
             sscanf(text + 8, "%u%c", &level, &tail) == 1 && level <= TLOD_MAX_LEVEL) {
    m->kind = MODE_UNIFORM;
    m->level = level;
    snprintf(m->name, sizeof(m->name), "uniform:%u", level);
  } else {
    return false;
  }
  snprintf(m->dir, sizeof(m->dir), "%s", m->name);
  char* colon = strchr(m->dir, ':');
  if (colon) *colon = '-';
  return true;
}

static int mode_error(const char* option, const char* text) {
  return cli_error(CLI_USAGE, "%s: expected adaptive, uniform:L (L = 0..%d) or flat, got '%s'", option, TLOD_MAX_LEVEL,
                   text);
}

static int parse_compare(const char* text, play_options* o) {
  char buf[256];
  snprintf(buf, sizeof(buf), "%s", text);
  o->mode_count = 0;
  for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    if (o->mode_count == PLAY_MAX_MODES) return cli_error(CLI_USAGE, "--compare: at most %d modes", PLAY_MAX_MODES);
    play_mode* m = &o->modes[o->mode_count];
    if (!parse_mode(tok, m)) return mode_error("--compare", tok);
    for (uint32_t k = 0; k < o->mode_count; k++)
      if (!strcmp(o->modes[k].name, m->name)) return cli_error(CLI_USAGE, "--compare: mode '%s' given twice", m->name);
    o->mode_count++;
  }
  if (o->mode_count < 2)
    return cli_error(CLI_USAGE, "--compare: expected two or more modes separated by commas, got '%s'", text);
  return CLI_OK;
}

static bool parse_size(const char* v, uint32_t* w, uint32_t* h) {
  char tail;
  if (!v || strspn(v, "0123456789x") != strlen(v) || sscanf(v, "%ux%u%c", w, h, &tail) != 2) return false;
  return *w >= 1 && *h >= 1 && *w <= 16384 && *h <= 16384;
}

static int parse(int argc, char** argv, play_options* o) {
  *o = (play_options){.surface = TLOD_SURFACE_PHONG,
                      .epsilon = 0.5f,
                      .policy = TLOD_POLICY_HYBRID,
                      .max_level = 6,
                      .width = 1280,
                      .height = 720,
                      .fps = 60.0f,
                      .path = "orbit"};
  parse_mode("adaptive", &o->modes[0]);
  o->mode_count = 1;
  for (int i = 0; i < argc; i++) {
    const char* a = argv[i];
    const char* v = NULL;
    int e;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      play_usage(stdout);
      exit(0);
    } else if (!strcmp(a, "--backend")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, backend_names)) < 0) return CLI_USAGE;
      o->backend = backend_names[e];
    } else if (!strcmp(a, "--mode")) {
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (!parse_mode(v, &o->modes[0])) return mode_error(a, v);
      o->mode_given = true;
    } else if (!strcmp(a, "--compare")) {
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      int rc = parse_compare(v, o);
      if (rc != CLI_OK) return rc;
      o->compare = true;
    } else if (!strcmp(a, "--surface")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, surface_names)) < 0) return CLI_USAGE;
      o->surface = e == 0 ? TLOD_SURFACE_PHONG : TLOD_SURFACE_PN;
    } else if (!strcmp(a, "--epsilon")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 1e-6, 1e9, &o->epsilon)) return CLI_USAGE;
    } else if (!strcmp(a, "--policy")) {
      if (!(v = cli_value(argc, argv, &i)) || (e = cli_parse_enum(a, v, policy_names)) < 0) return CLI_USAGE;
      o->policy = (tlod_lod_policy)(TLOD_POLICY_ERROR + e);
    } else if (!strcmp(a, "--max-level")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, TLOD_MAX_LEVEL, &o->max_level)) return CLI_USAGE;
    } else if (!strcmp(a, "--size")) {
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (!parse_size(v, &o->width, &o->height))
        return cli_error(CLI_USAGE, "--size: expected WxH with W and H in 1..16384, got '%s'", v);
    } else if (!strcmp(a, "--frames")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, PLAY_MAX_FRAMES, &o->frames)) return CLI_USAGE;
    } else if (!strcmp(a, "--duration")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 1e-3, 1e6, &o->duration)) return CLI_USAGE;
    } else if (!strcmp(a, "--fps")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_float(a, v, 1.0, 1000.0, &o->fps)) return CLI_USAGE;
    } else if (!strcmp(a, "--path")) {
      if (!(o->path = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (!strcmp(a, "--loop")) {
      o->loop = true;
    } else if (!strcmp(a, "--screenshot-every")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, PLAY_MAX_FRAMES, &o->screenshot_every))
        return CLI_USAGE;
    } else if (!strcmp(a, "--window")) {
      o->window = true;
    } else if (!strcmp(a, "--out")) {
      if (!(o->out = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (!*o->out || strlen(o->out) > PLAY_PATH_MAX - 64)
        return cli_error(CLI_USAGE, "--out: expected a folder name of 1..%d characters", PLAY_PATH_MAX - 64);
    } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
      o->quiet = true;
    } else if (a[0] == '-' && a[1]) {
      return cli_error(CLI_USAGE, "play: unknown option '%s' (see tlod play --help)", a);
    } else if (!o->scene) {
      o->scene = a;
    } else {
      return cli_error(CLI_USAGE, "play: unexpected argument '%s' (one scene per run)", a);
    }
  }
  if (o->compare && o->mode_given) return cli_error(CLI_USAGE, "play: give --mode or --compare, not both");
  if (o->frames && o->duration > 0.0f) return cli_error(CLI_USAGE, "play: give --frames or --duration, not both");
  if (o->backend && strcmp(o->backend, "gl") && o->screenshot_every)
    return cli_error(CLI_USAGE, "--screenshot-every: the %s backend draws no image (screenshots need --backend gl)",
                     o->backend);
  if (o->backend && strcmp(o->backend, "gl") && o->window)
    return cli_error(CLI_USAGE, "--window: the %s backend draws no image (needs --backend gl)", o->backend);
  return CLI_OK;
}

/* ---- scene --------------------------------------------------------------- */

static void scene_free(play_scene* s) {
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    tlod_backend_destroy(ob->backend);
    tlod_scheduler_destroy(ob->scheduler);
    tlod_surface_destroy(ob->surface);
    tlod_mesh_destroy(ob->mesh);
    cli_mesh_free(&ob->in);
  }
  tlod_patterns_destroy(s->patterns);
  tlod_context_destroy(s->ctx);
  memset(s, 0, sizeof(*s));
}

/* A file through the importer, keeping the first part's base colour. */
static int load_file(const char* path, cli_mesh* m, float color[4]) {
  char err[512];
  tlod_import_result* r = NULL;
  memset(m, 0, sizeof(*m));
  if (tlod_import_file(path, NULL, &r, err, sizeof(err)) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
  snprintf(m->name, sizeof(m->name), "%s", path);
  m->vertex_count = r->vertex_count;
  m->positions = r->positions;
  m->normals = r->normals;
  m->index_count = r->index_count;
  m->indices = r->indices;
  m->face_count = r->face_count;
  m->face_sizes = r->face_sizes;
  m->source_face_count = m->face_sizes ? m->face_count : m->index_count / 3;
  snprintf(m->warnings, sizeof(m->warnings), "%s", r->warnings);
  if (r->part_count) memcpy(color, r->parts[0].base_color, sizeof(float) * 4);
  r->positions = r->normals = NULL;
  r->indices = NULL;
  r->face_sizes = NULL;
  tlod_import_free(r);
  return CLI_OK;
}

/* Loads SOURCE (file or demo:NAME) as object `name`; place, when given, moves it (see demo_place). */
static int add_object(play_scene* s, const play_options* o, const char* source, const char* name, const float color[4],
                      void (*place)(cli_mesh* m, const play_scene* s)) {
  play_object* ob = &s->objects[s->count];
  memset(ob, 0, sizeof(*ob));
  float c[4] = {color[0], color[1], color[2], color[3]};
  int rc = !strncmp(source, "demo:", 5) ? cli_load(source, &ob->in) : load_file(source, &ob->in, c);
  if (rc != CLI_OK) return rc;
  s->count++; /* from here on scene_free frees it */
  if (place) place(&ob->in, s);
  if (o->surface == TLOD_SURFACE_PN && (rc = cli_split_quads(&ob->in)) != CLI_OK) return rc;
  if ((rc = cli_create_mesh(s->ctx, &ob->in, TLOD_NORMALS_KEEP, 0.0f, &ob->mesh)) != CLI_OK) return rc;
  /* As tlod tessellate: alpha 0.75, so a frame matches a direct run of the same camera. */
  tlod_surface_desc sd = {.type = o->surface, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = 0.75f, .label = name};
  if (tlod_surface_create(s->ctx, ob->mesh, &sd, &ob->surface) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s: %s", source, tlod_context_last_error(s->ctx));
  tlod_mesh_info info = tlod_mesh_query_info(ob->mesh);
  if (info.face_count == 0) return cli_error(CLI_FAILED, "%s: no faces left to draw", source);
  play_object_info* pi = &ob->info;
  snprintf(pi->name, sizeof(pi->name), "%s", name);
  snprintf(pi->source, sizeof(pi->source), "%s", source);
  pi->vertices = tlod_mesh_vertex_count(ob->mesh);
  pi->faces = info.face_count;
  pi->patches = tlod_surface_patch_count(ob->surface);
  memcpy(pi->color, c, sizeof(c));
  for (int k = 0; k < 3; k++) {
    bool first = s->count == 1;
    s->bmin[k] = first || info.bbox_min[k] < s->bmin[k] ? info.bbox_min[k] : s->bmin[k];
    s->bmax[k] = first || info.bbox_max[k] > s->bmax[k] ? info.bbox_max[k] : s->bmax[k];
  }
  return CLI_OK;
}

/* The demo cylinder (radius 1, height 1.2 along z) stood upright beside the
 * cow's flank: a drum half the cow's height on the cow's ground. Rotation
 * (x, y, z) -> (x, z, -y) keeps the winding; the scale is the same in x and
 * z, so the normals (radial or axial) keep their directions. */
static void demo_place(cli_mesh* m, const play_scene* s) {
  const float height = 0.6f * (s->bmax[1] - s->bmin[1]), radius = 0.25f * height;
  const float c[3] = {0.5f * (s->bmin[0] + s->bmax[0]), s->bmin[1] + 0.5f * height,
                      s->bmax[2] + 0.5f * radius + radius};
  for (uint32_t v = 0; v < m->vertex_count; v++) {
    float* p = m->positions + 3 * v;
    float x = p[0], y = p[1], z = p[2];
    p[0] = c[0] + radius * x;
    p[1] = c[1] + height / 1.2f * z;
    p[2] = c[2] - radius * y;
    if (m->normals) {
      float* n = m->normals + 3 * v;
      float ny = n[1];
      n[1] = n[2];
      n[2] = -ny;
    }
  }
}

static int scene_load(const play_options* o, play_scene* s) {
  memset(s, 0, sizeof(*s));
  if (tlod_context_create(&(tlod_context_desc){.label = "tlod play"}, &s->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  int rc;
  if (!o->scene || !strcmp(o->scene, "demo:scene")) {
    snprintf(s->name, sizeof(s->name), "demo:scene");
    static const float cow[4] = {0.80f, 0.62f, 0.46f, 1.0f}, drum[4] = {0.42f, 0.58f, 0.82f, 1.0f};
    rc = add_object(s, o, "demo:cow", "cow", cow, NULL);
    if (rc == CLI_OK) rc = add_object(s, o, "demo:cylinder", "cylinder", drum, demo_place);
  } else {
    snprintf(s->name, sizeof(s->name), "%s", o->scene);
    const char* base = strrchr(o->scene, '/');
    base = base ? base + 1 : o->scene;
    if (!strncmp(base, "demo:", 5)) base += 5;
    static const float grey[4] = {0.8f, 0.8f, 0.8f, 1.0f};
    rc = add_object(s, o, o->scene, base, grey, NULL);
  }
  if (rc != CLI_OK) return rc;
  /* One pattern set for every object and mode: the finest level any mode needs. */
  uint32_t lmax = 1;
  for (uint32_t k = 0; k < o->mode_count; k++) {
    uint32_t l = o->modes[k].kind == MODE_ADAPTIVE ? o->max_level : o->modes[k].level;
    lmax = l > lmax ? l : lmax;
  }
  if (tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = lmax}, &s->patterns) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t i = 0; i < s->count; i++)
    s->infos[i] = s->objects[i].info;
  return CLI_OK;
}

/* One backend per object (each uploads one surface); destroys old ones first. */
static int create_backends(play_scene* s, const char* backend) {
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    tlod_backend_destroy(ob->backend);
    ob->backend = NULL;
    if (tlod_backend_create(s->ctx, &(tlod_backend_desc){.name = backend, .label = ob->info.name}, &ob->backend) !=
            TLOD_SUCCESS ||
        tlod_backend_upload(ob->backend, ob->surface, s->patterns) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "backend %s: %s", backend, tlod_context_last_error(s->ctx));
  }
  return CLI_OK;
}

/* Scheduler settings of a mode. uniform:L uses the UNIFORM policy (every
 * visible patch at L; culling applies); flat and uniform:0 the error rule
 * with an epsilon no patch exceeds (level 0 everywhere). */
static tlod_scheduler_desc mode_desc(const play_options* o, const play_mode* m, const char* label) {
  if (m->kind == MODE_ADAPTIVE)
    return (tlod_scheduler_desc){.epsilon_px = o->epsilon,
                                 .max_level = o->max_level,
                                 .policy = o->policy,
                                 .morph = TLOD_MORPH_TIME,
                                 .label = label};
  if (m->kind == MODE_UNIFORM && m->level > 0)
    return (tlod_scheduler_desc){
        .max_level = m->level, .policy = TLOD_POLICY_UNIFORM, .morph = TLOD_MORPH_NONE, .label = label};
  return (tlod_scheduler_desc){
      .epsilon_px = 1e30f, .max_level = 1, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE, .label = label};
}

static const char* mode_policy_name(const tlod_scheduler_desc* d) {
  switch (d->policy) {
  case TLOD_POLICY_ERROR:
    return "error";
  case TLOD_POLICY_SILHOUETTE:
    return "silhouette";
  case TLOD_POLICY_UNIFORM:
    return "uniform";
  default:
    return "hybrid";
  }
}

/* ---- output folder ------------------------------------------------------- */

/* "a/b" into buf; the caller's buffers are sized so it always fits. */
static bool path_join(char* buf, size_t size, const char* a, const char* b) {
  size_t na = strlen(a), nb = strlen(b);
  if (na + nb + 2 > size) {
    buf[0] = '\0';
    return false;
  }
  memmove(buf, a, na);
  buf[na] = '/';
  memcpy(buf + na + 1, b, nb + 1);
  return true;
}

static bool mkdir_p(const char* path) {
  char buf[4096];
  snprintf(buf, sizeof(buf), "%s", path);
  for (char* p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return false;
    *p = '/';
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST) return false;
  struct stat st;
  return stat(buf, &st) == 0 && S_ISDIR(st.st_mode);
}

static int make_out_dir(const play_options* o, char* out, size_t size) {
  if (o->out) {
    snprintf(out, size, "%s", o->out);
    size_t n = strlen(out);
    while (n > 1 && out[n - 1] == '/')
      out[--n] = '\0';
    if (!mkdir_p(out)) return cli_error(CLI_FAILED, "--out: cannot create folder '%s': %s", out, strerror(errno));
    return CLI_OK;
  }
  char stamp[32];
  time_t now = time(NULL);
  struct tm tm;
  localtime_r(&now, &tm);
  strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &tm);
  if (!mkdir_p("runs")) return cli_error(CLI_FAILED, "cannot create folder 'runs': %s", strerror(errno));
  for (int k = 1; k < 100; k++) {
    if (k == 1) {
      snprintf(out, size, "runs/%s", stamp);
    } else {
      snprintf(out, size, "runs/%s-%d", stamp, k);
    }
    if (mkdir(out, 0777) == 0) return CLI_OK;
    if (errno != EEXIST) break;
  }
  return cli_error(CLI_FAILED, "cannot create a run folder under 'runs': %s", strerror(errno));
}

/* ---- playback ------------------------------------------------------------ */

typedef struct play_run {
  const play_options* o;
  play_scene* scene;
  const camera_path* path;
  tlod_platform* platform; /* NULL: cpu */
  const char* backend;
  uint32_t frames;
  const char* run_dir;
  uint8_t* pixels;       /* screenshots */
  uint32_t index, count; /* of the modes, for the progress bar */
  bool tty;
} play_run;

static void progress(const play_run* r, const play_mode* m, uint32_t done, double elapsed_ms, bool final) {
  if (!r->tty) return;
  if (final) {
    fputs("\r\033[K", stderr);
    return;
  }
  const int width = 30;
  int filled = (int)((double)width * done / r->frames);
  char bar[64];
  for (int i = 0; i < width; i++)
    bar[i] = i < filled ? '#' : '-';
  bar[width] = '\0';
  double fps = elapsed_ms > 0.0 ? 1000.0 * done / elapsed_ms : 0.0;
  double eta = fps > 0.0 ? (r->frames - done) / fps : 0.0;
  char which[48] = "";
  if (r->count > 1) snprintf(which, sizeof(which), "%u/%u ", r->index + 1, r->count);
  fprintf(stderr, "\r\033[K%s%s [%s] %u/%u frames  %.1f fps  ETA %.1f s", which, m->name, bar, done, r->frames, fps,
          eta);
  fflush(stderr);
}

static void view_of(const play_run* r, const tool_camera* cam, tlod_view_desc* v) {
  *v = (tlod_view_desc){.viewport_width = r->o->width, .viewport_height = r->o->height};
  camera_look_at(cam->eye, cam->target, cam->up, v->view);
  camera_perspective(cam->fovy_deg, (float)r->o->width / (float)r->o->height, cam->near_z, cam->far_z, v->proj);
}

/* Reads the frame back and writes screenshots/frame_NNNNN.png. */
static int screenshot(play_run* r, play_frame* fr, double run_start) {
#if TLOD_HAS_GL
  double t0 = cli_now_ms();
  snprintf(fr->screenshot, sizeof(fr->screenshot), "screenshots/frame_%05u.png", fr->frame);
  char path[PLAY_PATH_MAX + 64], err[512];
  path_join(path, sizeof(path), r->run_dir, fr->screenshot);
  if (!tlod_platform_read_rgba(r->platform, r->pixels) ||
      !tlod_png_write(path, r->o->width, r->o->height, r->pixels, err, sizeof(err))) {
    fr->screenshot[0] = '\0';
    return cli_error(CLI_FAILED, "screenshot of frame %u: %s", fr->frame, err);
  }
  fr->screenshot_at_ms = t0 - run_start;
  fr->screenshot_ms = cli_now_ms() - t0;
  return CLI_OK;
#else
  (void)r, (void)fr, (void)run_start;
  return cli_error(CLI_FAILED, "screenshots need the GL backend");
#endif
}

/* Plays one mode into trace t. Returns CLI_OK, or CLI_FAILED after an error
 * mid-run (t then holds the frames played). */
static int play_mode_run(play_run* r, const play_mode* m, play_trace* t) {
  const play_options* o = r->o;
  play_scene* s = r->scene;
  char label[96];
  int rc = CLI_OK;
  for (uint32_t i = 0; i < s->count; i++) {
    play_object* ob = &s->objects[i];
    snprintf(label, sizeof(label), "%s/%s", ob->info.name, m->name);
    tlod_scheduler_desc d = mode_desc(o, m, label);
    tlod_scheduler_destroy(ob->scheduler);
    ob->scheduler = NULL;
    if (tlod_scheduler_create(s->ctx, ob->surface, s->patterns, &d, &ob->scheduler) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
    if (i == 0) {
      tlod_scheduler_desc q = tlod_scheduler_query_desc(ob->scheduler);
      t->policy = mode_policy_name(&q);
      t->epsilon = q.epsilon_px;
      t->max_level = q.max_level;
    }
  }
#if TLOD_HAS_GL
  if (r->platform) tlod_platform_bind(r->platform);
#endif
  const double dt_ms = 1000.0 / o->fps;
  const double run_start = cli_now_ms();
  double last_progress = -1e30;
  t->stopped = "completed";
  for (uint32_t n = 0; n < r->frames; n++) {
    if (g_interrupted) {
      t->stopped = "interrupted";
      break;
    }
    play_object_stats* os = NULL;
    play_frame* fr = play_trace_add_frame(t, &os);
    if (!fr) {
      t->stopped = "error";
      rc = cli_error(CLI_FAILED, "out of memory after %u frames", t->frame_count);
      break;
    }
    /* Fixed step: frame n shows path time n / fps, whatever the frame took. */
    fr->time_s = (double)n / o->fps;
    tool_camera cam = {0};
    camera_path_eval(r->path, fr->time_s, o->loop, &cam);
    camera_fit_planes(cam.eye, s->bmin, s->bmax, &cam.near_z, &cam.far_z);
    memcpy(fr->eye, cam.eye, sizeof(fr->eye));
    memcpy(fr->target, cam.target, sizeof(fr->target));
    memcpy(fr->up, cam.up, sizeof(fr->up));
    fr->fovy = cam.fovy_deg;
    fr->near_z = cam.near_z;
    fr->far_z = cam.far_z;
    tlod_view_desc view;
    view_of(r, &cam, &view);
    const double f0 = cli_now_ms();
    fr->at_ms = f0 - run_start;
    for (uint32_t i = 0; i < s->count && rc == CLI_OK; i++) {
      play_object* ob = &s->objects[i];
      double t0 = cli_now_ms();
      if (tlod_scheduler_update(ob->scheduler,
                                &(tlod_frame_desc){.views = &view, .view_count = 1, .dt_ms = (float)dt_ms}) !=
          TLOD_SUCCESS) {
        rc = cli_error(CLI_FAILED, "frame %u: %s", n, tlod_context_last_error(s->ctx));
        break;
      }
      double t1 = cli_now_ms();
      const tlod_draw_list* dl = tlod_scheduler_draw_list(ob->scheduler, 0);
      play_object_stats* st = &os[i];
      st->update_at_ms = t0 - run_start;
      st->update_ms = t1 - t0;
      memcpy(st->stage_ms, dl->stage_ms, sizeof(st->stage_ms));
      st->patches = dl->patch_count;
      st->culled = dl->culled;
      st->instances = dl->instance_count;
      st->strips = dl->strip_count;
      st->pattern_triangles = dl->pattern_triangles;
      st->strip_triangles = dl->strip_triangles;
      memcpy(st->level_histogram, dl->level_histogram, sizeof(st->level_histogram));
      st->effective_epsilon = dl->effective_epsilon;
    }
#if TLOD_HAS_GL
    if (rc == CLI_OK && r->platform) {
      glClearColor(0.11f, 0.12f, 0.14f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
#endif
    for (uint32_t i = 0; i < s->count && rc == CLI_OK; i++) {
      play_object* ob = &s->objects[i];
      tlod_backend_frame bf = {.draw_list = tlod_scheduler_draw_list(ob->scheduler, 0),
                               .viewport = {0, 0, o->width, o->height},
                               .finish = true};
      memcpy(bf.view, view.view, sizeof(bf.view));
      memcpy(bf.proj, view.proj, sizeof(bf.proj));
      memcpy(bf.base_color, ob->info.color, sizeof(bf.base_color));
      double t0 = cli_now_ms();
      if (tlod_backend_draw(ob->backend, &bf) != TLOD_SUCCESS) {
        rc = cli_error(CLI_FAILED, "frame %u: %s", n, tlod_context_last_error(s->ctx));
        break;
      }
      double t1 = cli_now_ms();
      tlod_backend_timings bt = tlod_backend_query_timings(ob->backend);
      play_object_stats* st = &os[i];
      st->draw_at_ms = t0 - run_start;
      st->draw_ms = t1 - t0;
      st->backend_cpu_ms = bt.cpu_ms;
      st->backend_gpu_ms = bt.gpu_ms;
      st->backend_wall_ms = bt.wall_ms;
      st->drawn_triangles = bt.triangles;
      st->draw_calls = bt.draw_calls;
    }
    fr->frame_ms = cli_now_ms() - f0;
    if (rc != CLI_OK) {
      t->frame_count--; /* the failed frame is not a record */
      t->stopped = "error";
      break;
    }
    if (o->screenshot_every && n % o->screenshot_every == 0 && (rc = screenshot(r, fr, run_start)) != CLI_OK) {
      t->stopped = "error";
      break;
    }
#if TLOD_HAS_GL
    if (o->window && r->platform) {
      tlod_platform_swap(r->platform);
      if (tlod_platform_should_close(r->platform)) {
        t->stopped = "window closed";
        break;
      }
    }
#endif
    double now = cli_now_ms();
    if (!o->quiet && now - last_progress > 100.0) {
      progress(r, m, n + 1, now - run_start, false);
      last_progress = now;
    }
  }
  t->wall_s = (cli_now_ms() - run_start) * 1e-3;
  if (!o->quiet) progress(r, m, t->frame_count, 0.0, true);
  return rc;
}

static int write_run(const play_trace* t, const char* dir) {
  char path[PLAY_PATH_MAX + 64], err[PLAY_PATH_MAX + 512];
  path_join(path, sizeof(path), dir, "trace.json");
  if (!play_write_trace_json(t, path, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  path_join(path, sizeof(path), dir, "trace.csv");
  if (!play_write_trace_csv(t, path, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  path_join(path, sizeof(path), dir, "chrome_trace.json");
  if (!play_write_chrome_trace(t, path, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  return CLI_OK;
}

/* Makes the GL context (headless or window). NULL with *rc set when it cannot
 * and GL was required; NULL with CLI_OK when the default falls back to cpu. */
static tlod_platform* open_platform(const play_options* o, int* rc, const char** backend) {
  bool required = (o->backend && !strcmp(o->backend, "gl")) || o->window || o->screenshot_every;
  char err[512] = "";
#if TLOD_HAS_GL
  tlod_platform* p = NULL;
  tlod_platform_desc d = {
      .width = o->width, .height = o->height, .window = o->window, .visible = o->window, .title = "tlod play"};
  if (tlod_platform_create(&d, &p, err, sizeof(err))) {
    *rc = CLI_OK;
    *backend = "gl";
    return p;
  }
#else
  snprintf(err, sizeof(err), "this build has no GL backend (TLOD_BACKEND_GL=OFF)");
#endif
  if (required) {
    const char* what = o->window
                           ? "--window: cannot open a GL window"
                           : (o->backend ? "--backend gl: no GL context"
                                         : "--screenshot-every: screenshots need a GL context, and there is none");
    *rc = cli_error(CLI_FAILED, "%s: %s", what, err);
    return NULL;
  }
  if (!o->quiet) fprintf(stderr, "tlod: note: no GL context (%s); playing on the cpu backend\n", err);
  *rc = CLI_OK;
  *backend = "cpu";
  return NULL;
}

/* Backends draw with the platform's context: destroy them while it exists. */
static void destroy_backends(play_scene* s) {
  for (uint32_t i = 0; i < s->count; i++) {
    tlod_backend_destroy(s->objects[i].backend);
    s->objects[i].backend = NULL;
  }
}

static void close_platform(tlod_platform* p) {
#if TLOD_HAS_GL
  tlod_platform_destroy(p);
#else
  (void)p;
#endif
}

int cmd_play(int argc, char** argv) {
  play_options o;
  int rc = parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;

  /* From here Ctrl-C only sets a flag: the run stops before its next frame
   * (during set-up: before the first) and writes what it played. */
  struct sigaction sa, old;
  memset(&sa, 0, sizeof(sa));
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  g_interrupted = 0;
  sigaction(SIGINT, &sa, &old);

  /* Everything that can fail on bad input happens before the run folder exists. */
  camera_path path = {0};
  char err[1024];
  bool builtin = camera_path_is_builtin(o.path);
  unsigned gltf_camera = 0;
  char tail;
  bool gltf = !strcmp(o.path, "gltf") || sscanf(o.path, "gltf:%u%c", &gltf_camera, &tail) == 1;
  if (gltf && (!o.scene || !strncmp(o.scene, "demo:", 5))) {
    rc = cli_error(CLI_USAGE, "--path %s: the scene must be a .gltf or .glb file with cameras", o.path);
  } else if (gltf) {
    if (!camera_path_load_gltf(o.scene, gltf_camera, &path, err, sizeof(err))) rc = cli_error(CLI_FAILED, "%s", err);
  } else if (!builtin && !camera_path_load(o.path, &path, err, sizeof(err))) {
    rc = cli_error(CLI_FAILED, "%s", err);
  }
  play_scene scene = {0};
  if (rc == CLI_OK) rc = scene_load(&o, &scene);
  if (rc == CLI_OK && builtin && !camera_path_builtin(o.path, scene.bmin, scene.bmax, &path))
    rc = cli_error(CLI_FAILED, "cannot build the %s path", o.path);
  const char* backend = o.backend ? o.backend : "gl";
  tlod_platform* platform = NULL;
  if (rc == CLI_OK && !strcmp(backend, "gl")) platform = open_platform(&o, &rc, &backend);
  if (rc == CLI_OK) rc = create_backends(&scene, backend);
  uint8_t* pixels = NULL;
  if (rc == CLI_OK && o.screenshot_every && !(pixels = malloc((size_t)o.width * o.height * 4)))
    rc = cli_error(CLI_FAILED, "out of memory for %ux%u screenshots", o.width, o.height);
  char out_dir[PLAY_PATH_MAX] = "";
  if (rc == CLI_OK) rc = make_out_dir(&o, out_dir, sizeof(out_dir));
  if (rc != CLI_OK) {
    sigaction(SIGINT, &old, NULL);
    free(pixels);
    destroy_backends(&scene);
    close_platform(platform);
    scene_free(&scene);
    camera_path_free(&path);
    return rc;
  }

  uint32_t frames = o.frames;
  if (!frames && o.duration > 0.0f) frames = (uint32_t)fmax(1.0, floor((double)o.duration * o.fps + 0.5));
  if (!frames) frames = camera_path_frames(&path, o.fps);
  if (frames > PLAY_MAX_FRAMES) frames = PLAY_MAX_FRAMES;

  char renderer[512] = "cpu reference tessellator (realises each draw list as a mesh; no image)";
#if TLOD_HAS_GL
  if (platform) tlod_platform_describe(platform, renderer, sizeof(renderer));
#endif
  char version[32];
  snprintf(version, sizeof(version), "tlod %d.%d.%d", TLOD_VERSION / 1000, TLOD_VERSION / 10 % 100, TLOD_VERSION % 10);

  play_trace traces[PLAY_MAX_MODES];
  const play_trace* done[PLAY_MAX_MODES];
  char run_dirs[PLAY_MAX_MODES][PLAY_PATH_MAX + 32];
  uint32_t run_count = 0;
  play_run run = {.o = &o,
                  .scene = &scene,
                  .path = &path,
                  .platform = platform,
                  .backend = backend,
                  .frames = frames,
                  .pixels = pixels,
                  .count = o.mode_count,
                  .tty = !o.quiet && isatty(STDERR_FILENO)};
  for (uint32_t k = 0; k < o.mode_count && rc == CLI_OK && (k == 0 || !g_interrupted); k++) {
    const play_mode* m = &o.modes[k];
    play_trace* t = &traces[k];
    if (o.compare) {
      path_join(run_dirs[k], sizeof(run_dirs[k]), out_dir, m->dir);
    } else {
      snprintf(run_dirs[k], sizeof(run_dirs[k]), "%s", out_dir);
    }
    char shots[PLAY_PATH_MAX + 64];
    path_join(shots, sizeof(shots), run_dirs[k], "screenshots");
    if (!mkdir_p(run_dirs[k]) || (o.screenshot_every && !mkdir_p(shots))) {
      rc = cli_error(CLI_FAILED, "cannot create folder '%s': %s", o.screenshot_every ? shots : run_dirs[k],
                     strerror(errno));
      break;
    }
    if (k > 0 && (rc = create_backends(&scene, backend)) != CLI_OK) break; /* fresh timer queries per mode */
    *t = (play_trace){.tool_version = version,
                      .scene = scene.name,
                      .mode = m->name,
                      .backend = backend,
                      .renderer = renderer,
                      .surface = o.surface == TLOD_SURFACE_PN ? "pn" : "phong",
                      .path = path.name,
                      .path_duration_s = camera_path_duration(&path),
                      .loop = o.loop,
                      .fps = o.fps,
                      .width = o.width,
                      .height = o.height,
                      .frames_requested = frames,
                      .screenshot_every = o.screenshot_every,
                      .objects = scene.infos,
                      .object_count = scene.count,
                      .dir = o.compare ? m->dir : ".",
                      .stopped = "completed"};
    run.run_dir = run_dirs[k];
    run.index = k;
    rc = play_mode_run(&run, m, t);
    done[run_count++] = t;
    int wrc = write_run(t, run_dirs[k]);
    if (rc == CLI_OK) rc = wrc;
  }
  sigaction(SIGINT, &old, NULL);
  if (g_interrupted && !o.quiet)
    fprintf(stderr, "tlod: interrupted: wrote the %u frames played so far\n",
            run_count ? done[run_count - 1]->frame_count : 0);

  if (run_count) {
    char p[PLAY_PATH_MAX + 64];
    path_join(p, sizeof(p), out_dir, "summary.json");
    if (!play_write_summary_json(done, run_count, out_dir, p, err, sizeof(err)) && rc == CLI_OK)
      rc = cli_error(CLI_FAILED, "%s", err);
    path_join(p, sizeof(p), out_dir, "summary.txt");
    if (!play_write_summary_text(done, run_count, out_dir, p, err, sizeof(err)) && rc == CLI_OK)
      rc = cli_error(CLI_FAILED, "%s", err);
    if (!o.quiet) play_print_summary(stdout, done, run_count, out_dir);
  }
  for (uint32_t k = 0; k < run_count; k++)
    play_trace_free(&traces[k]);
  destroy_backends(&scene);
  close_platform(platform);
  free(pixels);
  scene_free(&scene);
  camera_path_free(&path);
  if (rc == CLI_OK && g_interrupted) return 130;
  return rc;
}
