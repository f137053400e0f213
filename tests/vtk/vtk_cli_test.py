#!/usr/bin/env python3
"""VTK input through the tlod command (issue 14): the test meshes of vtk_model.h, written at run time
by vtk_import_bench gen, tessellated by `tlod tessellate` with the tool's VTK defaults.
  - --surface auto is quadratic for second-order hexahedra (output bytes equal to --surface
    quadratic, unlike phong) and phong for linear ones;
  - quads are kept as quads (stats input_counts against the boundary known by construction);
  - adaptive output over many cameras (--eye, error and hybrid policies, --no-weld) welds by exact
    position into a closed, consistently oriented mesh (closed_after_weld, as tests/cli checks its
    meshes; not `tlod info`, which drops the zero-area strip triangles of flat faces as degenerate).
Usage: vtk_cli_test.py TLOD VTK_IMPORT_BENCH WORK_DIR"""
import hashlib, json, math, os, random, subprocess, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from tlod_cli import check, closed_after_weld, finish, init, read_obj, run  # noqa: E402

TLOD, GEN, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
init(TLOD)
os.makedirs(WORK, exist_ok=True)

# model -> (file, boundary triangles, boundary quads, centre, radius)
MODELS = {
    "box": ("box.vtk", 0, 52, (1.0, 0.75, 0.5), 1.35),
    "cylinder": ("cylinder.vtu", 0, 66, (0.0, 0.0, 1.0), 1.42),
    "mixed": ("mixed.vtu", 14, 11, (2.0, 0.5, 0.5), 2.13),
    "hex20": ("hex20.vtk", 0, 10, (1.0, 0.6, 0.6), 1.4),
    "hex27": ("hex27.vtu", 0, 10, (1.0, 0.6, 0.6), 1.4),
}
paths = {}
for model, (name, *_rest) in MODELS.items():
    paths[model] = os.path.join(WORK, name)
    p = subprocess.run([GEN, "gen", model, paths[model]], capture_output=True, text=True)
    check("generate %s" % name, p.returncode == 0, p.stderr)


def out_path(model, args):
    """One output file per (model, arguments), the same in every run."""
    return os.path.join(WORK, "%s_%s.obj" % (model, hashlib.sha1(" ".join(args).encode()).hexdigest()[:12]))


def tessellate(model, *args):
    out = out_path(model, args)
    st = out + ".json"
    rc, _, err = run("tessellate", paths[model], "-o", out, "--stats", st, "-q", *args)
    stats = json.load(open(st)) if rc == 0 else {}
    return rc, out, stats, err


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


# --surface auto: quadratic for second-order faces, phong for linear ones
for model, want, other in (("hex20", "quadratic", "phong"), ("hex27", "quadratic", "phong"),
                           ("cylinder", "phong", "quadratic")):
    rc1, auto, _, e1 = tessellate(model, "--level", "3", "--surface", "auto")
    rc2, same, _, e2 = tessellate(model, "--level", "3", "--surface", want)
    rc3, diff, _, e3 = tessellate(model, "--level", "3", "--surface", other)
    ok = rc1 == rc2 == rc3 == 0
    check("%s: --surface auto == %s, != %s" % (model, want, other),
          ok and read_bytes(auto) == read_bytes(same) and (model == "cylinder" or read_bytes(auto) != read_bytes(diff)),
          e1 + e2 + e3)
    rc, _, _, err = tessellate(model, "--level", "3")
    check("%s: auto is the default for VTK input" % model,
          rc == 0 and read_bytes(auto) == read_bytes(out_path(model, ("--level", "3"))), err)

# quads kept as quads
for model, (name, tris, quads, _c, _r) in MODELS.items():
    rc, _, stats, err = tessellate(model, "--level", "1")
    ic = stats.get("input_counts", {})
    check("%s: %d triangles and %d quads reach the tessellator" % (name, tris, quads),
          rc == 0 and ic.get("triangles") == tris and ic.get("quads") == quads, err or str(ic))

# crack-free adaptive output over cameras: far enough (3..12 R, aimed within 0.1 R of the centre,
# fovy 70) that the frustum holds the whole mesh, so no patch is culled and the output must be closed.
# The box and the mixed block have flat faces only: with the VTK crease default every patch is flat
# and one level does, so they go without creases (smooth normals, curved Phong edges).
rng = random.Random(14)
for model, (name, _t, _q, c, R) in MODELS.items():
    crease = ["--crease", "0"] if model in ("box", "mixed") else []
    bad, levels = [], set()
    for cam in range(8):
        d = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        dist = R * rng.uniform(3, 12)
        eye = ",".join("%.6f" % (c[k] + d[k] / n * dist) for k in range(3))
        target = ",".join("%.6f" % (c[k] + rng.uniform(-0.1, 0.1) * R) for k in range(3))
        policy = ("error", "hybrid")[cam % 2]
        rc, out, stats, err = tessellate(model, "--eye", eye, "--target", target, "--fovy", "70", "--policy", policy,
                                         "--no-weld", "--max-level", "5", *crease)
        ok, why = closed_after_weld(*read_obj(out)) if rc == 0 else (False, err)
        levels.update(stats.get("levels", []))
        if not ok or stats["adaptive"]["culled"] != 0:
            bad.append("camera %d eye %s target %s %s: %s (%d culled)" % (cam, eye, target, policy, why,
                                                                        stats.get("adaptive", {}).get("culled", -1)))
    check("%s: adaptive --no-weld output closed for 8 cameras (levels %s)" % (name, sorted(levels)),
          not bad and len(levels) > 1, "; ".join(bad))

finish()
