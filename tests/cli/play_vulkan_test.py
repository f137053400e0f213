#!/usr/bin/env python3
"""End-to-end tests of `tlod play --backend vulkan` and `tlod bench --backend vulkan` (docs/play.md "Vulkan"), on
lavapipe: a generated multi-object animated glTF scene played 100 frames under the validation layer with a resize in
the middle (exit 0, no validation message, every frame's drawn triangles equal to its draw lists' and to the gl run's
on the same scene and camera path); image parity of gl and vulkan screenshots of the same frames within the tolerance
of docs/play.md "Parity with gl"; the SPIR-V cache (a second start compiles nothing, counted in summary.json); a
--shader-cache folder that cannot be made is an error, a default one a warning; a Vulkan that cannot start (no
driver, no validation layer) is an error, never a fallback; --window under Xvfb; usage errors;
bench --suite objects / vkstart on vulkan. Usage: play_vulkan_test.py TLOD DATA_DIR WORK_DIR [vk|novk]"""
import math, os, subprocess, sys

from gltf_write import Gltf, camera_file, cube, sphere
from png_read import png_rows
from tlod_cli import check, finish, load_json, one_error_line, run, setup

TLOD, DATA, WORK, _ = setup(sys.argv[:4])
BUILT_WITH_VULKAN = (sys.argv[4] if len(sys.argv) > 4 else "vk") == "vk"
W, H = 320, 200
RW, RH = 256, 160  # --resize-at 50:256x160
FRAMES = 100
CLEAR = (28, 31, 36)  # play_loop.c play_clear_rgba (0.11, 0.12, 0.14) in 8 bits
# Parity (docs/play.md "Parity with gl"): at least 99% of the pixels within 8/255 on every channel, and no pixel that is
# background in one image and object in the other unless it is an edge pixel (its 3x3 neighbourhood holds both).
PARITY_CHANNEL, PARITY_SHARE = 8, 0.99

if not BUILT_WITH_VULKAN:
    rc, so, se = run("play", "--backend", "vulkan", "--frames", "1", "--out", os.path.join(WORK, "novk"))
    check("novk: --backend vulkan is a usage error naming the build's backends (exit 2)",
          rc == 2 and one_error_line(se) and "vulkan" in se, (rc, se))
    finish()


# ---- the scene: six objects (one mesh drawn twice), three of them animated -----------------

def animated_scene(path):
    g = Gltf()
    pos, nrm, idx = cube(0.5)
    mats = [g.material(c) for c in ((1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (1, 1, 0, 1), (0.8, 0.8, 0.8, 1))]
    red, green, blue, yellow = (g.mesh(pos, nrm, idx, m) for m in mats[:4])
    ball = g.mesh(*sphere(0.8), mats[4])
    g.node(name="red_a", mesh=red, translation=[-3, 0, 0])
    g.node(name="red_b", mesh=red, translation=[-1, 1.2, 0])  # the same mesh again: an instance
    g.node(name="slider", mesh=green, translation=[1, 0, 0])
    g.node(name="spinner", mesh=blue, translation=[3, -1, 0])
    g.node(name="yellow", mesh=yellow, translation=[0, -1.5, 1], rotation=[0, math.sin(0.3), 0, math.cos(0.3)])
    g.node(name="ball", mesh=ball, translation=[0, 0.3, -1])
    times = g.accessor("f", [0.0, 1.0, 2.0], "SCALAR", minmax=([0.0], [2.0]))
    slide = g.accessor("f", [1, 0, 0, 1, 1.5, 0, 1, 0, 0], "VEC3")
    half = math.sqrt(0.5)
    spin = g.accessor("f", [0, 0, 0, 1, 0, half, 0, half, 0, 1, 0, 0], "VEC4")
    grow = g.accessor("f", [1, 1, 1, 1.4, 1.4, 1.4, 1, 1, 1], "VEC3")
    g.g["animations"] = [{"name": "move", "channels": [
        {"sampler": 0, "target": {"node": 2, "path": "translation"}},
        {"sampler": 1, "target": {"node": 3, "path": "rotation"}},
        {"sampler": 2, "target": {"node": 5, "path": "scale"}}],
        "samplers": [{"input": times, "output": slide}, {"input": times, "output": spin},
                     {"input": times, "output": grow}]}]
    g.save(path)


SCENE = os.path.join(WORK, "animated.gltf")
animated_scene(SCENE)
CAM = os.path.join(WORK, "camera.json")
camera_file(CAM, [0, 1, 12], [0, 0, 0], 40)


def play(backend, out, *extra):
    return run("play", SCENE, "--backend", backend, "--size", "%dx%d" % (W, H), "--path", CAM, "--out", out,
               "--shader-cache", os.path.join(WORK, "cache_play"), *extra)


def frames_of(out):
    t = load_json(os.path.join(out, "trace.json"))
    return t.get("frames", []) if isinstance(t, dict) else []


# ---- (a) 100 frames under the validation layer, resized at frame 50 ---------------------

VK, GL = os.path.join(WORK, "vk"), os.path.join(WORK, "gl")
common = ("--frames", str(FRAMES), "--loop", "--resize-at", "50:%dx%d" % (RW, RH), "--screenshot-every", "25", "-q")
rc, so, se = play("vulkan", VK, "--validate", *common)
s = load_json(os.path.join(VK, "summary.json")) if rc == 0 else {}
s = s if isinstance(s, dict) else {}
check("validate: 100 frames of the animated scene on vulkan with a resize at frame 50 (exit 0)", rc == 0, se)
check("validate: summary.json says the layer was on and counted 0 messages (session and run)",
      s.get("validate") is True and s.get("validation_messages") == 0 and
      [r.get("validation_messages") for r in s.get("runs", [])] == [0] and s.get("backend") == "vulkan", s)
check("validate: nothing from the layer on stderr",
      not any(k in se for k in ("VUID", "Validation", "SYNC-")), se)
t = load_json(os.path.join(VK, "trace.json")) if rc == 0 else {}
check("validate: every frame played, 6 objects, animation 'move'",
      s.get("runs", [{}])[0].get("frames") == FRAMES and s.get("animation") == "move" and
      isinstance(t, dict) and len(t.get("objects", [])) == 6, s.get("runs"))
check("validate: the resize is in the summary",
      s.get("resize_at") == {"frame": 50, "width": RW, "height": RH}, s.get("resize_at"))
vk_frames = frames_of(VK)
check("triangles: every vulkan frame draws exactly its draw lists' triangles",
      len(vk_frames) == FRAMES and all(f["drawn_triangles"] == f["triangles"] > 0 for f in vk_frames),
      [(f["frame"], f["triangles"], f["drawn_triangles"]) for f in vk_frames
       if f["drawn_triangles"] != f["triangles"]][:5])

rc, so, se = play("gl", GL, *common)
check("gl: the same scene, path and resize on gl (exit 0)", rc == 0, se)
gl_frames = frames_of(GL)
check("triangles: gl and vulkan draw the same triangles every frame (draw lists and drawn)",
      len(gl_frames) == FRAMES and
      [(f["triangles"], f["drawn_triangles"]) for f in gl_frames] ==
      [(f["triangles"], f["drawn_triangles"]) for f in vk_frames],
      [(a["frame"], a["triangles"], b["triangles"]) for a, b in zip(gl_frames, vk_frames)
       if a["triangles"] != b["triangles"]][:5])
check("triangles: the resize changes the levels (the viewport reached the scheduler)",
      len(vk_frames) == FRAMES and vk_frames[49]["triangles"] != vk_frames[50]["triangles"],
      [f["triangles"] for f in vk_frames[48:52]])
sg = load_json(os.path.join(GL, "summary.json")) if rc == 0 else {}
sg = sg if isinstance(sg, dict) else {}
pick = lambda j: [(r["triangles"], r["drawn_triangles_mean"], r["pattern_triangles_mean"], r["culled_mean"])
                  for r in j.get("runs", [])]
check("triangles: summary numbers equal for gl and vulkan", pick(sg) and pick(sg) == pick(s), (pick(sg), pick(s)))


# ---- (b) image parity of the screenshots ------------------------------------------------

def is_background(p):
    return all(abs(a - b) <= 3 for a, b in zip(p, CLEAR))


def parity(path_a, path_b):
    """(share of pixels within PARITY_CHANNEL, class mismatches off the edges, size) of two RGBA screenshots."""
    wa, ha, bpp, _, ra = png_rows(path_a)
    wb, hb, _, _, rb = png_rows(path_b)
    if (wa, ha) != (wb, hb):
        return 0.0, -1, (wa, ha, wb, hb)
    px = lambda rows, x, y: tuple(rows[y][x * bpp:x * bpp + 3])
    cls_a = [[is_background(px(ra, x, y)) for x in range(wa)] for y in range(ha)]
    cls_b = [[is_background(px(rb, x, y)) for x in range(wa)] for y in range(ha)]
    close = hard = 0
    for y in range(ha):
        for x in range(wa):
            a, b = px(ra, x, y), px(rb, x, y)
            close += all(abs(i - j) <= PARITY_CHANNEL for i, j in zip(a, b))
            if cls_a[y][x] == cls_b[y][x]:
                continue
            near = {c[yy][xx] for c in (cls_a, cls_b) for yy in range(max(0, y - 1), min(ha, y + 2))
                    for xx in range(max(0, x - 1), min(wa, x + 2))}
            hard += len(near) < 2
    return close / float(wa * ha), hard, (wa, ha)


shots = []
for k in (0, 25, 50, 75):
    name = os.path.join("screenshots", "frame_%05d.png" % k)
    a, b = os.path.join(GL, name), os.path.join(VK, name)
    shots.append((k,) + (parity(a, b) if os.path.exists(a) and os.path.exists(b) else (0.0, -1, None)))
check("parity: gl and vulkan screenshots of frames 0, 25, 50, 75: >= 99% of pixels within 8/255, no background/"
      "object mismatch off the edges", all(share >= PARITY_SHARE and hard == 0 for _, share, hard, _ in shots), shots)
check("parity: the screenshots after the resize are %dx%d" % (RW, RH),
      [size for k, _, _, size in shots if k >= 50] == [(RW, RH)] * 2, shots)
objects = 0
img = png_rows(os.path.join(VK, "screenshots", "frame_00000.png")) if shots[0][3] else None
if img:
    objects = sum(not is_background(tuple(r[x * img[2]:x * img[2] + 3])) for r in img[4] for x in range(img[0]))
check("parity: the vulkan image is not empty (objects cover > 3% of it)", objects > 0.03 * W * H, objects)


# ---- (c) the shader cache: a second start compiles nothing --------------------------------

def vk_stats(out):
    j = load_json(os.path.join(out, "summary.json"))
    return (j.get("runs") or [{}])[0].get("vk", {}) if isinstance(j, dict) else {}, j


CACHE = os.path.join(WORK, "cache_c")
rc1, _, se1 = run("play", SCENE, "--backend", "vulkan", "--frames", "3", "--size", "160x100", "--shader-cache",
                  CACHE, "--out", os.path.join(WORK, "cache1"), "-q")
rc2, _, se2 = run("play", SCENE, "--backend", "vulkan", "--frames", "3", "--size", "160x100", "--shader-cache",
                  CACHE, "--out", os.path.join(WORK, "cache2"), "-q")
v1, j1 = vk_stats(os.path.join(WORK, "cache1"))
v2, j2 = vk_stats(os.path.join(WORK, "cache2"))
check("cache: both starts play (exit 0)", rc1 == 0 and rc2 == 0, (se1, se2))
check("cache: the first start compiles its stages and finds none cached",
      v1.get("shader_compiles", 0) > 0 and v1.get("shader_cache_hits") == 0, v1)
check("cache: the second start compiles 0 stages and loads every one from the cache",
      v2.get("shader_compiles") == 0 and v2.get("shader_cache_hits") == v1.get("shader_compiles"), (v1, v2))
check("cache: summary.json names the folder, which holds .spv files",
      isinstance(j2, dict) and j2.get("shader_cache") == CACHE and os.path.isdir(CACHE) and
      any(f.endswith(".spv") for f in os.listdir(CACHE)), j2.get("shader_cache") if isinstance(j2, dict) else j2)
rc, _, se = run("play", SCENE, "--backend", "vulkan", "--frames", "2", "--size", "160x100", "--shader-cache", "off",
                "--out", os.path.join(WORK, "cache_off"), "-q")
v3, j3 = vk_stats(os.path.join(WORK, "cache_off"))
check("cache: --shader-cache off compiles every start (no folder in the summary)",
      rc == 0 and v3.get("shader_compiles", 0) > 0 and v3.get("shader_cache_hits") == 0 and
      j3.get("shader_cache") == "", (rc, se, v3))

# ---- (d) a shader cache that cannot be had -------------------------------------------------

A_FILE = os.path.join(WORK, "a_file")
open(A_FILE, "w").write("not a folder\n")
BAD = os.path.join(A_FILE, "cache")
out = os.path.join(WORK, "bad_cache")
rc, so, se = run("play", SCENE, "--backend", "vulkan", "--frames", "1", "--shader-cache", BAD, "--out", out)
check("bad cache: a --shader-cache folder that cannot be made is an error naming it (exit 1, one line)",
      rc == 1 and one_error_line(se) and "--shader-cache" in se and BAD in se and "Not a directory" in se, (rc, se))
check("bad cache: nothing was played (no run folder)", not os.path.exists(out))
out = os.path.join(WORK, "bad_default")
rc, so, se = run("play", SCENE, "--backend", "vulkan", "--frames", "1", "--size", "160x100", "--out", out,
                 env={"HOME": A_FILE, "XDG_CACHE_HOME": ""})
j = load_json(os.path.join(out, "summary.json")) if rc == 0 else {}
check("bad cache: an unusable default folder is a warning naming it, and the run plays without a disk cache",
      rc == 0 and "tlod: warning: no shader cache: cannot create folder '%s/.cache/tesslod'" % A_FILE in se and
      isinstance(j, dict) and j.get("shader_cache") == "", (rc, se))

# ---- a Vulkan that cannot start: an error, never a fallback ----------------------------------

EMPTY = os.path.join(WORK, "no_layers")
os.makedirs(EMPTY)
out = os.path.join(WORK, "no_layer")
rc, so, se = run("play", SCENE, "--backend", "vulkan", "--validate", "--frames", "1", "--out", out,
                 env={"VK_LAYER_PATH": EMPTY})
check("no layer: --validate without the validation layer fails naming it (exit 1, one line, nothing played)",
      rc == 1 and one_error_line(se) and "VK_LAYER_KHRONOS_validation" in se and not os.path.exists(out), (rc, se))
out = os.path.join(WORK, "no_driver")
rc, so, se = run("play", SCENE, "--backend", "vulkan", "--frames", "1", "--out", out,
                 env={"VK_DRIVER_FILES": os.path.join(WORK, "no_such_icd.json")})
check("no driver: --backend vulkan without a Vulkan driver fails with the reason, no fallback (exit 1, one line)",
      rc == 1 and one_error_line(se) and "--backend vulkan: vkCreateInstance" in se and "cpu" not in se and
      not os.path.exists(out), (rc, se))

# ---- usage errors ----------------------------------------------------------------------------

for args, what in ((("--backend", "gl", "--validate"), "--validate"),
                   (("--backend", "vulkan", "--resize-at", "640x480"), "--resize-at"),
                   (("--backend", "vulkan", "--resize-at", "5:0x10"), "--resize-at"),
                   (("--backend", "cpu", "--screenshot-every", "1"), "--screenshot-every")):
    rc, so, se = run("play", SCENE, "--frames", "1", "--out", os.path.join(WORK, "usage"), *args)
    check("usage: %s is a usage error naming %s (exit 2)" % (" ".join(args), what),
          rc == 2 and one_error_line(se) and what in se, (rc, se))

# ---- --window: a GLFW window and swapchain under Xvfb ----------------------------------------

out = os.path.join(WORK, "window")
p = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24", TLOD, "play", SCENE, "--backend", "vulkan",
                    "--window", "--frames", "20", "--size", "%dx%d" % (W, H), "--resize-at", "10:%dx%d" % (RW, RH),
                    "--screenshot-every", "19", "--shader-cache", os.path.join(WORK, "cache_play"), "--out", out,
                    "-q"], capture_output=True, text=True, timeout=300)
j = load_json(os.path.join(out, "summary.json")) if p.returncode == 0 else {}
check("window: vulkan plays 20 frames into a window with a swapchain resize (exit 0)",
      p.returncode == 0 and isinstance(j, dict) and j["runs"][0]["frames"] == 20 and "window" not in
      j["runs"][0]["stopped"], (p.returncode, p.stderr[-2000:]))
check("window: the screenshot of the last frame is the resized size",
      p.returncode == 0 and png_rows(os.path.join(out, "screenshots", "frame_00019.png"))[:2] == (RW, RH))

# ---- bench on vulkan ---------------------------------------------------------------------------

rc, so, se = run("bench", "--suite", "vkstart", "--repeat", "1", timeout=600)
filled = next((l for l in so.splitlines() if l.startswith("vkstart ") and "filled cache" in l), "")
check("bench vkstart: runs (exit 0) and the filled-cache start compiles 0 stages",
      rc == 0 and " 0 compiled" in filled and " 0 from the cache" not in filled, (rc, so, se))
rc, so, se = run("bench", "--suite", "objects", "--backend", "vulkan", "--frames", "2",
                 "--shader-cache", os.path.join(WORK, "cache_play"), timeout=600)
lines = [l for l in so.splitlines() if l.startswith("objects    vulkan")]
check("bench objects --backend vulkan: cpu and vulkan rows (exit 0)", rc == 0 and len(lines) == 4, (rc, so, se))
rc, so, se = run("bench", "--suite", "gl", "--backend", "cpu")
check("bench: --backend cpu is a usage error (the suites that draw need gl or vulkan)",
      rc == 2 and one_error_line(se), (rc, se))

finish()
