#!/usr/bin/env python3
"""Regression tests of the tlod command's hardening (issue #10): one --out per
run at a time (the run-folder lock), failed writes reported as failed,
numbers that used to wrap, a folder given as an input file, a camera with
no view direction, a camera path too long to play, and a trace whose memory
does not grow with frames.
Usage: hardening_test.py TLOD DATA_DIR WORK_DIR [gl|nogl]"""
import json, os, resource, signal, subprocess, sys, time

from tlod_cli import check, finish, load_json, setup, one_error_line, run

TLOD, DATA, WORK, BUILT_WITH_GL = setup(sys.argv)
SMALL = ["--backend", "cpu", "--size", "64x64", "-q"]
BOX = os.path.join(DATA, "glTF-Sample-Models", "Box", "Box.gltf")


def out(name):
    return os.path.join(WORK, name)


# ---- two tlod play on one --out ---------------------------------------------
folder = out("shared")
os.makedirs(folder)
first = subprocess.Popen([TLOD, "play", *SMALL, "--frames", "4000", "--out", folder], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
lock = os.path.join(folder, ".tlod.lock")
deadline = time.time() + 30
while not os.path.exists(lock) and first.poll() is None and time.time() < deadline:
    time.sleep(0.01)
t0 = time.time()
rc, so, se = run("play", *SMALL, "--frames", "10", "--out", folder, timeout=60)
secs = time.time() - t0
first_running = first.poll() is None
fo, fe = first.communicate(timeout=300)
check("lock: the second play on one --out fails at once (exit 1, %.2f s, the first still running)" % secs,
      rc == 1 and secs < 5 and first_running, (rc, secs, first_running, se))
check("lock: its one error line names the folder and the other tlod's pid",
      one_error_line(se) and folder in se and "another tlod" in se and ("pid %d" % first.pid) in se, se)
t, s = load_json(os.path.join(folder, "trace.json")), load_json(os.path.join(folder, "summary.json"))
check("lock: the first run exits 0 and its trace and summary are valid JSON with all 4000 frames",
      first.returncode == 0 and isinstance(t, dict) and len(t["frames"]) == 4000 and isinstance(s, dict)
      and s["runs"][0]["frames"] == 4000 and s["runs"][0]["stopped"] == "completed", (first.returncode, fe, s))
check("lock: the lock file is gone after the run, and the folder can be played again",
      not os.path.exists(lock) and run("play", *SMALL, "--frames", "5", "--out", folder)[0] == 0)

# ---- failed writes ----------------------------------------------------------


def limited(limit):
    """A file size limit (RLIMIT_FSIZE): a write past it fails with EFBIG, as a
    full disk fails with ENOSPC (SIGXFSZ ignored, so the write returns)."""
    def pre():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return pre


def run_limited(limit, *args):
    p = subprocess.run([TLOD, *args], capture_output=True, text=True, timeout=300, preexec_fn=limited(limit))
    return p.returncode, p.stdout, p.stderr


# The trace reaches the limit mid-run (it is streamed a window at a time); the summary still fits.
d = out("fsize")
rc, so, se = run_limited(400000, "play", *SMALL, "--frames", "3000", "--out", d)
s = load_json(os.path.join(d, "summary.json"))
check("write error mid-run: exit 1, the error names the trace file and the errno",
      rc == 1 and "trace" in se and "File too large" in se, (rc, se))
check("write error mid-run: summary.json says failed, with the error, the run stopped as error before its end",
      isinstance(s, dict) and s.get("status") == "failed" and "File too large" in s.get("error", "")
      and s["runs"][0]["stopped"] == "error" and s["runs"][0]["frames"] < 3000, s)
check("write error mid-run: no trace and no temporary left",
      sorted(os.listdir(d)) == ["summary.json", "summary.txt"], os.listdir(d))

# summary.txt cannot be written (a folder is in its place): summary.json must not say all went well.
d = out("summary_txt")
os.makedirs(os.path.join(d, "summary.txt"))
rc, so, se = run("play", *SMALL, "--frames", "5", "--out", d)
s = load_json(os.path.join(d, "summary.json"))
check("summary.txt unwritable: exit 1, and summary.json says failed naming summary.txt",
      rc == 1 and isinstance(s, dict) and s.get("status") == "failed" and "summary.txt" in s.get("error", ""),
      (rc, se, s))
rc, so, se = run("play", *SMALL, "--frames", "5", "--out", out("ok"))
s = load_json(os.path.join(out("ok"), "summary.json"))
check("a good run: summary.json says ok with no error",
      rc == 0 and isinstance(s, dict) and s.get("status") == "ok" and s.get("error") == "", s)

# --stats onto something that is not a regular file: refused, the thing left alone (the rename used to
# replace it: as root, --stats /dev/full made /dev/full a file; a FIFO shows the same without the risk).
fifo = out("stats.fifo")
os.mkfifo(fifo)
rc, so, se = run("tessellate", "demo:cow", "--level", "1", "-o", out("cow.obj"), "--stats", fifo)
check("--stats FIFO: exit 1 'not a regular file', the FIFO still a FIFO",
      rc == 1 and "not a regular file" in se and os.path.exists(fifo) and not os.path.isfile(fifo), (rc, se))
if BUILT_WITH_GL:
    d = out("shots")
    # 8000 bytes: summary.json (about 3.5 kB) fits, a 256x256 screenshot of the demo scene (about 25 kB) does not.
    rc, so, se = run_limited(8000, "play", "--backend", "gl", "--size", "256x256", "--frames", "3",
                             "--screenshot-every", "1", "-q", "--out", d)
    s = load_json(os.path.join(d, "summary.json"))
    check("screenshot write error: exit 1, summary.json failed naming the screenshot and the write's errno "
          "(EFBIG, not the EIO left after closing)",
          rc == 1 and isinstance(s, dict) and s.get("status") == "failed" and "frame_00000.png" in s.get("error", "")
          and "File too large" in s.get("error", ""), (rc, se, s))

# ---- numbers that wrapped ---------------------------------------------------
WRAPS = [
    (["play", "--size", "4294967297x720"], "--size: 4294967297x720: width out of range 1..16384"),
    (["play", "--size", "1280x4294967297"], "--size: 1280x4294967297: height out of range 1..16384"),
    (["play", "--size", "1280x720x3"], "--size: 1280x720x3: expected WxH"),
    (["play", "--size", " 1280x720"], "--size:  1280x720: expected WxH"),
    (["play", "--mode", "uniform:4294967296"], "--mode: uniform:4294967296: level out of range 0..10"),
    (["play", "--mode", "uniform:-1"], "--mode: uniform:-1: level out of range 0..10"),
    (["play", "--compare", "adaptive,uniform:4294967297"], "--compare: uniform:4294967297: level out of range"),
    (["play", BOX, "--path", "gltf:-1"], "--path: gltf:-1: camera out of range 0..4294967295"),
    (["play", BOX, "--path", "gltf:4294967296"], "--path: gltf:4294967296: camera out of range"),
    (["play", "--frames", "4294967297"], "--frames: 4294967297: value out of range 1..1000000"),
    (["play", "--frames", "+5"], "--frames: +5: expected a whole number"),
    (["play", "--fps", "0x3c"], "--fps: 0x3c: expected a number"),
    (["play", "--fps", "1e999"], "--fps: 1e999: value out of range"),
    (["play", "--epsilon", "nan"], "--epsilon: nan: expected a number"),
    (["tessellate", "demo:cow", "-o", out("x.obj"), "--eye", "1,2,3", "--size", "4294967297x720"],
     "--size: 4294967297x720: width out of range 1..65536"),
    (["tessellate", "demo:cow", "-o", out("x.obj"), "--eye", "1,2,3x"], "--eye: 1,2,3x: expected X,Y,Z"),
    (["tessellate", "demo:cow", "-o", out("x.obj"), "--eye", "1e39,2,3"], "--eye: 1e39,2,3: x out of range"),
    (["tessellate", "demo:cow", "-o", out("x.obj"), "--eye", "1, 2,3"], "--eye: 1, 2,3: expected X,Y,Z"),
    (["bench", "--frames", "4294967297"], "--frames: 4294967297: value out of range 1..100000"),
]
for args, message in WRAPS:
    rc, so, se = run(*args, "--out", out("wrap")) if args[0] == "play" else run(*args)
    check("refused, not wrapped: %s -> exit 2, '%s'" % (" ".join(args[1:]).replace(DATA, "DATA"), message),
          rc == 2 and one_error_line(se) and message in se and not os.path.exists(out("wrap")), (rc, se))
rc, so, se = run("tessellate", "demo:torus-4294967299x3", "-o", out("torus.obj"))
check("demo:torus-4294967299x3: exit 1 naming the rings, no output",
      rc == 1 and "rings out of range" in se and not os.path.exists(out("torus.obj")), (rc, se))

# ---- a folder as an input file ----------------------------------------------
os.makedirs(out("a_folder.json"))
rc, so, se = run("play", *SMALL, "--path", out("a_folder.json"), "--out", out("folder_path"))
check("--path FOLDER: exit 1, 'Is a directory', not a JSON syntax error",
      rc == 1 and one_error_line(se) and "Is a directory" in se and "parse error" not in se, se)
os.makedirs(out("a_folder.obj"))
rc, so, se = run("tessellate", out("a_folder.obj"), "-o", out("y.obj"))
check("tessellate FOLDER: exit 1, 'Is a directory'", rc == 1 and "Is a directory" in se, se)
rc, so, se = run("tessellate", "demo:cow", "--level", "1", "-o", out("a_folder.obj"))
check("-o FOLDER: exit 1, 'Is a directory', the folder left alone",
      rc == 1 and "Is a directory" in se and os.path.isdir(out("a_folder.obj")), se)

# ---- a camera with no view direction ----------------------------------------
for args, names in ((["--eye", "1,2,3", "--target", "1,2,3"], "eye and target are the same point"),
                    (["--eye", "0,5,0", "--target", "0,0,0"], "up is parallel to the view direction"),
                    (["--eye", "0,0,5", "--target", "0,0,0", "--up", "0,0,0"], "up is parallel to the view direction")):
    rc, so, se = run("tessellate", "demo:cow", "-o", out("eye.obj"), *args)
    check("tessellate %s: exit 2, naming --eye, --target, --up: %s" % (" ".join(args), names),
          rc == 2 and one_error_line(se) and "--eye" in se and "--target" in se and "--up" in se and names in se
          and not os.path.exists(out("eye.obj")), (rc, se))

# ---- a camera path too long to play -----------------------------------------
huge = out("huge.json")
with open(huge, "w") as f:
    json.dump({"keyframes": [{"time": 0, "eye": [0, 1, 5], "target": [0, 0, 0]},
                             {"time": 3e38, "eye": [5, 1, 0], "target": [0, 0, 0]}]}, f)
t0 = time.time()
try:
    rc, so, se = run("play", *SMALL, "--path", huge, "--out", out("huge"), timeout=30)
except subprocess.TimeoutExpired:
    rc, se = None, "still playing after 30 s"
check("path of 3e38 s: refused at once (exit 2), naming --path and the frame cap",
      rc == 2 and one_error_line(se) and "--path" in se and "1000000" in se and not os.path.exists(out("huge")), se)
rc, so, se = run("play", *SMALL, "--path", huge, "--frames", "5", "--out", out("huge5"))
s = load_json(os.path.join(out("huge5"), "summary.json"))
check("path of 3e38 s with --frames 5: plays 5 frames", rc == 0 and isinstance(s, dict) and s["runs"][0]["frames"] == 5,
      (rc, se))
try:
    rc, so, se = run("play", *SMALL, "--duration", "1000000", "--fps", "1000", "--out", out("long"), timeout=30)
except subprocess.TimeoutExpired:
    rc, se = None, "still playing after 30 s"
check("--duration 1e6 at 1000 fps: refused (exit 2) naming --duration and the cap",
      rc == 2 and "--duration" in se and "1000000" in se, se)

# ---- the trace's memory does not grow with frames ---------------------------
d = out("memory")
rc, so, se = run("play", "--backend", "null", "--frames", "6000", "-q", "--out", d)
s, t = load_json(os.path.join(d, "summary.json")), load_json(os.path.join(d, "trace.json"))
samples = {r["frame"]: r for r in s["runs"][0].get("resources", [])} if isinstance(s, dict) else {}
ok = rc == 0 and 1000 in samples and 6000 in samples
growth = samples[6000]["peak_rss_kib"] - samples[1000]["peak_rss_kib"] if ok else None
check("6000 frames: resources sampled after frames 1, 10, 100, 1000 and the last",
      ok and sorted(samples) == [1, 10, 100, 1000, 6000], (rc, se, sorted(samples)))
check("6000 frames: peak RSS grows less than 512 KiB from frame 1000 to 6000 (was ~3 MB held in memory): %s KiB"
      % growth, ok and growth < 512, growth)
check("6000 frames: the streamed trace holds every frame in order, the CSV a row each",
      isinstance(t, dict) and [f["frame"] for f in t["frames"]] == list(range(6000))
      and t["frames_completed"] == 6000 and len(open(os.path.join(d, "trace.csv")).read().splitlines()) == 6001)
if BUILT_WITH_GL:
    d = out("gl_objects")
    rc, so, se = run("play", "--backend", "gl", "--size", "64x64", "--frames", "150", "-q", "--out", d)
    s = load_json(os.path.join(d, "summary.json"))
    res = s["runs"][0]["resources"] if isinstance(s, dict) else []
    objs = [r.get("gl_objects") for r in res]
    check("gl: the live GL objects are counted and the same after frame 1, 10, 100 and 150",
          rc == 0 and len(objs) == 4 and objs[0] and objs[0]["programs"] > 0 and objs[0]["buffers"] > 0
          and all(o == objs[0] for o in objs), objs)

finish()
