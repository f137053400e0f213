#!/usr/bin/env python3
"""End-to-end tests of `tlod play` (docs/play.md): trace schema, CSV, Chrome
trace, consistency with a direct `tlod tessellate` run of frame 0's camera,
repeatability, screenshots, --compare, path files, bad input, SIGINT, and the
no-argument default run.
Usage: play_test.py TLOD DATA_DIR WORK_DIR"""
import glob, json, os, shutil, signal, struct, subprocess, sys, time, zlib

from png_read import png_rows
from tlod_cli import check, finish, init, load_json, one_error_line, run

TLOD, DATA, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
# "gl": the build has the GL backend, and a GL context must work (a failure, never a skip);
# "nogl": the build has none, and the GL checks are left out for that reason alone.
BUILT_WITH_GL = (sys.argv[4] if len(sys.argv) > 4 else "gl") == "gl"
init(TLOD)
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
SIZE = (640, 360)  # small: keeps the gl runs and the PNG decoding quick
SIZE_ARG = "%dx%d" % SIZE


# ---- the documented schema (docs/play.md) -----------------------------------

NUM, INT, STR, BOOL = "number", "int", "string", "bool"
STAGES = ["silhouette", "metric", "levels", "morph", "strips"]
LEVELS = 11  # TLOD_MAX_LEVEL + 1


def vec(n):
    return ("vec", n)


def obj(fields):
    return ("obj", fields)


OBJECT_INFO = obj({"name": STR, "source": STR, "vertices": INT, "faces": INT, "patches": INT, "color": vec(4),
                   "surface": INT, "node": INT, "skinned": BOOL, "textured": BOOL})
STAGE_MS = obj({s: NUM for s in STAGES})
COUNTS = {"backend_cpu_ms": NUM, "backend_gpu_ms": NUM, "backend_wall_ms": NUM, "patches": INT, "visible": INT,
          "culled": INT, "strips": INT, "pattern_triangles": INT, "strip_triangles": INT, "triangles": INT,
          "drawn_triangles": INT, "draw_calls": INT, "effective_epsilon": NUM, "level_histogram": ("ints", LEVELS)}
FRAME_OBJECT = obj(dict({"name": STR, "scheduler_ms": NUM, "stage_ms": STAGE_MS}, **COUNTS))
FRAME = obj(dict({"frame": INT, "time_s": NUM, "eye": vec(3), "target": vec(3), "up": vec(3), "fovy": NUM,
                  "near": NUM, "far": NUM, "frame_ms": NUM, "anim_ms": NUM, "scheduler_ms": NUM, "stage_ms": STAGE_MS,
                  "screenshot_ms": NUM, "screenshot": STR, "objects": ("list", FRAME_OBJECT)}, **COUNTS))
TRACE = obj({"schema": STR, "tool": STR, "scene": STR, "mode": STR, "backend": STR, "renderer": STR, "gpu_eval": STR, "surface": STR,
             "policy": STR, "epsilon_px": NUM, "max_level": INT, "scene_budget": INT, "path": STR, "path_duration_s": NUM, "loop": BOOL,
             "fps": NUM, "dt_ms": NUM, "width": INT, "height": INT, "screenshot_every": INT,
             "frames_requested": INT, "frames_completed": INT, "stopped": STR, "wall_s": NUM,
             "objects": ("list", OBJECT_INFO), "frames": ("list", FRAME), "objects_inline": INT,
             "object_counts_file": STR, "animation": STR, "animation_duration_s": NUM, "debug_view": STR, "warning_count": INT,
             "warnings": ("list", STR)})
DIST = obj({k: NUM for k in ("mean", "p50", "p95", "p99", "max", "min")})
VK_STATS = ("shader_compiles", "shader_cache_hits", "shader_ms", "pipelines", "create_ms", "memory_blocks",
            "memory_bytes", "ring_bytes", "upload_bytes", "descriptor_sets")
RUN = obj({"mode": STR, "dir": STR, "policy": STR, "epsilon_px": NUM, "max_level": INT, "scene_budget": INT,
           "frames_requested": INT,
           "frames": INT, "stopped": STR, "wall_s": NUM, "frame_ms": DIST, "fps": NUM, "first_frame_ms": NUM,
           "scheduler_ms": DIST, "stage_ms_mean": obj({s: NUM for s in STAGES}), "backend_cpu_ms": DIST,
           "backend_wall_ms": DIST, "backend_gpu_ms_mean": NUM, "backend_gpu_frames": INT, "triangles": DIST,
           "pattern_triangles_mean": NUM, "strip_triangles_mean": NUM, "drawn_triangles_mean": NUM,
           "culled_mean": NUM, "effective_epsilon_mean": NUM, "level_histogram_mean": vec(LEVELS),
           "resources": ("list", obj({"frame": INT, "peak_rss_kib": INT, "rss_kib": INT})),
           "validation_messages": INT, "vk": obj({k: NUM for k in VK_STATS})})
GL_OBJECTS = obj({k: INT for k in ("buffers", "textures", "renderbuffers", "framebuffers", "vertex_arrays", "programs",
                                   "shaders", "queries")})
SUMMARY = obj({"schema": STR, "status": STR, "error": STR, "tool": STR, "scene": STR, "backend": STR, "renderer": STR, "gpu_eval": STR, "surface": STR, "path": STR,
               "animation": STR, "debug_view": STR, "warning_count": INT, "warnings": ("list", STR), "fps": NUM, "width": INT, "height": INT, "out_dir": STR, "runs": ("list", RUN),
               "resize_at": obj({"frame": INT, "width": INT, "height": INT}), "validate": BOOL,
               "validation_messages": INT, "shader_cache": STR})


def is_num(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def validate(value, schema, where="$"):
    """Returns a list of problems: every key present, no other key, every type right."""
    problems = []
    if schema == NUM:
        ok = is_num(value)
    elif schema == INT:
        ok = isinstance(value, int) and not isinstance(value, bool)
    elif schema == STR:
        ok = isinstance(value, str)
    elif schema == BOOL:
        ok = isinstance(value, bool)
    elif schema[0] == "vec":
        ok = isinstance(value, list) and len(value) == schema[1] and all(is_num(x) for x in value)
    elif schema[0] == "ints":
        ok = isinstance(value, list) and len(value) == schema[1] and all(
            isinstance(x, int) and not isinstance(x, bool) for x in value)
    elif schema[0] == "list":
        if not isinstance(value, list):
            return ["%s: expected a list" % where]
        for i, v in enumerate(value):
            problems += validate(v, schema[1], "%s[%d]" % (where, i))
            if len(problems) > 10:
                break
        return problems
    elif schema[0] == "obj":
        if not isinstance(value, dict):
            return ["%s: expected an object" % where]
        fields = schema[1]
        for k in fields:
            if k not in value:
                problems.append("%s: missing key %s" % (where, k))
            else:
                problems += validate(value[k], fields[k], where + "." + k)
        for k in value:
            if k not in fields:
                problems.append("%s: unexpected key %s" % (where, k))
        return problems
    else:
        raise ValueError(schema)
    return [] if ok else ["%s: %r is not a %s" % (where, value, schema if isinstance(schema, str) else schema[0])]


def validate_summary(s):
    if not isinstance(s, dict) or not isinstance(s.get("runs"), list):
        return ["not a summary"]
    problems = []
    for r in s["runs"]:
        r.pop("relative_to_first", None)
        for k, sample in enumerate(r.get("resources", [])):  # gl_objects: gl runs only
            if isinstance(sample, dict) and "gl_objects" in sample:
                problems += validate(sample.pop("gl_objects"), GL_OBJECTS, "$.runs[].resources[%d]" % k)
    return problems + validate(s, SUMMARY)


# ---- PNG ---------------------------------------------------------------------

def png_decode(path):
    """(width, height, colour type, set of distinct pixels) of an 8-bit PNG (every 4th row, 3rd pixel)."""
    w, h, bpp, ctype, rows = png_rows(path)
    colours = set()
    for y in range(0, h, 4):
        colours.update(bytes(rows[y][i:i + bpp]) for i in range(0, w * bpp, bpp * 3))
    return w, h, ctype, colours


# ---- checks of one run ---------------------------------------------------------

def check_run(name, out, frames, backend, screenshots_every=0):
    """Validates the files of one run folder; returns the trace (or None)."""
    t = load_json(os.path.join(out, "trace.json"))
    if not check(name + ": trace.json parses", isinstance(t, dict), t):
        return None
    problems = validate(t, TRACE)
    check(name + ": trace.json matches the schema (every key and type, every frame)", not problems, problems[:10])
    if problems:
        return None
    check(name + ": schema name, backend, frame counts",
          t["schema"] == "tlod-play-trace/2" and t["backend"] == backend and t["frames_completed"] == frames
          and len(t["frames"]) == frames and t["frames_requested"] == frames and t["stopped"] == "completed",
          (t["schema"], t["backend"], t["frames_completed"], len(t["frames"]), t["stopped"]))
    bad = []
    for i, f in enumerate(t["frames"]):
        objs = f["objects"]
        if f["frame"] != i or abs(f["time_s"] - i / t["fps"]) > 1e-6:
            bad.append("frame %d: number/time" % i)
        if f["triangles"] != f["pattern_triangles"] + f["strip_triangles"]:
            bad.append("frame %d: triangles != pattern + strip" % i)
        for k in ("patches", "culled", "strips", "pattern_triangles", "strip_triangles", "triangles",
                  "drawn_triangles", "draw_calls"):
            if f[k] != sum(o[k] for o in objs):
                bad.append("frame %d: %s is not the sum over objects" % (i, k))
        if f["level_histogram"] != [sum(o["level_histogram"][l] for o in objs) for l in range(LEVELS)]:
            bad.append("frame %d: level histogram is not the sum over objects" % i)
        for o in objs:
            if sum(o["level_histogram"]) != o["visible"] or o["visible"] + o["culled"] != o["patches"]:
                bad.append("frame %d %s: histogram/visible/culled/patches disagree" % (i, o["name"]))
            if o["triangles"] != o["pattern_triangles"] + o["strip_triangles"]:
                bad.append("frame %d %s: triangles" % (i, o["name"]))
        if f["frame_ms"] <= 0 or f["scheduler_ms"] < 0 or f["backend_wall_ms"] <= 0:
            bad.append("frame %d: times" % i)
        if backend == "gl" and f["drawn_triangles"] == 0:
            bad.append("frame %d: gl drew nothing" % i)
        want_shot = screenshots_every and i % screenshots_every == 0
        if bool(f["screenshot"]) != bool(want_shot):
            bad.append("frame %d: screenshot entry %r" % (i, f["screenshot"]))
    check(name + ": per-frame counts consistent (sums, histograms, visible + culled, times)", not bad, bad[:5])
    check(name + ": objects are the cow and the cylinder",
          [o["name"] for o in t["objects"]] == ["cow", "cylinder"] and t["objects"][0]["patches"] == 3285,
          t["objects"])

    # CSV: a header, then exactly one line per frame
    with open(os.path.join(out, "trace.csv")) as fcsv:
        lines = fcsv.read().splitlines()
    header = lines[0].split(",") if lines else []
    rows = [l.split(",") for l in lines[1:]]
    check(name + ": trace.csv has a header and exactly one line per frame",
          len(lines) == frames + 1 and header[:3] == ["frame", "time_s", "frame_ms"]
          and all(len(r) == len(header) for r in rows), (len(lines), header[:3]))
    if len(rows) == frames and "triangles" in header and "level_3" in header:
        ti, li = header.index("triangles"), header.index("level_3")
        check(name + ": CSV rows agree with the JSON trace",
              all(int(r[0]) == f["frame"] and int(r[ti]) == f["triangles"] and int(r[li]) == f["level_histogram"][3]
                  for r, f in zip(rows, t["frames"])))

    # Chrome trace
    c = load_json(os.path.join(out, "chrome_trace.json"))
    ok = isinstance(c, dict) and isinstance(c.get("traceEvents"), list) and c["traceEvents"]
    events = c["traceEvents"] if ok else []
    fields_ok = all(isinstance(e, dict) and isinstance(e.get("name"), str) and e.get("ph") == "X"
                    and is_num(e.get("ts")) and is_num(e.get("dur")) and e.get("dur") >= 0
                    and isinstance(e.get("pid"), int) and isinstance(e.get("tid"), int)
                    and isinstance(e.get("cat"), str) and isinstance(e.get("args"), dict) for e in events)
    names = {e["name"] for e in events} if fields_ok else set()
    per_frame = 1 + 2 * (1 + len(STAGES) + 1)  # frame + per object: update, stages, draw
    check(name + ": chrome_trace.json parses; every event has name, ph X, ts, dur, pid, tid",
          ok and fields_ok and len(events) >= frames * per_frame
          and {"frame", "metric cow", "backend_draw cow", "scheduler_update cylinder"} <= names,
          (ok, fields_ok, len(events), sorted(names)[:12]))

    # summary
    s = load_json(os.path.join(out, "summary.json"))
    sp = validate_summary(s) if isinstance(s, dict) else ["does not parse"]
    check(name + ": summary.json matches the schema", not sp, sp[:5])
    if not sp:
        r = s["runs"][0]
        fm = sorted(f["frame_ms"] for f in t["frames"])
        check(name + ": summary statistics (mean, p50, max of frame_ms)",
              r["frames"] == frames and abs(r["frame_ms"]["mean"] - sum(fm) / len(fm)) < 1e-3 * max(1, fm[-1])
              and abs(r["frame_ms"]["max"] - fm[-1]) < 1e-6 * max(1, fm[-1])
              and abs(r["frame_ms"]["p50"] - fm[(len(fm) + 1) // 2 - 1]) < 1e-6 * max(1, fm[-1]),
              (r["frame_ms"], fm[-1]))
    check(name + ": summary.txt written", os.path.getsize(os.path.join(out, "summary.txt")) > 0)
    return t


def histograms(t):
    return [[o["level_histogram"] for o in f["objects"]] for f in t["frames"]]


def triangles(t):
    return [[(o["pattern_triangles"], o["strip_triangles"]) for o in f["objects"]] for f in t["frames"]]


def final_files(d):
    return [p for p in glob.glob(os.path.join(d, "**"), recursive=True) if os.path.isfile(p)]


# ---- usage -------------------------------------------------------------------
rc, out, err = run("play", "--help")
check("play --help exits 0 with usage", rc == 0 and "usage: tlod play" in out and "--compare" in out)

# ---- GL available? -------------------------------------------------------------
probe_start = time.time()
rc, out, err = run("play", "--backend", "gl", "--frames", "1", "--size", "64x64", "-q", "--out",
                   os.path.join(WORK, "probe"))
startup_s = time.time() - probe_start  # set-up of a run: the SIGINT test waits well past it
have_gl = rc == 0
if BUILT_WITH_GL:
    check("the GL backend starts (headless EGL on llvmpipe)", have_gl, (rc, err))
else:
    check("a build without GL refuses --backend gl, naming the backends it has",
          rc == 2 and "cpu|null" in err, (rc, err))
    print("note: this build has no GL backend (TLOD_BACKEND_GL=OFF): the gl checks are left out")

# ---- cpu: 100 frames ---------------------------------------------------------------
cpu_dir = os.path.join(WORK, "cpu")
t0 = time.time()
rc, out, err = run("play", "--backend", "cpu", "--frames", "100", "--size", SIZE_ARG, "--out", cpu_dir, "-q")
check("cpu: 100 frames exit 0, quiet", rc == 0 and not out and not err, (rc, out, err))
cpu = check_run("cpu", cpu_dir, 100, "cpu")

# ---- repeatability ------------------------------------------------------------
cpu2_dir = os.path.join(WORK, "cpu2")
rc, out, err = run("play", "--backend", "cpu", "--frames", "100", "--size", SIZE_ARG, "--out", cpu2_dir, "-q")
cpu2 = load_json(os.path.join(cpu2_dir, "trace.json"))
if cpu and isinstance(cpu2, dict):
    check("repeatability: two runs give identical levels and triangle counts per frame and object",
          histograms(cpu) == histograms(cpu2) and triangles(cpu) == triangles(cpu2)
          and [f["eye"] for f in cpu["frames"]] == [f["eye"] for f in cpu2["frames"]])
    check("the path moves the camera and the levels change along it",
          cpu["frames"][0]["eye"] != cpu["frames"][50]["eye"]
          and len({f["triangles"] for f in cpu["frames"]}) > 10)
else:
    check("repeatability: second run", False, err)

# ---- consistency with a direct scheduler run of frame 0's camera -------------------
if cpu:
    f0 = cpu["frames"][0]
    cow = f0["objects"][0]
    stats = os.path.join(WORK, "direct.json")
    fmt = lambda v: ",".join("%.9g" % x for x in v)
    rc, out, err = run("tessellate", "demo:cow", "-o", os.path.join(WORK, "direct.obj"), "--stats", stats, "-q",
                       "--eye", fmt(f0["eye"]), "--target", fmt(f0["target"]), "--up", fmt(f0["up"]),
                       "--fovy", "%.9g" % f0["fovy"], "--size", SIZE_ARG)
    d = load_json(stats)
    if check("direct run: tlod tessellate demo:cow with frame 0's camera", rc == 0 and isinstance(d, dict), err):
        a = d["adaptive"]
        hist = a["level_histogram"]
        check("frame 0: the cow's level histogram equals the direct run's",
              cow["level_histogram"][:len(hist)] == hist and not any(cow["level_histogram"][len(hist):]),
              (cow["level_histogram"], hist))
        check("frame 0: the cow's pattern / strip triangles and culled patches equal the direct run's",
              cow["pattern_triangles"] == a["pattern_triangles"]
              and cow["strip_triangles"] == a["strip_triangles_planned"] and cow["culled"] == a["culled"]
              and cow["strips"] == a["strips"], (cow, a))
        check("frame 0: the cpu backend realised as many triangles as the direct run wrote",
              cow["drawn_triangles"] == d["output_counts"]["triangles"],
              (cow["drawn_triangles"], d["output_counts"]["triangles"]))

# ---- gl: 100 frames, screenshots every 25 -------------------------------------------
if have_gl:
    gl_dir = os.path.join(WORK, "gl")
    rc, out, err = run("play", "--backend", "gl", "--frames", "100", "--size", SIZE_ARG, "--screenshot-every", "25",
                       "--out", gl_dir, "-q")
    check("gl: 100 frames exit 0", rc == 0, err)
    gl = check_run("gl", gl_dir, 100, "gl", screenshots_every=25)
    if gl and cpu:
        check("gl and cpu: the scheduler gives identical levels and triangle counts on both backends",
              histograms(gl) == histograms(cpu) and triangles(gl) == triangles(cpu))
        check("gl: drawn triangles per frame equal the planned ones",
              all(f["drawn_triangles"] == f["triangles"] for f in gl["frames"]))
    shots = sorted(glob.glob(os.path.join(gl_dir, "screenshots", "*.png")))
    names = [os.path.basename(p) for p in shots]
    check("gl: screenshots/frame_NNNNN.png every 25 frames",
          names == ["frame_%05d.png" % n for n in (0, 25, 50, 75)], names)
    for p in shots:
        try:
            w, h, ctype, colours = png_decode(p)
            check("screenshot %s: valid PNG %dx%d RGBA, not blank (%d colours sampled)" % (
                os.path.basename(p), w, h, len(colours)), (w, h) == SIZE and ctype == 6 and len(colours) > 1)
        except Exception as e:  # noqa: BLE001 -- any decoding problem is a failure
            check("screenshot %s decodes" % os.path.basename(p), False, e)
    rc, out, err = run("play", "--backend", "gl", "--mode", "uniform:2", "--path", "zoom", "--frames", "12",
                       "--size", "128x72", "--out", os.path.join(WORK, "gl_uniform"), "-q")
    check("gl: uniform:2 along the zoom path exits 0", rc == 0, err)
    # --gpu-eval: the choice and why, in the summary and the trace (llvmpipe: auto is the CPU mesh)
    if gl:
        check("gl: auto on llvmpipe draws the CPU mesh and says why (trace gpu_eval)",
              gl["gpu_eval"].startswith("off (auto: llvmpipe"), gl["gpu_eval"])
    on_dir = os.path.join(WORK, "gl_eval_on")
    rc, out, err = run("play", "--backend", "gl", "--gpu-eval", "on", "--frames", "5", "--size", SIZE_ARG,
                       "--out", on_dir)
    on = load_json(os.path.join(on_dir, "trace.json"))
    check("gl: --gpu-eval on is printed and traced; it draws the triangles the CPU mesh drew",
          rc == 0 and "gpu eval: on (asked for: desc.gl.gpu_eval on)" in out and isinstance(on, dict)
          and on["gpu_eval"].startswith("on (asked for") and gl is not None
          and [f["drawn_triangles"] for f in on["frames"]] == [f["drawn_triangles"] for f in gl["frames"][:5]],
          (rc, out[-300:], err))
    rc, out, err = run("play", "--backend", "gl", "--debug-view", "strips", "--frames", "2", "--size", "128x72",
                       "--out", os.path.join(WORK, "gl_eval_strips"))
    check("gl: auto stays on the GPU for --debug-view strips (the CPU mesh carries no strip flag)",
          rc == 0 and "gpu eval: on (auto: --debug-view strips needs it)" in out, (rc, out[-300:], err))
    rc, out, err = run("play", "--backend", "cpu", "--gpu-eval", "off", "--frames", "2")
    check("--gpu-eval with a backend that draws no image is a usage error", rc == 2 and "--gpu-eval" in err, (rc, err))

# ---- --compare -------------------------------------------------------------------------
cmp_dir = os.path.join(WORK, "compare")
rc, out, err = run("play", "--backend", "cpu", "--compare", "adaptive,uniform:2,flat", "--frames", "20", "--size",
                   SIZE_ARG, "--out", cmp_dir)
check("compare: exit 0, summary on stdout", rc == 0 and "uniform:2" in out and "frame ms" in out, (rc, err))
s = load_json(os.path.join(cmp_dir, "summary.json"))
sp = validate_summary(s) if isinstance(s, dict) else ["does not parse"]
check("compare: one combined summary.json with a run per mode",
      not sp and [r["mode"] for r in s["runs"]] == ["adaptive", "uniform:2", "flat"]
      and [r["dir"] for r in s["runs"]] == ["adaptive", "uniform-2", "flat"], sp or s)
traces = {m: load_json(os.path.join(cmp_dir, m, "trace.json")) for m in ("adaptive", "uniform-2", "flat")}
if all(isinstance(x, dict) and not validate(x, TRACE) for x in traces.values()):
    u, fl, ad = traces["uniform-2"], traces["flat"], traces["adaptive"]
    check("compare: uniform:2 puts every visible patch at level 2 (culling applies)",
          all(o["level_histogram"][2] == o["visible"] for f in u["frames"] for o in f["objects"]))
    check("compare: flat puts every visible patch at level 0",
          all(o["level_histogram"][0] == o["visible"] and o["strip_triangles"] == 0
              for f in fl["frames"] for o in f["objects"]))
    if cpu:
        check("compare: its adaptive run repeats the single run frame by frame",
              histograms(ad) == histograms(cpu)[:20] and triangles(ad) == triangles(cpu)[:20])
else:
    check("compare: per-mode traces in subfolders match the schema", False, list(traces))

# ---- a keyframe file -----------------------------------------------------------------
path_file = os.path.join(WORK, "path.json")
keys = [{"time": 0, "eye": [0, 2, 20], "target": [0, 0, 0]},
        {"time": 0.5, "eye": [15, 4, 10], "target": [1, 0, 0], "fovy": 40},
        {"time": 1.5, "eye": [20, 2, -5], "target": [0, 1, 0], "up": [0, 1, 0], "fovy": 50}]
with open(path_file, "w") as f:
    json.dump({"name": "test", "keyframes": keys}, f)
rc, out, err = run("play", "--backend", "cpu", "--path", path_file, "--size", SIZE_ARG, "--out",
                   os.path.join(WORK, "pathfile"), "-q")
t = load_json(os.path.join(WORK, "pathfile", "trace.json"))
if check("path file: plays, one pass by default (1.5 s at 60 fps: 91 frames)",
         rc == 0 and isinstance(t, dict) and len(t["frames"]) == 91, (rc, err)):
    fr = t["frames"]
    close = lambda a, b: all(abs(x - y) < 1e-4 for x, y in zip(a, b))
    check("path file: the spline passes through the keyframes (eye, target, fovy)",
          close(fr[0]["eye"], keys[0]["eye"]) and close(fr[30]["eye"], keys[1]["eye"])
          and close(fr[30]["target"], keys[1]["target"]) and abs(fr[30]["fovy"] - 40) < 1e-4
          and close(fr[90]["eye"], keys[2]["eye"]) and abs(fr[0]["fovy"] - 45) < 1e-4, [fr[i]["eye"] for i in (0, 30, 90)])
    check("path file: fovy linear between keys", abs(fr[15]["fovy"] - 42.5) < 1e-3, fr[15]["fovy"])
rc, out, err = run("play", "--backend", "cpu", "--path", path_file, "--loop", "--frames", "120", "--size", SIZE_ARG,
                   "--out", os.path.join(WORK, "pathloop"), "-q")
t = load_json(os.path.join(WORK, "pathloop", "trace.json"))
check("path file --loop: starts over at the end (frame 90 is frame 0's camera)",
      rc == 0 and isinstance(t, dict) and t["frames"][90]["eye"] == t["frames"][0]["eye"], err)

# ---- bad input: one line, exit 1 or 2, nothing under final names -------------------------
def bad_path(name, content):
    p = os.path.join(WORK, name)
    with open(p, "w") as f:
        f.write(content)
    return p


k0 = '{"time": 0, "eye": [0, 2, 20], "target": [0, 0, 0]}'
bad_glb = sorted(glob.glob(os.path.join(DATA, "glTF-Validator/glb/*.glb")))
bad_cases = [
    ("missing scene file", ["play", os.path.join(WORK, "no_such.obj")], 1),
    ("broken scene file", ["play", bad_glb[0] if bad_glb else os.path.join(WORK, "no.glb")], 1),
    ("path JSON missing 'eye'", ["play", "--path", bad_path("p_missing.json",
                                '{"keyframes": [%s, {"time": 1, "target": [0, 0, 0]}]}' % k0)], 1),
    ("path JSON non-increasing times", ["play", "--path", bad_path("p_times.json",
                                       '{"keyframes": [%s, %s]}' % (k0, k0))], 1),
    ("path JSON with one keyframe", ["play", "--path", bad_path("p_one.json", '{"keyframes": [%s]}' % k0)], 1),
    ("path JSON syntax error", ["play", "--path", bad_path("p_syntax.json", '{"keyframes": [%s,' % k0)], 1),
    ("path file missing", ["play", "--path", os.path.join(WORK, "nope.json")], 1),
    ("unknown backend", ["play", "--backend", "metal"], 2),
    ("--mode uniform:x", ["play", "--mode", "uniform:x"], 2),
    ("--mode uniform:11", ["play", "--mode", "uniform:11"], 2),
    ("--size 0x10", ["play", "--size", "0x10"], 2),
    ("--size 12", ["play", "--size", "12"], 2),
    ("--screenshot-every with cpu", ["play", "--backend", "cpu", "--screenshot-every", "5"], 2),
    ("--frames and --duration", ["play", "--frames", "5", "--duration", "1"], 2),
    ("--compare with one mode", ["play", "--compare", "adaptive"], 2),
    ("unknown option", ["play", "--frob"], 2),
]
for i, (what, args, code) in enumerate(bad_cases):
    out_dir = os.path.join(WORK, "bad%d" % i)
    rc, out, err = run(*args, "--out", out_dir)
    check("bad input: %s -> exit %d, one error line, no output" % (what, code),
          rc == code and one_error_line(err) and not os.path.exists(out_dir), (rc, err, final_files(out_dir)))

# ---- the registry: --backend lists only what this build has; null validates and counts ----
rc, out, err = run("play", "--backend", "metal", "--out", os.path.join(WORK, "vk"))
check("--backend metal: the error names the backends this build has (vulkan: play_vulkan_test.py)",
      rc == 2 and "cpu" in err and "null" in err, (rc, err))
null_dir = os.path.join(WORK, "null_run")
rc, out, err = run("play", "--backend", "null", "--frames", "5", "--size", SIZE_ARG, "-q", "--out", null_dir)
t = load_json(os.path.join(null_dir, "trace.json")) if rc == 0 else None
check("--backend null: plays with the same draw-list counts, drawn_triangles = planned triangles",
      rc == 0 and isinstance(t, dict) and t["backend"] == "null" and len(t["frames"]) == 5
      and all(f["drawn_triangles"] == f["triangles"] > 0 for f in t["frames"]), (rc, err))

# ---- no GL context: the default falls back to cpu, an explicit gl fails -------------------
no_egl = {"__EGL_VENDOR_LIBRARY_FILENAMES": os.path.join(WORK, "no_such_vendor.json")}  # glvnd finds no driver
rc, out, err = run("play", "--frames", "3", "--size", SIZE_ARG, "--out", os.path.join(WORK, "fallback"), env=no_egl)
t = load_json(os.path.join(WORK, "fallback", "trace.json"))
check("no GL context: the default backend falls back to cpu with a note",
      rc == 0 and "playing on the cpu backend" in err and isinstance(t, dict) and t["backend"] == "cpu", (rc, err))
out_dir = os.path.join(WORK, "no_gl")
if BUILT_WITH_GL:
    rc, out, err = run("play", "--backend", "gl", "--frames", "3", "--out", out_dir, env=no_egl)
    check("no GL context: --backend gl fails with the reason, exit 1, no output",
          rc == 1 and one_error_line(err) and "no GL context" in err and not os.path.exists(out_dir), (rc, err))

# ---- SIGINT: stops after the current frame and writes what was played -------------------
int_dir = os.path.join(WORK, "interrupted")
backend = "gl" if have_gl else "cpu"
p = subprocess.Popen([TLOD, "play", "--backend", backend, "--frames", "20000", "--loop", "--size", SIZE_ARG, "--out",
                      int_dir, "-q"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
time.sleep(max(2.5, 8 * startup_s))  # past the set-up, a few frames in (a SIGINT during set-up gives 0 frames)
p.send_signal(signal.SIGINT)
try:
    out, err = p.communicate(timeout=60)
    rc = p.returncode
except subprocess.TimeoutExpired:
    p.kill()
    out, err = p.communicate()
    rc = None
check("SIGINT: exits with 130", rc == 130, (rc, err))
t = load_json(os.path.join(int_dir, "trace.json"))
if check("SIGINT: trace.json written and valid", isinstance(t, dict) and not validate(t, TRACE), t):
    n = t["frames_completed"]
    check("SIGINT: the trace holds the frames so far (0 < frames < requested), marked interrupted",
          0 < n < 20000 and len(t["frames"]) == n and t["stopped"] == "interrupted", (n, t["stopped"]))
    with open(os.path.join(int_dir, "trace.csv")) as f:
        check("SIGINT: trace.csv has a line per frame played", len(f.read().splitlines()) == n + 1)
    c = load_json(os.path.join(int_dir, "chrome_trace.json"))
    s = load_json(os.path.join(int_dir, "summary.json"))
    check("SIGINT: chrome trace and summary written",
          isinstance(c, dict) and isinstance(s, dict) and s["runs"][0]["frames"] == n)

# ---- no arguments: the default run ----------------------------------------------------
if have_gl:
    cwd = os.path.join(WORK, "default")
    os.makedirs(cwd)
    t1 = time.time()
    rc, out, err = run("play", cwd=cwd, timeout=180)
    secs = time.time() - t1
    runs = glob.glob(os.path.join(cwd, "runs", "*"))
    check("no arguments: exit 0, one runs/<timestamp> folder, summary printed (%.1f s)" % secs,
          rc == 0 and len(runs) == 1 and "frame ms" in out and "adaptive" in out, (rc, err, runs))
    if len(runs) == 1:
        files = sorted(os.listdir(runs[0]))
        check("no arguments: the run folder holds the six files",
              files == ["chrome_trace.json", "objects.csv", "summary.json", "summary.txt", "trace.csv", "trace.json"],
              files)
        t = load_json(os.path.join(runs[0], "trace.json"))
        check("no arguments: demo scene, gl, adaptive, orbit, 240 frames at 1280x720",
              isinstance(t, dict) and t["backend"] == "gl" and t["mode"] == "adaptive" and t["path"] == "orbit"
              and t["frames_completed"] == 240 and (t["width"], t["height"]) == (1280, 720)
              and t["scene"] == "demo:scene", t if not isinstance(t, dict) else t["frames_completed"])


# --path gltf: a camera of the scene file, moved by its animation. The file is
# made here: a tetrahedron, a camera node under a parent translated by (0, 1, 0),
# a translation channel with keys at 0, 1, 2 s and a rotation channel
# (quarter turn about y) with keys at 0 and 2 s.
import base64, math
def animated_camera_gltf(path):
    pos = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]
    idx = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
    times_t = [0.0, 1.0, 2.0]
    trans = [0, 0, 5, 2, 0, 5, 2, 2, 6]
    times_r = [0.0, 2.0]
    s = math.sqrt(0.5)
    rot = [0, 0, 0, 1, 0, s, 0, s]
    blob = struct.pack("<12f", *pos) + struct.pack("<12H", *idx) + struct.pack("<3f", *times_t) + \
        struct.pack("<9f", *trans) + struct.pack("<2f", *times_r) + struct.pack("<8f", *rot)
    views, off = [], 0
    for n in (48, 24, 12, 36, 8, 32):
        views.append({"buffer": 0, "byteOffset": off, "byteLength": n})
        off += n
    g = {"asset": {"version": "2.0"}, "scene": 0,
         "scenes": [{"nodes": [0, 1]}],
         "nodes": [{"mesh": 0}, {"translation": [0, 1, 0], "children": [2]}, {"camera": 0}],
         "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
         "accessors": [
             {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
             {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"},
             {"bufferView": 2, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
             {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"},
             {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [2]},
             {"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC4"}],
         "bufferViews": views,
         "buffers": [{"byteLength": len(blob),
                      "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
         "animations": [{"channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}},
                                      {"sampler": 1, "target": {"node": 2, "path": "rotation"}}],
                         "samplers": [{"input": 2, "output": 3}, {"input": 4, "output": 5}]}]}
    with open(path, "w") as f:
        json.dump(g, f)

cam_file = os.path.join(WORK, "animated_camera.gltf")
animated_camera_gltf(cam_file)
out = os.path.join(WORK, "gltf_path")
rc, so, se = run("play", cam_file, "--backend", "cpu", "--path", "gltf", "--fps", "10", "--out", out, "-q")
t = load_json(os.path.join(out, "trace.json")) if rc == 0 else None
frames = t["frames"] if isinstance(t, dict) else []
def near(a, b, tol=1e-4):
    return all(abs(x - y) <= tol for x, y in zip(a, b))
ok = len(frames) == 21
if ok:
    f0, f10, f20 = frames[0], frames[10], frames[20]
    ok = near(f0["eye"], [0, 1, 5]) and near(f10["eye"], [2, 1, 5]) and near(f20["eye"], [2, 3, 6])
    # at 0 s the camera looks down -z; at 2 s a quarter turn about y makes it look down -x
    d0 = [f0["target"][i] - f0["eye"][i] for i in range(3)]
    d2 = [f20["target"][i] - f20["eye"][i] for i in range(3)]
    ok = ok and near(d0, [0, 0, -1]) and near(d2, [-1, 0, 0], 1e-3) and abs(f0["fovy"] - math.degrees(0.8)) < 1e-3
check("--path gltf: the file's camera, parent transform and animation (21 frames at 10 fps)", ok,
      se if rc else str([(f["eye"], f["target"]) for f in frames[:1] + frames[10:11] + frames[20:21]]))
rc, so, se = run("play", cam_file, "--backend", "cpu", "--path", "gltf:3", "--out", os.path.join(WORK, "gltf_bad"))
check("--path gltf:3 on a file with one camera: exit 1, one line naming it",
      rc == 1 and one_error_line(se) and "camera 3" in se and not os.path.exists(os.path.join(WORK, "gltf_bad")), se)
rc, so, se = run("play", "--backend", "cpu", "--path", "gltf", "--out", os.path.join(WORK, "gltf_demo"))
check("--path gltf on the demo scene: exit 2", rc == 2 and one_error_line(se), se)

tmp = [p for p in glob.glob(os.path.join(WORK, "**", "*.tmp*"), recursive=True)]
check("no temporary files left anywhere", not tmp, tmp)

print("(%.0f s)" % (time.time() - t0))
finish()
