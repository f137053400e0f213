"""tlod bench --json (issue 15): the document parses, names the processor and
the SIMD level, has the memory rates of the run and the headline figures
(scheduler_1m_ms, eval_bandwidth_fraction, strip_triangle_overhead) as
positive finite numbers with the cases they come from; a --json path that
cannot be written fails with one clear error line and leaves no file; --peers
without OpenSubdiv fails saying so. Small options keep it cheap: the suite's
machinery, not the figures' size, is under test.
Usage: bench_json_test.py TLOD DATA_DIR WORK_DIR [osd|noosd]"""
import math, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tlod_cli import check, finish, load_json, one_error_line, run, setup

TLOD, DATA, WORK, _ = setup(sys.argv[:4])
OSD = len(sys.argv) > 4 and sys.argv[4] == "osd"
SMALL = ["--suite", "figures", "demo:torus-12x6", "--scheduler-mesh", "demo:torus-40x40", "--model", "demo:cylinder",
         "--threads", "2", "--frames", "2", "--repeat", "1", "--warmup", "0", "--bandwidth-mib", "16"]


def positive(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) and x > 0


out_json = os.path.join(WORK, "figures.json")
rc, out, err = run("bench", *SMALL, "--json", out_json)
doc = load_json(out_json) if rc == 0 else err
check("bench --json: exit 0 and the file parses", rc == 0 and isinstance(doc, dict), err + str(doc))
doc = doc if isinstance(doc, dict) else {}
check("processor and simd named", isinstance(doc.get("processor"), str) and doc["processor"] not in ("", "unknown")
      and doc.get("simd") in ("scalar", "sse2", "avx2", "avx512"), doc.get("processor"))
for key in ("scheduler_1m_ms", "scheduler_1m_cpu_ms", "eval_bandwidth_fraction", "strip_triangle_overhead"):
    check("%s: positive finite" % key, positive(doc.get(key)), doc.get(key))
check("scheduler_1m_ms is the moving refining case on 2 threads: CPU median / 2",
      any(c.get("camera") == "refine-moving" and c.get("threads") == 2 and
          abs(c.get("cpu_median_ms", 0) / 2 - doc.get("scheduler_1m_ms", -1)) < 1e-6 for c in doc.get("scheduler", [])))
rates = doc.get("bandwidth", {})
check("memory rates of 1 and 2 threads, read/write/copy", all(
    positive(rates.get(t, {}).get(k)) for t in ("threads_1", "threads_2")
    for k in ("read_bytes_per_s", "write_bytes_per_s", "copy_bytes_per_s")), rates)
sched = doc.get("scheduler", [])
check("scheduler cases: moving and static, refining (levels above 0, culled, strips)", len(sched) == 2 and all(
    positive(c.get("cpu_median_ms")) and positive(c.get("wall_median_ms")) and positive(c.get("bound_ms")) and
    sum(c.get("level_histogram", [0])[1:]) > 0 and c.get("culled", 0) > 0 and c.get("strip_triangles", 0) > 0
    for c in sched), sched)
phong5 = [c for c in doc.get("eval", []) if c.get("surface") == "phong" and c.get("level") == 5 and c.get("threads") == 2]
check("eval_bandwidth_fraction is Phong L5 T2's", len(phong5) == 1 and
      abs(phong5[0].get("memcpy_fraction", 0) - doc.get("eval_bandwidth_fraction", -1)) < 1e-6, phong5)
t1 = doc.get("table1_hybrid", [])
check("strip_triangle_overhead is the worst Table 1 scene's", len(t1) == 1 and
      abs(t1[0].get("strip_over_pattern", 0) - doc.get("strip_triangle_overhead", -1)) < 1e-6, t1)

bad = os.path.join(WORK, "no-such-folder", "figures.json")
rc, out, err = run("bench", "--suite", "build", "demo:torus-6x3", "--repeat", "1", "--warmup", "0", "--json", bad)
check("bad --json path: fails with one error line naming it", rc != 0 and one_error_line(err) and "--json" in err and
      bad in err and not os.path.exists(bad), err)

rc, out, err = run("bench", "--peers", "--peer-faces", "200", "--json", os.path.join(WORK, "peers.json"))
if OSD:
    peers = load_json(os.path.join(WORK, "peers.json")) if rc == 0 else err
    check("--peers with OpenSubdiv: a peers key", rc == 0 and isinstance(peers, dict) and "peers" in peers, err)
else:
    check("--peers without OpenSubdiv: fails, saying it is missing and how to install it",
          rc != 0 and one_error_line(err) and "OpenSubdiv" in err and "bootstrap --peers" in err, err)
finish()
