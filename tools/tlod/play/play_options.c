/* tlod play -- usage and option parsing. */
#define _POSIX_C_SOURCE 200809L /* strtok_r */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "common/gpu_target.h"
#include "common/mesh_load.h"
#include "play_options.h"
#include "play_serve.h"
#include "tesslod/backend.h"
#include "tool_names.h"

const char* const play_debug_view_names[] = {"none", "levels", "silhouette", "strips", "wireframe", NULL};
const char* const play_gpu_eval_names[] = {"auto", "on", "off", NULL};

void play_usage(FILE* f) {
  fprintf(
      f,
      "usage: tlod play [SCENE] [options]\n"
      "Plays SCENE along a camera path with a fixed time step and records per-frame timings.\n"
      "  SCENE               .gltf .glb .obj .ply file, a VTK file (.vtk .vtu .vtp .pvtu .stl, a .pvd series or\n"
      "                      numbered files NAME_*.vtu), a built-in mesh (%s), or nothing /\n"
      "                      demo:scene for the built-in demo scene (the VTK cow beside a creased cylinder)\n"
      "  --backend B         gl (default when a GL context can be made, else cpu) | cpu | null (draws nothing)\n"
      "                      | vulkan (headless or --window; an error when it cannot start, never a fallback)\n"
      "                      (this build has: %s)\n"
      "  --mode M            adaptive (default) | uniform:L (every visible patch at level L, 0..%d) | flat (level 0)\n"
      "  --compare M,M[,..]  play the same path once per mode (output per mode in subfolders)\n"
      "  --surface S         auto (default) | phong | pn | flat | quadratic; auto: quadratic for VTK files with\n"
      "                      second-order faces (their exact curved surface), else phong; pn splits quads\n"
      "                      into triangles and ignores second-order nodes\n"
      "  --crease DEG        computed normals split across edges sharper than DEG (default: none; VTK\n"
      "                      files %.0f)\n"
      "  --field F           colour by a result field (VTK point or cell data): NAME, NAME:C (component C,\n"
      "                      0-based, or x|y|z) or NAME:magnitude (default for vectors); default: none;\n"
      "                      a legend goes into the screenshots; a series (.pvd, numbered files) plays its\n"
      "                      steps over the timeline (step times in seconds, the last held; --loop repeats)\n"
      "  --range MIN,MAX     the field values at the ends of the colour map (default: the field's range over\n"
      "                      all steps)\n"
      "  --colormap M        viridis (default) | diverging (cool-warm, centred on the range's middle)\n"
      "  --epsilon PX        adaptive: screen-space error bound in pixels (default 0.5)\n"
      "  --policy P          adaptive: error | silhouette | hybrid (default hybrid)\n"
      "  --max-level L       adaptive: finest level, 1..%d (default 6)\n"
      "  --scene-budget N    adaptive: at most N triangles per frame over all objects, shared by their\n"
      "                      screen error (one epsilon for all), not split evenly (default: none)\n"
      "  --size WxH          viewport in pixels (default 1280x720)\n"
      "  --path P            orbit (default) | flyby | zoom | FILE.json (keyframes, see docs/play.md)\n"
      "                      | gltf[:N] (camera N of the glTF scene, with its animation)\n"
      "  --animation A       glTF scenes: the animation played along the timeline, looping over its\n"
      "                      duration: a name, an index, or none (default: the first)\n"
      "  --frames N          frames to play (default: the path's length at --fps (orbit: 240))\n"
      "  --duration S        seconds of path time to play (frames = S * fps); not with --frames\n"
      "  --fps F             fixed time step 1/F s per frame (default 60): runs are repeatable\n"
      "  --loop              start the path over at its end (default: hold the last keyframe)\n"
      "  --screenshot-every N  gl, vulkan: write screenshots/frame_NNNNN.png every N frames (from frame 0)\n"
      "  --debug-view V      gl, vulkan: levels (colour by level) | silhouette | strips (strips in pink)\n"
      "                      | wireframe (edges over the shading) | none (default); in trace and screenshots\n"
      "  --gpu-eval E        gl, vulkan: auto (default: off on llvmpipe and other software rasterisers, else on)\n"
      "                      | on (surfaces evaluated in the vertex shader) | off (CPU mesh: the draw list\n"
      "                      evaluated on the CPU, one indexed draw per object); auto is on with --debug-view\n"
      "                      levels or strips (the CPU mesh carries neither)\n"
      "  --window            gl, vulkan: draw into a GLFW window (needs DISPLAY) instead of headless\n"
      "  --resize-at N:WxH   resize the framebuffer and viewport to WxH before frame N (every mode)\n"
      "  --validate          vulkan: Vulkan validation layer (with synchronization validation) on; any\n"
      "                      message fails the run, their count is in the summary\n"
      "  --shader-cache D    vulkan: SPIR-V cache folder, or off (default $XDG_CACHE_HOME/tesslod, else\n"
      "                      $HOME/.cache/tesslod; a given folder that cannot be made or written is an error)\n"
      "  --out DIR           run folder (default runs/YYYYmmdd-HHMMSS)\n"
      "  -q, --quiet         no progress bar and no summary\n"
      "  --serve [ADDR:]PORT serve the live dashboard while playing (ADDR default 127.0.0.1; docs/play.md)\n"
      "  --serve-linger S    keep serving S seconds after playing (default 0: stop at the end)\n"
      "Writes trace.json, trace.csv, chrome_trace.json, summary.json and summary.txt into the run folder.\n"
      "Ctrl-C stops after the current frame, writes what was played and exits with 130.\n",
      cli_demo_names(), tlod_backend_names(), TLOD_MAX_LEVEL, (double)CLI_VTK_CREASE_DEG, TLOD_MAX_LEVEL);
}

static int mode_error(const char* option, const char* text, const char* problem) {
  return cli_error(CLI_USAGE, "%s: %s: %s", option, text, problem);
}

static int parse_compare(const char* text, play_options* o) {
  char buf[256];
  snprintf(buf, sizeof(buf), "%s", text);
  o->mode_count = 0;
  for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    if (o->mode_count == PLAY_MAX_MODES) return cli_error(CLI_USAGE, "--compare: at most %d modes", PLAY_MAX_MODES);
    play_mode* m = &o->modes[o->mode_count];
    const char* problem = play_mode_parse(tok, m);
    if (problem) return mode_error("--compare", tok, problem);
    for (uint32_t k = 0; k < o->mode_count; k++)
      if (!strcmp(o->modes[k].name, m->name)) return cli_error(CLI_USAGE, "--compare: mode '%s' given twice", m->name);
    o->mode_count++;
  }
  if (o->mode_count < 2)
    return cli_error(CLI_USAGE, "--compare: expected two or more modes separated by commas, got '%s'", text);
  return CLI_OK;
}

static int parse_flag(const char* a, play_options* o) {
  if (!strcmp(a, "--loop")) {
    o->loop = true;
  } else if (!strcmp(a, "--window")) {
    o->window = true;
  } else if (!strcmp(a, "--validate")) {
    o->validate = true;
  } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
    o->quiet = true;
  } else {
    return CLI_NOT_MINE;
  }
  return CLI_OK;
}

static int parse_modes(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  if (!strcmp(a, "--mode")) {
    if (!(v = cli_value(argc, argv, i))) return CLI_USAGE;
    const char* problem = play_mode_parse(v, &o->modes[0]);
    if (problem) return mode_error(a, v, problem);
    o->mode_given = true;
    return CLI_OK;
  }
  if (!strcmp(a, "--compare")) {
    if (!(v = cli_value(argc, argv, i))) return CLI_USAGE;
    o->compare = true;
    return parse_compare(v, o);
  }
  return CLI_NOT_MINE;
}

static int parse_lod(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  int e;
  if (!strcmp(a, "--surface")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, tool_surface_auto_options)) < 0) return CLI_USAGE;
    o->surface = (tlod_surface_type)e;
    return CLI_OK;
  }
  if (!strcmp(a, "--crease"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 0.0, 180.0, &o->crease));
  if (!strcmp(a, "--scene-budget"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_uint(a, v, 1, UINT32_MAX, &o->scene_budget));
  int rc = cli_parse_lod_option(argc, argv, i, &o->epsilon, &o->policy, &o->max_level);
  if (rc != CLI_NOT_MINE) return rc;
  return parse_modes(argc, argv, i, o);
}

static int parse_field(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  int e;
  if (!strcmp(a, "--field")) {
    if (!(o->field.spec = cli_value(argc, argv, i))) return CLI_USAGE;
    if (!*o->field.spec || *o->field.spec == ':') return cli_error(CLI_USAGE, "--field: expected NAME[:COMPONENT]");
    return CLI_OK;
  }
  if (!strcmp(a, "--range")) {
    o->field.has_range = true;
    return cli_usage_unless((v = cli_value(argc, argv, i)) && field_parse_range(a, v, o->field.range));
  }
  if (!strcmp(a, "--colormap")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, colormap_names)) < 0) return CLI_USAGE;
    o->field.colormap = (colormap_kind)e;
    o->colormap_given = true;
    return CLI_OK;
  }
  return CLI_NOT_MINE;
}

static int parse_timing(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  if (!strcmp(a, "--frames"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_uint(a, v, 1, PLAY_MAX_FRAMES, &o->frames));
  if (!strcmp(a, "--duration"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 1e-3, 1e6, &o->duration));
  if (!strcmp(a, "--fps"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 1.0, 1000.0, &o->fps));
  if (!strcmp(a, "--path")) return cli_usage_unless((o->path = cli_value(argc, argv, i)) != NULL);
  if (!strcmp(a, "--animation")) return cli_usage_unless((o->animation = cli_value(argc, argv, i)) != NULL);
  return CLI_NOT_MINE;
}

/* --resize-at N:WxH. */
static bool parse_resize(const char* option, const char* text, play_options* o) {
  const char* colon = strchr(text, ':');
  char frame[32];
  if (!colon || colon == text || (size_t)(colon - text) >= sizeof(frame)) {
    cli_error(CLI_USAGE, "%s: %s: expected FRAME:WxH (e.g. 50:640x360)", option, text);
    return false;
  }
  snprintf(frame, sizeof(frame), "%.*s", (int)(colon - text), text);
  o->resize = true;
  return cli_parse_uint(option, frame, 0, PLAY_MAX_FRAMES, &o->resize_frame) &&
         cli_parse_size(option, colon + 1, 16384, &o->resize_w, &o->resize_h);
}

static int parse_output(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  const char* v = NULL;
  int e;
  if (!strcmp(a, "--backend")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, tool_backend_options())) < 0) return CLI_USAGE;
    o->backend = tool_backend_options()[e];
    return CLI_OK;
  }
  if (!strcmp(a, "--size"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_size(a, v, 16384, &o->width, &o->height));
  if (!strcmp(a, "--screenshot-every"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) &&
                            cli_parse_uint(a, v, 1, PLAY_MAX_FRAMES, &o->screenshot_every));
  if (!strcmp(a, "--debug-view")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, play_debug_view_names)) < 0) return CLI_USAGE;
    o->debug_view = (play_debug_view)e;
    return CLI_OK;
  }
  if (!strcmp(a, "--gpu-eval")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, play_gpu_eval_names)) < 0) return CLI_USAGE;
    o->gpu_eval = e;
    return CLI_OK;
  }
  if (!strcmp(a, "--resize-at")) return cli_usage_unless((v = cli_value(argc, argv, i)) && parse_resize(a, v, o));
  if (!strcmp(a, "--shader-cache")) {
    if (!(o->shader_cache = cli_value(argc, argv, i))) return CLI_USAGE;
    if (!*o->shader_cache) return cli_error(CLI_USAGE, "--shader-cache: expected a folder or off");
    return CLI_OK;
  }
  if (!strcmp(a, "--out")) {
    if (!(o->out = cli_value(argc, argv, i))) return CLI_USAGE;
    if (!*o->out || strlen(o->out) > PLAY_PATH_MAX - 64)
      return cli_error(CLI_USAGE, "--out: expected a folder name of 1..%d characters", PLAY_PATH_MAX - 64);
    return CLI_OK;
  }
  return CLI_NOT_MINE;
}

static int parse_argument(int argc, char** argv, int* i, play_options* o) {
  const char* a = argv[*i];
  if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
    play_usage(stdout);
    exit(0);
  }
  int rc = parse_flag(a, o);
  if (rc == CLI_NOT_MINE) rc = parse_lod(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = parse_timing(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = parse_field(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = parse_output(argc, argv, i, o);
  if (rc == CLI_NOT_MINE) rc = play_serve_option(argc, argv, i, o);
  if (rc != CLI_NOT_MINE) return rc;
  if (a[0] == '-' && a[1]) return cli_error(CLI_USAGE, "play: unknown option '%s' (see tlod play --help)", a);
  if (o->scene) return cli_error(CLI_USAGE, "play: unexpected argument '%s' (one scene per run)", a);
  o->scene = a;
  return CLI_OK;
}

/* Options that do not go together. */
static int check(const play_options* o) {
  if (o->compare && o->mode_given) return cli_error(CLI_USAGE, "play: give --mode or --compare, not both");
  if (o->frames && o->duration > 0.0f) return cli_error(CLI_USAGE, "play: give --frames or --duration, not both");
  if (o->serve_linger > 0.0f && !o->serve) return cli_error(CLI_USAGE, "--serve-linger: needs --serve");
  if ((o->field.has_range || o->colormap_given) && !o->field.spec)
    return cli_error(CLI_USAGE, "%s: needs --field NAME", o->field.has_range ? "--range" : "--colormap");
  bool image = !o->backend || gpu_backend(o->backend);
  if (!image && o->screenshot_every)
    return cli_error(CLI_USAGE,
                     "--screenshot-every: the %s backend draws no image (screenshots need --backend gl or vulkan)",
                     o->backend);
  if (!image && o->debug_view)
    return cli_error(CLI_USAGE, "--debug-view: the %s backend draws no image (needs --backend gl or vulkan)",
                     o->backend);
  if (!image && o->gpu_eval)
    return cli_error(CLI_USAGE, "--gpu-eval: the %s backend draws no image (needs --backend gl or vulkan)", o->backend);
  if (!image && o->window)
    return cli_error(CLI_USAGE, "--window: the %s backend draws no image (needs --backend gl or vulkan)", o->backend);
  if (o->validate && (!o->backend || strcmp(o->backend, "vulkan")))
    return cli_error(CLI_USAGE, "--validate: the Vulkan validation layer needs --backend vulkan");
  return CLI_OK;
}

int play_parse(int argc, char** argv, play_options* o) {
  *o = (play_options){.surface = TLOD_SURFACE_DEFAULT,
                      .crease = -1.0f,
                      .epsilon = 0.5f,
                      .policy = TLOD_POLICY_HYBRID,
                      .max_level = 6,
                      .width = 1280,
                      .height = 720,
                      .fps = 60.0f,
                      .path = "orbit"};
  play_mode_parse("adaptive", &o->modes[0]);
  o->mode_count = 1;
  for (int i = 0; i < argc; i++) {
    int rc = parse_argument(argc, argv, &i, o);
    if (rc != CLI_OK) return rc;
  }
  return check(o);
}
