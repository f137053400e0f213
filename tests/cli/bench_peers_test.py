"""tlod bench --peers (issue 15): tesslod against OpenSubdiv on small meshes, cheap.
Usage: bench_peers_test.py TLOD DATA_DIR WORK_DIR osd|noosd
osd: the build has OpenSubdiv; every case of the JSON "peers" key has positive figures for both libraries
(preprocessing cold and warm, ours also with the scheduler's tables: "adaptive"), the
input vertices lie on our Phong surface (it interpolates: distance exactly 0) and not on OpenSubdiv's Loop /
Catmull-Clark limit (distance > 0: it approximates), and a bad --json path fails with one error line naming it.
noosd: --peers fails, saying OpenSubdiv is missing and how to install it (never a silent skip)."""
import math, os, sys

import tlod_cli as t

tlod, data, work, _ = t.setup(sys.argv[:4])
with_osd = sys.argv[4] == "osd"


def positive(x):
    return isinstance(x, (int, float)) and math.isfinite(x) and x > 0


def check_sides(name, obj):
    bad = {k: v for k, v in obj.items() if (k.startswith("ours_") or k.startswith("osd_")) and not positive(v)}
    t.check(name + ": both libraries have positive figures", not bad and any(k.startswith("osd_") for k in obj), bad)


def check_case(c):
    name = "%s %d faces L%d" % (c["mesh"], c["faces"], c["level"])
    for path in ("positions", "positions+normals"):
        for part in ("preprocess", "static", "deforming"):
            check_sides("%s %s %s" % (name, path, part), c[path][part])
        p = c[path]["preprocess"]
        keys = ("ours_ms_min", "ours_warm_ms_min", "ours_adaptive_ms_min", "osd_ms_min", "osd_warm_ms_min",
                "ours_peak_bytes", "ours_adaptive_peak_bytes", "osd_peak_bytes")
        t.check("%s %s: preprocessing cold, warm and adaptive for both" % (name, path), all(k in p for k in keys), p)
    a = c["accuracy"]
    t.check(name + ": input vertices on our Phong surface (distance 0)", a["ours_vertex_distance"] == 0.0, a)
    t.check(name + ": not on OpenSubdiv's limit surface (distance > 0)", a["osd_limit_vertex_distance"] > 1e-4, a)
    t.check(name + ": volume changes finite and small",
            all(math.isfinite(a[k]) and abs(a[k]) < 0.1 for k in ("ours_volume_change", "osd_volume_change")), a)


if with_osd:
    out = os.path.join(work, "peers.json")
    rc, so, se = t.run("bench", "--peers", "--peer-faces", "600", "--repeat", "1", "--warmup", "0", "--json", out)
    t.check("bench --peers runs", rc == 0, se)
    doc = t.load_json(out)
    peers = doc.get("peers", {}) if isinstance(doc, dict) else {}
    t.check("the JSON has a peers key with OpenSubdiv's version", peers.get("opensubdiv", "").startswith("3."), doc)
    cases = peers.get("cases", [])
    t.check("12 cases: triangle, quad, mixed at levels 1-4",
            sorted((c["mesh"], c["level"]) for c in cases) ==
            sorted((m, l) for m in ("triangle", "quad", "mixed") for l in range(1, 5)), cases)
    for c in cases:
        check_case(c)
    rc, so, se = t.run("bench", "--peers", "--peer-faces", "100", "--repeat", "1", "--json",
                       os.path.join(work, "no", "such", "dir", "p.json"))
    t.check("a bad --json path fails with one error line naming it",
            rc != 0 and t.one_error_line(se) and "no/such/dir" in se, se)
else:
    rc, so, se = t.run("bench", "--peers", "--peer-faces", "100")
    t.check("--peers without OpenSubdiv fails saying how to get it",
            rc != 0 and t.one_error_line(se) and "OpenSubdiv" in se and "libosd-dev" in se, se)
t.finish()
