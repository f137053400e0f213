#!/usr/bin/env python3
"""End-to-end tests of the tlod command: exit codes, one-line errors, no
half-written outputs, closed output for closed input, stats contents.
Usage: cli_test.py TLOD DATA_DIR WORK_DIR"""
import json, os, subprocess, sys, glob

from tlod_cli import check, closed_after_weld, finish, init, one_error_line, read_obj, run

TLOD, DATA, WORK = sys.argv[1:4]
init(TLOD)
os.makedirs(WORK, exist_ok=True)


# usage errors
rc, out, err = run()
check("no arguments exits 2", rc == 2)
rc, out, err = run("frobnicate")
check("unknown command: exit 2, one line", rc == 2 and one_error_line(err), err)
for cmd in ("tessellate", "info", "bench"):
    rc, out, err = run(cmd, "--help")
    check(cmd + " --help exits 0 with usage", rc == 0 and "usage: tlod " + cmd in out)
box = os.path.join(DATA, "glTF-Sample-Models/Box/Box.gltf")
for bad in (["--level", "99"], ["--level", "-1"], ["--alpha", "2"], ["--alpha", "nan"], ["--surface", "nurbs"],
            ["--normals", "x"], ["--frob"], ["--crease"]):
    o = os.path.join(WORK, "bad_flag.obj")
    rc, out, err = run("tessellate", box, "-o", o, *bad)
    check("bad flag %s: exit 2, one line, no output" % " ".join(bad),
          rc == 2 and one_error_line(err) and not os.path.exists(o), err)
rc, out, err = run("tessellate", box)
check("missing -o: exit 2", rc == 2 and one_error_line(err), err)

# bad input files: one clear line naming the file, exit 1, no output left behind
bad_files = sorted(glob.glob(os.path.join(DATA, "glTF-Validator/glb/*.glb")))
bad_files += [os.path.join(DATA, "glTF-Validator", p) for p in (
    "json/invalid_syntax.gltf", "mesh_data/index_buffer_oob.gltf", "mesh/unresolved_indices.gltf",
    "mesh/position_accessor_invalid_format.gltf", "mesh/accessor_unequal_count.gltf", "buffer/not_found.gltf",
    "buffer/invalid_uri_data_bytelength.gltf", "buffer_view/invalid_length.gltf")]
bad_files += [os.path.join(DATA, "assimp/BoxWithInfinites.glb"), os.path.join(WORK, "does_not_exist.obj"),
              os.path.join(DATA, "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf")]
bad_files += sorted(glob.glob(os.path.join(DATA, "obj_bad/*.obj")))
for path in bad_files:
    o = os.path.join(WORK, "bad_input.obj")
    rc, out, err = run("tessellate", path, "-o", o)
    base = os.path.basename(path)
    check("bad input %s: exit 1, one line naming it, no output" % base,
          rc == 1 and one_error_line(err) and base in err and not os.path.exists(o), "rc=%d %s" % (rc, err))
    rc, out, err = run("info", path)
    check("info on bad input %s: exit 1" % base, rc == 1 and one_error_line(err), err)

# closed inputs give closed outputs (no-weld output welded by exact position)
for surface in ("flat", "phong", "pn"):
    for src in (box, "demo:cow", "demo:cylinder", os.path.join(DATA, "glTF-Sample-Models/BoxInterleaved/BoxInterleaved.glb")):
        o = os.path.join(WORK, "closed_%s.obj" % surface)
        rc, out, err = run("tessellate", src, "-o", o, "--surface", surface, "--level", "2", "--no-weld", "-q")
        ok, why = closed_after_weld(*read_obj(o)) if rc == 0 else (False, err)
        check("--no-weld %s %s welds to a closed mesh" % (os.path.basename(src), surface), ok, why)

# stats
o = os.path.join(WORK, "duck.obj")
st = os.path.join(WORK, "duck.json")
rc, out, err = run("tessellate", os.path.join(DATA, "glTF-Sample-Models/Duck/glTF-Binary/Duck.glb"), "-o", o,
                   "--surface", "pn", "--level", "2", "--stats", st)
ok = rc == 0 and os.path.exists(st)
stats = json.load(open(st)) if ok else {}
check("stats: input and output counts", ok and stats["input_counts"]["triangles"] == 4212 and
      stats["output_counts"]["pattern_triangles"] == 4212 * 16, str(stats.get("output_counts")))
check("stats: timings and repairs present", ok and stats["timings_ms"]["tessellate"] >= 0 and
      "normals_repaired" in stats["repairs"])
verts, tris = read_obj(o) if ok else ([], [])
check("output triangle count matches stats", ok and len(tris) == stats["output_counts"]["triangles"])

# zero normals are repaired and reported, not passed through
rc, out, err = run("tessellate", os.path.join(DATA, "assimp/BoxBadNormals.glb"), "-o", os.path.join(WORK, "bn.ply"),
                   "--stats", os.path.join(WORK, "bn.json"))
bn = json.load(open(os.path.join(WORK, "bn.json"))) if rc == 0 else {}
check("BoxBadNormals: 4 normals repaired", rc == 0 and bn["repairs"]["normals_repaired"] == 4, str(bn.get("repairs")))

# info
rc, out, err = run("info", "demo:cow")
check("info demo:cow: closed, 3285 faces", rc == 0 and "closed" in out and "3285 faces" in out, out)

# every output format loads back through the importer (info reads it)
for ext in ("obj", "ply", "gltf", "glb"):
    o = os.path.join(WORK, "fmt." + ext)
    rc, out, err = run("tessellate", "demo:cylinder", "-o", o, "--level", "1", "-q")
    rc2, out2, err2 = run("info", o)
    check("output .%s reads back closed" % ext, rc == 0 and rc2 == 0 and "closed" in out2, err + err2)

# adaptive (view-dependent) tessellation
cow_faces = 3285
# silhouette at max level 4: at 5 it refines most of the cow to the cap (two 350 MB OBJ files, a minute of
# reading them here) and tests nothing more than 4 does.
for policy, top in (("error", 5), ("hybrid", 5), ("silhouette", 4)):
    for surface in ("phong", "pn"):
        o = os.path.join(WORK, "adaptive_%s_%s.obj" % (policy, surface))
        st = os.path.join(WORK, "adaptive_%s_%s.json" % (policy, surface))
        rc, out, err = run("tessellate", "demo:cow", "-o", o, "--surface", surface, "--eye", "8,3,10",
                           "--policy", policy, "--no-weld", "--max-level", str(top), "--stats", st, "-q")
        ok, why = closed_after_weld(*read_obj(o)) if rc == 0 else (False, err)
        check("adaptive %s %s: closed after welding" % (policy, surface), ok, why)
        s = json.load(open(st)) if rc == 0 else {}
        lv = s.get("levels", [])
        check("adaptive %s %s: levels per input face" % (policy, surface),
              len(lv) == cow_faces and all(-1 <= l <= top for l in lv) and
              sum(s["adaptive"]["level_histogram"]) + s["adaptive"]["culled"] == s["adaptive"]["patches"],
              "%d levels" % len(lv))
# a close camera culls part of the mesh: -1 levels, and an open output
o = os.path.join(WORK, "close.obj")
st = os.path.join(WORK, "close.json")
rc, out, err = run("tessellate", "demo:cow", "-o", o, "--eye", "3,0.5,2", "--target", "3,0.5,0", "--stats", st, "-q")
s = json.load(open(st)) if rc == 0 else {"levels": [], "adaptive": {"culled": 0}}
check("close camera culls patches (-1 levels)", rc == 0 and s["adaptive"]["culled"] > 0 and -1 in s["levels"] and
      max(s["levels"]) >= 1, err)
# smaller epsilon, more triangles
counts = []
for eps in ("4", "1", "0.25"):
    st = os.path.join(WORK, "eps.json")
    rc, out, err = run("tessellate", "demo:cow", "-o", os.path.join(WORK, "eps.ply"), "--eye", "8,3,10",
                       "--epsilon", eps, "--policy", "error", "--stats", st, "-q")
    counts.append(json.load(open(st))["output_counts"]["triangles"] if rc == 0 else -1)
check("triangles grow as epsilon shrinks", counts[0] < counts[1] < counts[2], str(counts))
# without strips the adaptive output has cracks
o = os.path.join(WORK, "nostitch.obj")
rc, out, err = run("tessellate", "demo:cow", "-o", o, "--eye", "8,3,10", "--no-weld", "--no-stitch", "-q")
ok, why = closed_after_weld(*read_obj(o)) if rc == 0 else (True, err)
check("--no-stitch leaves cracks the checker sees", rc == 0 and not ok, why)
for bad in (["--eye", "1,2"], ["--eye", "1,2,3", "--size", "0x10"], ["--eye", "1,2,3", "--policy", "x"],
            ["--eye", "1,2,3", "--epsilon", "0"], ["--eye", "1,2,3", "--fovy", "0"]):
    rc, out, err = run("tessellate", "demo:cow", "-o", os.path.join(WORK, "bad_adaptive.obj"), *bad)
    check("bad adaptive flags %s: exit 2, one line" % " ".join(bad), rc == 2 and one_error_line(err), err)

# bench: every case reported, with sane figures
csv = os.path.join(WORK, "bench.csv")
rc, out, err = run("bench", "demo:torus-20x10", "--levels", "1,2", "--threads", "1,2", "--repeat", "1", "--warmup", "0",
                   "--csv", csv)
rows = [l.split(",") for l in open(csv).read().splitlines()[1:]] if rc == 0 else []
evals = [r for r in rows if r[0] == "evaluate"]
check("bench eval: 1 mesh + 3 surface rows per thread count, 12 evaluate rows", rc == 0 and
      len([r for r in rows if r[0] == "mesh"]) == 2 and len([r for r in rows if r[0] == "patches"]) == 6 and
      len(evals) == 12 and all(float(r[7]) > 0 and float(r[4]) > 0 for r in evals), err + out[-300:])
check("bench eval: ratios printed", "phong/flat" in out and "pn/flat" in out and "of memcpy" in out)
rc, out, err = run("bench", "--suite", "table1", "--model", "demo:cylinder")
check("bench table1: three policies", rc == 0 and out.count("table1 ") == 3 and "uniform/adaptive" in out, err)

finish()
