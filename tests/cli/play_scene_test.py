#!/usr/bin/env python3
"""End-to-end tests of `tlod play` on glTF scenes (docs/play.md "glTF scenes"): generated scenes of several nodes,
materials, an instanced mesh and a node hierarchy drawn in their colours at their transforms (pixels at screen
positions computed here from the camera), a textured quad whose pixels match its texels under the known light, the
Duck with its texture, node animation along the timeline, a skinned scene's per-object counts, --animation, and the
importer's warnings printed once and kept in the trace and summary.
Usage: play_scene_test.py TLOD DATA_DIR WORK_DIR [gl|nogl]"""
import base64, csv, math, os, sys

from gltf_write import Gltf, camera_file, cube, png_bytes, sphere
from png_read import pixel, png_rows
from tlod_cli import check, finish, load_json, setup, run

TLOD, DATA, WORK, BUILT_WITH_GL = setup(sys.argv)
W, H = 320, 200
LIGHT = (0.3, 0.8, 0.5)  # tesslod/backend.h: the default light direction
LAMBERT_Z = 0.15 + 0.85 * LIGHT[2] / math.sqrt(sum(c * c for c in LIGHT))  # a face looking along +z


def project(p, eye, target, fovy):
    """Pixel (x, y from the top) of world point p seen by a look-at camera (up +y) at W x H."""
    f = [t - e for t, e in zip(target, eye)]
    fl = math.sqrt(sum(c * c for c in f))
    f = [c / fl for c in f]
    s = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]  # f x up
    sl = math.sqrt(sum(c * c for c in s))
    s = [c / sl for c in s]
    u = [s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]]
    d = [a - b for a, b in zip(p, eye)]
    x, y, z = sum(a * b for a, b in zip(s, d)), sum(a * b for a, b in zip(u, d)), sum(a * b for a, b in zip(f, d))
    k = 1 / math.tan(math.radians(fovy) / 2)
    nx, ny = k * x / z / (W / H), k * y / z
    return int((nx * 0.5 + 0.5) * W), int((1 - (ny * 0.5 + 0.5)) * H)


def play(scene, out, *extra, backend="gl"):
    return run("play", scene, "--backend", backend, "--size", "%dx%d" % (W, H), "--out", out, *extra)


def dominant(rgb):
    """'r', 'g', 'b', 'y' (red + green) or '-' (dark / grey): the colour a pixel shows."""
    r, g, b = rgb
    if max(rgb) < 40:
        return "-"
    hi = [c >= 0.6 * max(rgb) for c in rgb]
    return {(1, 0, 0): "r", (0, 1, 0): "g", (0, 0, 1): "b", (1, 1, 0): "y"}.get(tuple(int(x) for x in hi), "-")


# ---- 1. nodes, materials, an instanced mesh, a hierarchy ---------------------------

EYE, TARGET, FOVY = [0, 0, 12], [0, 0, 0], 40
g = Gltf()
pos, nrm, idx = cube(0.5)
red, green, blue, yellow = (g.material(c) for c in ((1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (1, 1, 0, 1)))
m_red, m_green, m_blue, m_yellow = (g.mesh(pos, nrm, idx, m) for m in (red, green, blue, yellow))
g.node(name="red_a", mesh=m_red, translation=[-3, 0, 0])
g.node(name="red_b", mesh=m_red, translation=[-1, 1, 0])            # the same mesh again: an instance
g.node(name="green", mesh=m_green, translation=[1, 0, 0], scale=[0.8, 0.8, 0.8])
child = g.node(root=False, name="blue", mesh=m_blue, translation=[1, -1, 0])
g.node(name="parent", translation=[2, 0, 0], children=[child])     # blue ends at (3, -1, 0)
g.node(name="yellow", mesh=m_yellow, translation=[0, -1.5, 0], rotation=[0, math.sin(0.3), 0, math.cos(0.3)])
SCENE = os.path.join(WORK, "scene.gltf")
g.save(SCENE)
CAM = os.path.join(WORK, "camera.json")
camera_file(CAM, EYE, TARGET, FOVY)
WHERE = {"red_a": ([-3, 0, 0], "r"), "red_b": ([-1, 1, 0], "r"), "green": ([1, 0, 0], "g"),
         "blue": ([3, -1, 0], "b"), "yellow": ([0, -1.5, 0], "y")}
GAPS = [[-2, 0, 0], [2, 1, 0], [0, 1.2, 0]]  # between the objects: background

out = os.path.join(WORK, "nodes_cpu")
rc, so, se = play(SCENE, out, "--frames", "2", "--path", CAM, "-q", backend="cpu")
t = load_json(os.path.join(out, "trace.json")) if rc == 0 else {}
objs = t.get("objects", []) if isinstance(t, dict) else []
check("scene: plays on cpu (exit 0)", rc == 0, se)
check("scene: one object per node with a mesh, named after the nodes",
      sorted(o["name"] for o in objs) == sorted(WHERE), [o["name"] for o in objs])
by = {o["name"]: o for o in objs}
check("scene: the instanced mesh is one surface drawn twice, the others have their own",
      len(objs) == 5 and by["red_a"]["surface"] == by["red_b"]["surface"] and
      len({o["surface"] for o in objs}) == 4, [(o["name"], o["surface"]) for o in objs])
check("scene: each object has its material's colour",
      by and by["green"]["color"] == [0, 1, 0, 1] and by["blue"]["color"] == [0, 0, 1, 1], objs)
rows = list(csv.DictReader(open(os.path.join(out, "objects.csv")))) if rc == 0 else []
check("scene: objects.csv has a row per frame and object with its counts",
      len(rows) == 10 and all(int(r["triangles"]) >= 12 and int(r["patches"]) == 12 for r in rows),
      rows[:3])
frames = t.get("frames", []) if isinstance(t, dict) else []
check("scene: frame totals are the sum of the objects' rows",
      frames and sum(int(r["triangles"]) for r in rows if r["frame"] == "0") == frames[0]["triangles"])

if BUILT_WITH_GL:
    out = os.path.join(WORK, "nodes_gl")
    rc, so, se = play(SCENE, out, "--frames", "1", "--path", CAM, "--screenshot-every", "1", "-q")
    check("scene: plays on gl with a screenshot (exit 0)", rc == 0, se)
    img = png_rows(os.path.join(out, "screenshots", "frame_00000.png")) if rc == 0 else None
    seen = {n: dominant(pixel(img, *project(p, EYE, TARGET, FOVY))) for n, (p, c) in WHERE.items()} if img else {}
    check("scene: every object shows its colour at its projected position (instances, hierarchy, scale, rotation)",
          seen == {n: c for n, (p, c) in WHERE.items()}, seen)
    gaps = [dominant(pixel(img, *project(p, EYE, TARGET, FOVY))) for p in GAPS] if img else []
    check("scene: the background between them", gaps == ["-"] * len(GAPS), gaps)

# ---- 2. a textured quad: pixels = texel (sRGB decoded) x Lambert of the known light ----

TEXELS = [[(255, 0, 0, 255), (0, 255, 0, 255)], [(0, 0, 255, 255), (188, 188, 188, 255)]]
g = Gltf()
img = png_bytes(2, 2, [sum((list(t) for t in row), []) for row in TEXELS])
g.g["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(img).decode()}]
g.g["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
g.g["textures"] = [{"source": 0, "sampler": 0}]
quad = g.mesh([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], [0, 0, 1] * 4, [0, 1, 2, 0, 2, 3],
              g.material((1, 1, 1, 1), texture=0), uv=[0, 1, 1, 1, 1, 0, 0, 0])
g.node(name="quad", mesh=quad)
QUAD = os.path.join(WORK, "quad.gltf")
g.save(QUAD)
QEYE = [0, 0, 4]
camera_file(CAM, QEYE, [0, 0, 0], 40)


def srgb_to_linear(c):
    c /= 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


if BUILT_WITH_GL:
    out = os.path.join(WORK, "quad_gl")
    rc, so, se = play(QUAD, out, "--frames", "1", "--path", CAM, "--screenshot-every", "1", "-q")
    check("texture: the textured quad plays on gl (exit 0)", rc == 0, se)
    shot = png_rows(os.path.join(out, "screenshots", "frame_00000.png")) if rc == 0 else None
    bad = []
    for (px, py, row, col) in ((-0.5, 0.5, 0, 0), (0.5, 0.5, 0, 1), (-0.5, -0.5, 1, 0), (0.5, -0.5, 1, 1)):
        want = [255 * srgb_to_linear(c) * LAMBERT_Z for c in TEXELS[row][col][:3]]
        got = pixel(shot, *project([px, py, 0], QEYE, [0, 0, 0], 40)) if shot else (0, 0, 0)
        if any(abs(a - b) > 4 for a, b in zip(got, want)):
            bad.append((row, col, got, [round(w, 1) for w in want]))
    check("texture: each quadrant shows its texel, sRGB-decoded, times 0.15 + 0.85 max(n.l, 0) (within 4/255)",
          shot is not None and not bad, bad)
    t = load_json(os.path.join(out, "trace.json")) if rc == 0 else {}
    check("texture: the object is marked textured", isinstance(t, dict) and t.get("objects", [{}])[0].get("textured"))

# ---- 3. the Duck with its texture ------------------------------------------------

DUCK = os.path.join(DATA, "glTF-Sample-Models", "Duck", "glTF-Binary", "Duck.glb")
if BUILT_WITH_GL:
    out = os.path.join(WORK, "duck_gl")
    rc, so, se = play(DUCK, out, "--frames", "1", "--screenshot-every", "1", "-q")
    check("duck: plays on gl (exit 0)", rc == 0, se)
    shot = png_rows(os.path.join(out, "screenshots", "frame_00000.png")) if rc == 0 else None
    px = [pixel(shot, x, y) for y in range(0, H, 4) for x in range(0, W, 4)] if shot else []
    duck = [p for p in px if max(p) > 60]
    yellow = [p for p in duck if p[0] > 1.1 * p[2] + 20 and p[1] > 1.1 * p[2] and p[0] >= p[1]]
    red = [p for p in duck if p[0] > 2 * p[1] + 20 and p[0] > 2 * p[2] + 20]
    grey = [p for p in duck if max(p) - min(p) < 12]
    # DuckCM.png: a yellow-orange body (r >= g >> b) and a red beak; white material would be grey.
    check("duck: its pixels take the texture's colours (mostly yellow-orange, some red beak, no grey)",
          len(duck) > 200 and len(yellow) > 0.6 * len(duck) and len(red) > 5 and len(grey) < 0.05 * len(duck),
          (len(duck), len(yellow), len(red), len(grey)))
    t = load_json(os.path.join(out, "trace.json")) if rc == 0 else {}
    check("duck: one textured object at the node's scale (a few thousand triangles, not millions)",
          isinstance(t, dict) and t["objects"][0]["textured"] and 500 < t["frames"][0]["triangles"] < 200000,
          t.get("frames", [{}])[0].get("triangles") if isinstance(t, dict) else t)

# ---- 4. node animation along the timeline ---------------------------------------------

g = Gltf()
m = g.mesh(pos, nrm, idx, g.material((1, 0, 0, 1)))
g.node(name="mover", mesh=m)
times = g.accessor("f", [0.0, 1.0], "SCALAR", minmax=([0.0], [1.0]))
moves = g.accessor("f", [-2, 0, 0, 2, 0, 0], "VEC3")
g.g["animations"] = [{"name": "slide", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                      "samplers": [{"input": times, "output": moves}]}]
ANIM = os.path.join(WORK, "anim.gltf")
g.save(ANIM)
camera_file(CAM, EYE, TARGET, FOVY)
out = os.path.join(WORK, "anim_cpu")
rc, so, se = play(ANIM, out, "--frames", "4", "--fps", "4", "--path", CAM, "-q", backend="cpu")
t = load_json(os.path.join(out, "trace.json")) if rc == 0 else {}
check("animation: the first animation plays by default, its duration in the trace",
      rc == 0 and t["animation"] == "slide" and t["animation_duration_s"] == 1 and
      all(f["anim_ms"] > 0 for f in t["frames"]), (rc, se, t.get("animation") if isinstance(t, dict) else t))
rc, so, se = play(ANIM, os.path.join(WORK, "anim_none"), "--frames", "2", "--animation", "none", "-q",
                  backend="cpu")
t = load_json(os.path.join(WORK, "anim_none", "trace.json")) if rc == 0 else {}
check("animation: --animation none plays the rest pose", rc == 0 and t["animation"] == "" and
      all(f["anim_ms"] == 0 for f in t["frames"]), se)
rc, so, se = play(ANIM, os.path.join(WORK, "anim_0"), "--frames", "1", "--animation", "0", "-q", backend="cpu")
check("animation: --animation 0 (by index) plays", rc == 0, se)
rc, so, se = play(ANIM, os.path.join(WORK, "anim_bad"), "--frames", "1", "--animation", "walk", "-q", backend="cpu")
check("animation: --animation with an unknown name is a usage error naming it (exit 2)",
      rc == 2 and "walk" in se and "1 animation" in se, (rc, se))
if BUILT_WITH_GL:
    out = os.path.join(WORK, "anim_gl")
    # 4 fps: t = 0, 0.25, 0.5, 0.75 s -> x = -2, -1, 0, 1 (linear), then it loops.
    rc, so, se = play(ANIM, out, "--frames", "4", "--fps", "4", "--path", CAM, "--screenshot-every", "1", "-q")
    seen = []
    for k, x in enumerate((-2, -1, 0, 1)):
        shot = png_rows(os.path.join(out, "screenshots", "frame_%05d.png" % k)) if rc == 0 else None
        at = dominant(pixel(shot, *project([x, 0, 0], EYE, TARGET, FOVY))) if shot else "?"
        left = dominant(pixel(shot, *project([x - 1, 0, 0], EYE, TARGET, FOVY))) if shot else "?"
        seen.append((at, left))
    check("animation: the cube is where the channel puts it at each frame's time (and not where it was)",
          seen == [("r", "-")] * 4, seen)

# ---- 5. a skinned, animated scene: per-object counts, skinned surfaces -------------------

SKIN = os.path.join(DATA, "glTF-Sample-Models", "SimpleSkin", "SimpleSkin.gltf")
out = os.path.join(WORK, "skin_cpu")
rc, so, se = play(SKIN, out, "--frames", "12", "--fps", "2", "-q", backend="cpu")
t = load_json(os.path.join(out, "trace.json")) if rc == 0 else {}
rows = list(csv.DictReader(open(os.path.join(out, "objects.csv")))) if rc == 0 else []
check("skin: SimpleSkin plays, its object skinned, its animation along the timeline",
      rc == 0 and t["objects"][0]["skinned"] and t["animation_duration_s"] > 0 and
      all(f["anim_ms"] > 0 for f in t["frames"]), (rc, se))
check("skin: per-object patch and triangle counts every frame (trace frames and objects.csv agree)",
      len(rows) == 12 and all(int(r["triangles"]) == f["objects"][0]["triangles"] and
                              int(r["patches"]) == f["objects"][0]["patches"] for r, f in zip(rows, t["frames"])),
      rows[:2])

# ---- 6. importer warnings: printed once, kept in the trace and summary ------------------

g = Gltf()
g.g["images"] = [{"uri": "missing.png"}]
g.g["textures"] = [{"source": 0}]
m = g.mesh(pos, nrm, idx, g.material((0, 1, 0, 1), texture=0), uv=[0, 0] * 24)
g.node(name="box", mesh=m)
WARN = os.path.join(WORK, "warn.gltf")
g.save(WARN)
out = os.path.join(WORK, "warn_cpu")
rc, so, se = play(WARN, out, "--frames", "2", "--compare", "adaptive,flat", backend="cpu")
lines = [l for l in se.splitlines() if "missing.png" in l]
check("warnings: a missing texture is one warning, printed once for two modes", rc == 0 and len(lines) == 1,
      (rc, se))
t = load_json(os.path.join(out, "adaptive", "trace.json")) if rc == 0 else {}
s = load_json(os.path.join(out, "summary.json")) if rc == 0 else {}
check("warnings: kept in the trace and the summary",
      isinstance(t, dict) and isinstance(s, dict) and t.get("warning_count") == 1 and
      any("missing.png" in w for w in t.get("warnings", [])) and s.get("warnings") == t.get("warnings"),
      (t.get("warnings") if isinstance(t, dict) else t, s.get("warnings") if isinstance(s, dict) else s))
check("warnings: the object falls back to its base colour factor, untextured",
      isinstance(t, dict) and t["objects"][0]["color"] == [0, 1, 0, 1] and not t["objects"][0]["textured"])
rc, so, se = play(WARN, os.path.join(WORK, "warn_q"), "--frames", "1", "-q", backend="cpu")
check("warnings: -q prints nothing", rc == 0 and se == "", se)

# ---- 7. --scene-budget: one triangle budget over every object, shared by screen error ---

g = Gltf()
ball = g.mesh(*sphere(1.0), g.material((0.8, 0.8, 0.8, 1)))
BALLS = {"near": [-1.5, 0, 7], "mid": [1.5, 0, 0], "far": [4, 0, -20]}  # the camera is at z = 12
for name, at in BALLS.items():
    g.node(name=name, mesh=ball, translation=at)
BALL_SCENE = os.path.join(WORK, "balls.gltf")
g.save(BALL_SCENE)


def frame_rows(out):
    path = os.path.join(out, "trace.csv")
    return list(csv.DictReader(open(path))) if os.path.exists(path) else []


free_out, budget_out = os.path.join(WORK, "budget_free"), os.path.join(WORK, "budget_on")
rc, so, se = play(BALL_SCENE, free_out, "--frames", "3", "--path", CAM, "--max-level", "5", "-q", backend="cpu")
free = frame_rows(free_out)
free_tris = min((int(r["triangles"]) for r in free), default=0)
BUDGET = free_tris // 3
check("scene budget: the unbudgeted scene plays and needs more than the budget", rc == 0 and BUDGET > 100,
      (rc, se, free_tris))
rc, so, se = play(BALL_SCENE, budget_out, "--frames", "3", "--path", CAM, "--max-level", "5", "--scene-budget",
                  str(BUDGET), "-q", backend="cpu")
rows = frame_rows(budget_out)
check("scene budget: plays (exit 0)", rc == 0 and len(rows) == 3, (rc, se))
check("scene budget: every frame's triangles (all objects) at or under the budget",
      rows and all(int(r["triangles"]) <= BUDGET for r in rows), ([r["triangles"] for r in rows], BUDGET))
check("scene budget: the effective epsilon was raised above --epsilon",
      rows and all(float(r["effective_epsilon"]) > 0.5 for r in rows), [r["effective_epsilon"] for r in rows])
t = load_json(os.path.join(budget_out, "trace.json")) if rc == 0 else {}
f0 = t["frames"][0]["objects"] if isinstance(t, dict) and t.get("frames") else []
by = {o["name"]: o for o in f0}
check("scene budget: recorded in the trace", isinstance(t, dict) and t.get("scene_budget") == BUDGET)
check("scene budget: one epsilon for every object",
      len(f0) == 3 and len({o["effective_epsilon"] for o in f0}) == 1, [o["effective_epsilon"] for o in f0])
check("scene budget: the near object gets more than a third of the budget, the far one less",
      len(by) == 3 and by["near"]["triangles"] > BUDGET // 3 > by["far"]["triangles"],
      {k: o["triangles"] for k, o in by.items()})

finish()
