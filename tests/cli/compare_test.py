"""tlod compare and tlod play --debug-view (issue 13), end to end.

compare: a real cpu run against itself passes; copies of it with frame times or triangles scaled in trace.json
and trace.csv (what a regressed build would record) fail with exit 1 naming the metric and both values, which the
test computes itself from the trace (nearest-rank p95, mean); thresholds are respected; another scene or path,
a folder that is not a run, a --compare parent and bad usage are errors with their own exit codes.
--debug-view (gl): the levels screenshot shows level colours (shade.frag's level_color table, up to the
lighting's scale) of levels the frame's histogram holds, and the wireframe one dark edge pixels.

    python3 tests/cli/compare_test.py TLOD DATA_DIR WORK_DIR [gl|nogl]
"""
import csv, json, math, os, shutil, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_read import png_rows
from tlod_cli import check, finish, load_json, one_error_line, run, setup

TLOD, DATA, WORK, GL = setup(sys.argv)

# backends/shaders/shade.frag level_color(): levels 0..7 (7 and above share the last).
LEVEL_COLORS = [(0.2, 0.3, 0.9), (0.1, 0.7, 0.9), (0.1, 0.8, 0.3), (0.7, 0.9, 0.1), (1.0, 0.7, 0.1),
                (1.0, 0.35, 0.1), (0.9, 0.1, 0.2), (0.8, 0.1, 0.8)]


def play(out, *args):
    rc, so, se = run("play", "--size", "320x180", "--frames", "60", "-q", "--out", out, *args)
    check("play %s exits 0" % " ".join(args), rc == 0, se)
    return out


def p95(values):
    s = sorted(values)
    return s[max(1, math.ceil(0.95 * len(s))) - 1]


def edited_copy(src, name, edit_frame=None, edit_top=None, keep=None):
    """A copy of run src with each trace.json frame record passed through edit_frame (in place), the top level
    through edit_top, the frames cut to the first keep; trace.csv rewritten from the same frames."""
    dst = os.path.join(WORK, name)
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(src, dst)
    trace = load_json(os.path.join(dst, "trace.json"))
    trace["frames"] = trace["frames"][:keep]
    trace["frames_completed"] = len(trace["frames"])
    for fr in trace["frames"]:
        if edit_frame:
            edit_frame(fr)
    if edit_top:
        edit_top(trace)
    with open(os.path.join(dst, "trace.json"), "w") as f:
        json.dump(trace, f)
    with open(os.path.join(src, "trace.csv")) as f:
        rows = list(csv.DictReader(f))[:len(trace["frames"])]
    for row, fr in zip(rows, trace["frames"]):
        for key in ("frame_ms", "triangles"):
            row[key] = fr[key]
    with open(os.path.join(dst, "trace.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return dst


def scale(key, factor):
    def edit(fr):
        fr[key] = fr[key] * factor if key != "triangles" else int(round(fr[key] * factor))
    return edit


def compare(*args):
    return run("compare", *args)


def check_regression(name, rc, out, metric, base, new):
    """Exit 1 and the regression line naming metric with both values (3 decimals, as printed)."""
    line = [l for l in out.splitlines() if l.startswith("regression: " + metric + " ")]
    check(name + ": exit 1", rc == 1, out)
    check(name + ": names %s %.3f -> %.3f" % (metric, base, new),
          len(line) == 1 and ("%.3f" % base) in line[0] and ("%.3f" % new) in line[0], out)


def compare_tests():
    base = play(os.path.join(WORK, "base"), "--backend", "cpu")
    trace = load_json(os.path.join(base, "trace.json"))
    check("no --debug-view: trace.json says debug_view none", trace.get("debug_view") == "none", trace.get("debug_view"))
    frames = trace["frames"]
    ms = [f["frame_ms"] for f in frames]
    tris = [f["triangles"] for f in frames]

    rc, out, err = compare(base, base)
    check("identical run: exit 0", rc == 0, out + err)
    check("identical run: the table has frame_ms p95 and triangles mean with ratio 1",
          all(any(l.startswith(m) and " 1.000 " in l for l in out.splitlines())
              for m in ("frame_ms p95", "triangles mean")), out)
    check("identical run: p95 printed is the trace's nearest-rank p95", ("%.3f" % p95(ms)) in out, out)
    summary = load_json(os.path.join(base, "summary.json"))
    check("identical run: p95 printed is summary.json's frame_ms p95",
          ("%.3f" % summary["runs"][0]["frame_ms"]["p95"]) in out, out)
    same = edited_copy(base, "same")
    rc, out, err = compare(base, same)
    check("a copy rewritten unchanged: exit 0", rc == 0, out + err)

    slow = edited_copy(base, "slow", scale("frame_ms", 1.5))
    rc, out, err = compare(base, slow)
    check_regression("frame times x1.5", rc, out, "frame_ms p95", p95(ms), p95([m * 1.5 for m in ms]))
    rc, out, err = compare(base, slow, "--max-p95-regression", "60")
    check("frame times x1.5 with --max-p95-regression 60: exit 0", rc == 0, out + err)

    more = edited_copy(base, "more", scale("triangles", 1.02))
    new_tris = [int(round(t * 1.02)) for t in tris]
    rc, out, err = compare(base, more)
    check_regression("triangles x1.02 (default limit 0%)", rc, out, "triangles mean", sum(tris) / len(tris),
                     sum(new_tris) / len(new_tris))
    rc, out, err = compare(base, more, "--max-triangle-regression", "5")
    check("triangles x1.02 with --max-triangle-regression 5: exit 0", rc == 0, out + err)

    bit = edited_copy(base, "bit", scale("frame_ms", 1.05))
    rc, out, err = compare(base, bit, "--max-p95-regression", "10")
    check("frame times x1.05 with --max-p95-regression 10: exit 0", rc == 0, out + err)
    rc, out, err = compare(base, bit, "--max-p95-regression", "2")
    check_regression("frame times x1.05 with --max-p95-regression 2", rc, out, "frame_ms p95", p95(ms),
                     p95([m * 1.05 for m in ms]))
    rc, out, err = compare(slow, base)
    check("faster new run (baseline x1.5): exit 0", rc == 0, out + err)

    short = edited_copy(base, "short", keep=40)
    rc, out, err = compare(base, short)
    check("40 of 60 frames: exit 0, compared the prefix with a note",
          rc == 0 and "compared frames 0..39" in out and ("%.3f" % p95(ms[:40])) in out, out + err)

    cut = edited_copy(base, "cut")
    with open(os.path.join(cut, "trace.json"), "rb") as f:
        text = f.read()
    with open(os.path.join(cut, "trace.json"), "wb") as f:
        f.write(text[:len(text) * 6 // 10])  # a run killed mid-write
    rc, out, err = compare(base, cut)
    check("a truncated trace: exit 0, a warning naming it, its complete frames compared",
          rc == 0 and "warning: " + os.path.join(cut, "trace.json") + ": truncated after frame" in err and
          "compared frames 0.." in out, out + err)

    mismatch_tests(base)


def set_top(key, value):
    def edit(trace):
        trace[key] = value
    return edit


def check_error(name, rc, err, *words):
    check(name + ": exit 3, one error line naming " + ", ".join(words),
          rc == 3 and one_error_line(err) and all(w in err for w in words), err)


def mismatch_tests(base):
    cow = edited_copy(base, "cow", edit_top=set_top("scene", "demo:cow"))
    rc, out, err = compare(base, cow)
    check_error("another scene", rc, err, cow, "scene", "demo:cow", "demo:scene")
    zoom = edited_copy(base, "zoom", edit_top=set_top("path", "zoom"))
    rc, out, err = compare(base, zoom)
    check_error("another path", rc, err, zoom, "path", "'zoom'", "'orbit'")
    empty = os.path.join(WORK, "not_a_run")
    os.makedirs(empty, exist_ok=True)
    rc, out, err = compare(base, empty)
    check_error("a folder that is not a run", rc, err, empty, "not a run")
    rc, out, err = compare(os.path.join(WORK, "missing"), base)
    check_error("a baseline that does not exist", rc, err, os.path.join(WORK, "missing"))
    parent = os.path.join(WORK, "modes")
    rc, _, se = run("play", "--backend", "cpu", "--size", "160x90", "--frames", "5", "-q", "--out", parent,
                    "--compare", "adaptive,flat")
    rc, out, err = compare(base, parent)
    check_error("a --compare parent folder", rc, err, parent, "2 modes", os.path.join(parent, "adaptive"))
    for args in ([base], [base, base, base], [base, base, "--max-p95-regression", "x"],
                 [base, base, "--max-p95-regression", "-1"], [base, base, "--bogus"]):
        rc, out, err = compare(*args)
        check("usage %s: exit 2, one error line" % " ".join(a.replace(WORK, "W") for a in args),
              rc == 2 and one_error_line(err), err)


def level_of(rgb):
    """The level whose colour rgb is, up to the lighting's scale (channels / brightest), or None."""
    m = max(rgb)
    if m < 60:
        return None
    q = [c / m for c in rgb]
    for level, col in enumerate(LEVEL_COLORS):
        n = [c / max(col) for c in col]
        if max(abs(a - b) for a, b in zip(q, n)) < 0.06:
            return level
    return None


def debug_run(view):
    out = os.path.join(WORK, "view_" + view)
    rc, _, err = run("play", "--backend", "gl", "--size", "640x360", "--frames", "1", "--screenshot-every", "1",
                     "--debug-view", view, "-q", "--out", out)
    check("play --debug-view %s: exit 0" % view, rc == 0, err)
    trace, summary = load_json(os.path.join(out, "trace.json")), load_json(os.path.join(out, "summary.json"))
    check("--debug-view %s recorded in trace.json and summary.json" % view,
          isinstance(trace, dict) and isinstance(summary, dict) and trace.get("debug_view") == view and
          summary.get("debug_view") == view, str(trace)[:200])
    w, h, bpp, _, rows = png_rows(os.path.join(out, "screenshots", "frame_00000.png"))
    pixels = [tuple(r[x * bpp:x * bpp + 3]) for r in rows for x in range(w)]
    return trace, pixels


def debug_view_tests():
    rc, _, err = run("play", "--backend", "cpu", "--debug-view", "levels", "--frames", "1", "-q", "--out",
                     os.path.join(WORK, "cpu_view"))
    check("--debug-view with cpu (no image): exit 2, one error line", rc == 2 and one_error_line(err), err)
    rc, _, err = run("play", "--backend", "cpu", "--debug-view", "depth", "--frames", "1", "-q")
    check("--debug-view depth: exit 2 naming it", rc == 2 and "depth" in err, err)
    if not GL:
        print("note: no GL backend in this build: the screenshots of --debug-view are not checked")
        return
    _, shaded = debug_run("none")
    trace, levels = debug_run("levels")
    counts = {}
    for p in levels:
        lv = level_of(p)
        if lv is not None:
            counts[lv] = counts.get(lv, 0) + 1
    found = {lv for lv, n in counts.items() if n >= 50}
    hist = trace["frames"][0]["level_histogram"]
    present = {min(lv, 7) for lv, n in enumerate(hist) if n > 0}
    check("levels: the screenshot differs from the shaded one", levels != shaded)
    check("levels: >= 2 level colours of >= 50 pixels each", len(found) >= 2, counts)
    check("levels: every level colour shown is a level of the frame's histogram %s" % hist, found <= present,
          counts)
    _, wire = debug_run("wireframe")
    dark = lambda px: sum(1 for p in px if max(p) <= 20)
    check("wireframe: dark edge pixels (%d) where the shaded view has few (%d)" % (dark(wire), dark(shaded)),
          dark(wire) > 500 and dark(shaded) * 10 < dark(wire))
    rc, out, err = compare(os.path.join(WORK, "view_none"), os.path.join(WORK, "view_wireframe"),
                           "--max-p95-regression", "1000000")
    check("compare shaded vs wireframe: exit 0 with a note that the debug views differ",
          rc == 0 and "note: debug views differ (baseline none, new wireframe)" in out, out + err)


compare_tests()
debug_view_tests()
finish()
