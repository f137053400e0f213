#!/usr/bin/env python3
"""tlod tessellate's exports keep the look (issue 11): glTF/GLB outputs of the Khronos Duck pass the Khronos
glTF validator (npm gltf-validator through node, installed by scripts/bootstrap) with zero errors, keep the
input's UVs bitwise at its corner vertices, its material, texture and image bytes; OBJ and PLY outputs carry the
UVs (vt, u v); a generated multi-node scene keeps its node hierarchy, matrices, meshes and materials, per-instance
meshes with a camera, and its instances placed in world space in OBJ. Both files of each comparison are read here
independently (json + struct), not through tesslod.
Usage: export_test.py TLOD DATA_DIR WORK_DIR REPO_DIR"""
import base64, json, math, os, shutil, struct, subprocess, sys

from tlod_cli import init, run, check, finish

TLOD, DATA, WORK, REPO = sys.argv[1:5]
init(TLOD)
os.makedirs(WORK, exist_ok=True)
DUCK_GLTF = os.path.join(DATA, "glTF-Sample-Models/Duck/glTF/Duck.gltf")
DUCK_GLB = os.path.join(DATA, "glTF-Sample-Models/Duck/glTF-Binary/Duck.glb")
DUCK_PNG = os.path.join(DATA, "glTF-Sample-Models/Duck/glTF/DuckCM.png")


# ---------------------------------------------------------------- glTF reading (independent of tesslod)

def load_gltf(path):
    """(json, [bytes of each buffer])"""
    raw = open(path, "rb").read()
    if raw[:4] == b"glTF":
        jlen = struct.unpack_from("<I", raw, 12)[0]
        doc = json.loads(raw[20:20 + jlen])
        rest = raw[20 + jlen:]
        bins = [rest[8:8 + struct.unpack_from("<I", rest, 0)[0]]] if rest else []
    else:
        doc, bins = json.loads(raw), []
    buffers = []
    for i, b in enumerate(doc.get("buffers", [])):
        uri = b.get("uri")
        if uri is None:
            buffers.append(bins[0])
        elif uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            buffers.append(open(os.path.join(os.path.dirname(path), uri), "rb").read())
    return doc, buffers


SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
FORMATS = {5126: "f", 5125: "I", 5123: "H", 5121: "B"}


def accessor(doc, buffers, index, raw=False):
    """Elements of an accessor: tuples of values, or (raw) bytes of each element."""
    a = doc["accessors"][index]
    v = doc["bufferViews"][a["bufferView"]]
    n, fmt = SIZES[a["type"]], FORMATS[a["componentType"]]
    size = n * struct.calcsize(fmt)
    stride = v.get("byteStride", size)
    data = buffers[v["buffer"]]
    base = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    out = []
    for i in range(a["count"]):
        chunk = data[base + i * stride:base + i * stride + size]
        out.append(bytes(chunk) if raw else struct.unpack("<%d%s" % (n, fmt), chunk))
    return out


def image_bytes(doc, buffers, path, index):
    im = doc["images"][index]
    if "bufferView" in im:
        v = doc["bufferViews"][im["bufferView"]]
        return buffers[v["buffer"]][v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]
    if im["uri"].startswith("data:"):
        return base64.b64decode(im["uri"].split(",", 1)[1])
    return open(os.path.join(os.path.dirname(path), im["uri"]), "rb").read()


def quat_matrix(q):
    x, y, z, w = q
    return [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
            2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
            2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0, 0, 0, 0, 1]


def local(node):
    if "matrix" in node:
        return node["matrix"]
    m = quat_matrix(node.get("rotation", [0, 0, 0, 1]))
    s = node.get("scale", [1, 1, 1])
    for col in range(3):
        for row in range(3):
            m[4 * col + row] *= s[col]
    m[12:15] = node.get("translation", [0, 0, 0])
    return m


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


# ---------------------------------------------------------------- the validator

VALIDATE_JS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gltf_validate.js")
NODE_MODULES = os.path.join(REPO, "node_modules")


def validate(path):
    """(errors, report or message)"""
    if not shutil.which("node"):
        return -1, "node not found: run scripts/bootstrap (installs nodejs and npm ci's gltf-validator)"
    p = subprocess.run(["node", VALIDATE_JS, NODE_MODULES, path], capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        return -1, "validator did not run (exit %d): %s" % (p.returncode, p.stderr.strip())
    report = json.loads(p.stdout)
    return report["issues"]["numErrors"], [(m["code"], m.get("pointer"), m["message"])
                                           for m in report["issues"]["messages"] if m["severity"] == 0][:10]


errors, detail = validate(DUCK_GLTF)
check("the Khronos glTF validator is installed and passes the input Duck", errors == 0, detail)

# ---------------------------------------------------------------- the Duck as .gltf and .glb

src_doc, src_bufs = load_gltf(DUCK_GLTF)
src_prim = src_doc["meshes"][0]["primitives"][0]
src_pos = accessor(src_doc, src_bufs, src_prim["attributes"]["POSITION"], raw=True)
src_uv = accessor(src_doc, src_bufs, src_prim["attributes"]["TEXCOORD_0"], raw=True)
src_idx = accessor(src_doc, src_bufs, src_prim["indices"])
corners = sorted({i[0] for i in src_idx})
png = open(DUCK_PNG, "rb").read()

for src in (DUCK_GLTF, DUCK_GLB):
    for ext in ("gltf", "glb"):
        name = "%s -> .%s" % (os.path.basename(src), ext)
        out = os.path.join(WORK, "duck_%s.%s" % (os.path.basename(src).replace(".", "_"), ext))
        rc, so, se = run("tessellate", src, "-o", out, "--level", "2", "-q")
        if not check("%s: written" % name, rc == 0 and os.path.exists(out), se):
            continue
        errors, detail = validate(out)
        check("%s: the Khronos validator reports 0 errors" % name, errors == 0, detail)
        doc, bufs = load_gltf(out)
        check("%s: nodes, their children (in any order) and meshes kept" % name,
              len(doc["nodes"]) == len(src_doc["nodes"]) and
              [n.get("mesh") for n in doc["nodes"]] == [n.get("mesh") for n in src_doc["nodes"]] and
              [sorted(n.get("children", [])) for n in doc["nodes"]] ==
              [sorted(n.get("children", [])) for n in src_doc["nodes"]], json.dumps(doc["nodes"])[:300])
        bad = [i for i, (a, b) in enumerate(zip(doc["nodes"], src_doc["nodes"]))
               if max(abs(x - y) for x, y in zip(local(a), local(b))) > 1e-6 * max(1.0, max(map(abs, local(b))))]
        check("%s: node matrices kept (TRS or matrix, 1e-6 relative)" % name, not bad, "nodes %s differ" % bad)
        prim = doc["meshes"][0]["primitives"][0]
        pos = accessor(doc, bufs, prim["attributes"]["POSITION"], raw=True)
        uv = accessor(doc, bufs, prim["attributes"]["TEXCOORD_0"], raw=True) if "TEXCOORD_0" in prim["attributes"] \
            else []
        pairs = set(zip(pos, uv))
        missing = [c for c in corners if (src_pos[c], src_uv[c]) not in pairs]
        check("%s: TEXCOORD_0 bitwise equal to the input's at all %d corner vertices" % (name, len(corners)),
              uv and not missing, "%d corners without their (position, uv) pair, e.g. vertex %s" %
              (len(missing), missing[:3]))
        check("%s: more vertices than the input (level 2 tessellated)" % name, len(pos) > len(src_pos))
        mat = doc["materials"][prim["material"]] if "material" in prim else {}
        tex = mat.get("pbrMetallicRoughness", {}).get("baseColorTexture", {})
        ok = "index" in tex and tex.get("texCoord", 0) == 0 and "source" in doc["textures"][tex["index"]]
        check("%s: material with its baseColorTexture (texCoord 0) and image" % name, ok, json.dumps(mat))
        if ok:
            t = doc["textures"][tex["index"]]
            check("%s: sampler kept" % name, doc["samplers"][t["sampler"]] == src_doc["samplers"][0],
                  str(doc.get("samplers")))
            img = image_bytes(doc, bufs, out, t["source"])
            check("%s: image bytes equal to the input's DuckCM.png (so it decodes the same)" % name, img == png,
                  "%d bytes vs %d" % (len(img), len(png)))
            check("%s: image embedded (nothing written beside the output)" % name,
                  "uri" not in doc["images"][t["source"]] or doc["images"][t["source"]]["uri"].startswith("data:"))

# OBJ and PLY: UVs as vt (v flipped back) and u v
want_uv = {(struct.unpack("<f", u[:4])[0], f32(1.0 - struct.unpack("<f", u[4:])[0])) for u in src_uv}
o = os.path.join(WORK, "duck.obj")
rc, so, se = run("tessellate", DUCK_GLB, "-o", o, "--level", "1", "-q")
vt = set()
faces_ok = True
if rc == 0:
    for line in open(o):
        if line.startswith("vt "):
            vt.add(tuple(f32(float(x)) for x in line.split()[1:3]))
        elif line.startswith("f ") and (line.split()[1].count("/") != 2 or "//" in line):
            faces_ok = False
check("OBJ: vt lines hold every input UV (v = 1 - v')", rc == 0 and want_uv <= vt,
      "%d of %d input UVs missing" % (len(want_uv - vt), len(want_uv)) if rc == 0 else se)
check("OBJ: faces reference v/vt/vn", rc == 0 and faces_ok)

o = os.path.join(WORK, "duck.ply")
rc, so, se = run("tessellate", DUCK_GLB, "-o", o, "--level", "1", "-q")
if check("PLY: written", rc == 0, se):
    raw = open(o, "rb").read()
    head, body = raw.split(b"end_header\n", 1)
    props = [l.split()[-1] for l in head.decode().splitlines() if l.startswith("property ") and "list" not in l]
    check("PLY: u v properties (float)", b"property float u\nproperty float v\n" in head, head.decode())
    nverts = int([l for l in head.decode().splitlines() if l.startswith("element vertex")][0].split()[2])
    nfloat = len([p for p in props if p in ("x", "y", "z", "nx", "ny", "nz", "u", "v")])
    iu = props.index("u") if "u" in props else -1
    got = set()
    for i in range(nverts if iu >= 0 else 0):
        vals = struct.unpack_from("<%df" % nfloat, body, i * 4 * nfloat)
        got.add((vals[iu], vals[iu + 1]))
    want_ply = {struct.unpack("<2f", u) for u in src_uv}
    check("PLY: u v hold every input UV bitwise (as stored)", want_ply <= got, "%d missing" % len(want_ply - got))


# ---------------------------------------------------------------- a generated multi-node scene

def cube():
    """24 vertices (a face each 4), normals, UVs, 12 triangles."""
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            a, b = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos)
            for (s, t) in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[a], p[b] = sign, 2 * s - 1.0, 2 * t - 1.0
                pos.append(p), nrm.append(n), uv.append([s * 0.5, t * 0.25])
            quad = [base, base + 1, base + 2, base, base + 2, base + 3]
            idx += quad if sign > 0 else [quad[0], quad[2], quad[1], quad[3], quad[5], quad[4]]
    return pos, nrm, uv, idx


def scene_gltf(path):
    pos, nrm, uv, idx = cube()
    blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm) + \
        b"".join(struct.pack("<2f", *t) for t in uv) + b"".join(struct.pack("<I", i) for i in idx)
    nv = len(pos)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * nv}, {"buffer": 0, "byteOffset": 12 * nv,
             "byteLength": 12 * nv}, {"buffer": 0, "byteOffset": 24 * nv, "byteLength": 8 * nv},
             {"buffer": 0, "byteOffset": 32 * nv, "byteLength": 4 * len(idx)}]
    acc = [{"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": [-1] * 3, "max": [1] * 3},
           {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
           {"bufferView": 2, "componentType": 5126, "count": nv, "type": "VEC2"},
           {"bufferView": 3, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]
    prim = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}
    c, s = math.cos(0.3), math.sin(0.3)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 3]}],
           "nodes": [{"name": "root", "children": [1, 2], "translation": [1, 2, 3], "scale": [2, 2, 2],
                      "rotation": [0, math.sin(0.25), 0, math.cos(0.25)]},
                     {"name": "left", "mesh": 0, "matrix": [c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1]},
                     {"name": "right", "mesh": 0, "translation": [-3, 0, 0]},
                     {"name": "other", "mesh": 1, "translation": [0, 10, 0], "scale": [0.5, 0.5, 0.5]}],
           "meshes": [{"name": "cube", "primitives": [dict(prim, material=0)]},
                      {"name": "two", "primitives": [dict(prim, material=0), dict(prim, material=1)]}],
           "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}},
                         {"name": "cut", "pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 0.5],
                                                                  "metallicFactor": 0.25, "roughnessFactor": 0.5},
                          "alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": True}],
           "accessors": acc, "bufferViews": views,
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    json.dump(doc, open(path, "w"))
    return doc


def mul(a, b):
    return [sum(a[4 * k + r] * b[4 * c + k] for k in range(4)) for c in range(4) for r in range(4)]


def worlds(doc):
    out = {}

    def walk(n, parent):
        out[n] = mul(parent, local(doc["nodes"][n]))
        for ch in doc["nodes"][n].get("children", []):
            walk(ch, out[n])
    for r in doc["scenes"][0]["nodes"]:
        walk(r, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    return out


scene_in = os.path.join(WORK, "scene.gltf")
sdoc = scene_gltf(scene_in)
errors, detail = validate(scene_in)
check("generated scene: valid input", errors == 0, detail)
for ext in ("gltf", "glb"):
    o = os.path.join(WORK, "scene_out." + ext)
    rc, so, se = run("tessellate", scene_in, "-o", o, "--level", "2", "-q")
    if not check("scene -> .%s: written" % ext, rc == 0, se):
        continue
    errors, detail = validate(o)
    check("scene -> .%s: the Khronos validator reports 0 errors" % ext, errors == 0, detail)
    doc, bufs = load_gltf(o)
    check("scene -> .%s: hierarchy, names and meshes of the nodes kept" % ext,
          [(n.get("name", ""), sorted(n.get("children", [])), n.get("mesh")) for n in doc["nodes"]] ==
          [(n.get("name", ""), sorted(n.get("children", [])), n.get("mesh")) for n in sdoc["nodes"]] and
          doc["scenes"][0]["nodes"] == sdoc["scenes"][0]["nodes"], json.dumps(doc["nodes"]))
    bad = [i for i, (a, b) in enumerate(zip(doc["nodes"], sdoc["nodes"]))
           if max(abs(x - y) for x, y in zip(local(a), local(b))) > 1e-6]
    check("scene -> .%s: every node's local matrix kept (1e-6)" % ext, not bad and len(doc["nodes"]) == 4,
          "nodes %s differ" % bad)
    check("scene -> .%s: meshes with one primitive per part and its material" % ext,
          [[p.get("material") for p in m["primitives"]] for m in doc["meshes"]] == [[0], [0, 1]] and
          [m.get("name") for m in doc["meshes"]] == ["cube", "two"], json.dumps(doc["meshes"])[:300])
    m1 = doc["materials"][1]
    check("scene -> .%s: materials kept (factor, MASK, cutoff, double-sided)" % ext,
          doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] == [1, 0, 0, 1] and
          m1["pbrMetallicRoughness"]["baseColorFactor"] == [0, 1, 0, 0.5] and m1.get("alphaMode") == "MASK" and
          m1.get("alphaCutoff") == 0.25 and m1.get("doubleSided") is True, json.dumps(doc["materials"]))
    # metallic and roughness: given values kept, absent ones written as glTF's default 1 (a viewer's look)
    pbr = [m["pbrMetallicRoughness"] for m in doc["materials"]]
    check("scene -> .%s: metallic and roughness kept (absent: 1, 1)" % ext,
          [(p.get("metallicFactor", 1), p.get("roughnessFactor", 1)) for p in pbr] == [(1, 1), (0.25, 0.5)],
          json.dumps(pbr))

# with a camera, each instance of the shared cube gets its own tessellation and mesh
o = os.path.join(WORK, "scene_eye.gltf")
rc, so, se = run("tessellate", scene_in, "-o", o, "--eye", "0,3,25", "--max-level", "4", "-q")
if check("scene with a camera: written", rc == 0, se):
    errors, detail = validate(o)
    check("scene with a camera: 0 validator errors", errors == 0, detail)
    doc, bufs = load_gltf(o)
    meshes = [n.get("mesh") for n in doc["nodes"]]
    check("scene with a camera: the second instance has a mesh of its own '<mesh>@<node>'",
          meshes[1] == 0 and meshes[2] == 2 and meshes[3] == 1 and doc["meshes"][2].get("name") == "cube@right",
          json.dumps([meshes, [m.get("name") for m in doc["meshes"]]]))

# a camera looking away culls every instance: each is written at level 0 (needs no pattern level beyond --max-level)
o = os.path.join(WORK, "scene_away.glb")
st = os.path.join(WORK, "scene_away.json")
rc, so, se = run("tessellate", scene_in, "-o", o, "--eye", "0,3,25", "--target", "0,3,50", "--max-level", "2",
                 "--stats", st, "-q")
stats = json.load(open(st)) if rc == 0 else {}
check("scene seen from behind: 4 culled instances written at level 0, 0 validator errors",
      rc == 0 and stats["scene"]["culled_instances"] == 4 and validate(o)[0] == 0, se or stats)

# OBJ of the scene: every instance in world space (flat surface: the box of each instance is its cube's)
o = os.path.join(WORK, "scene.obj")
rc, so, se = run("tessellate", scene_in, "-o", o, "--surface", "flat", "--level", "1", "-q")
if check("scene -> .obj: written", rc == 0, se):
    vs = [tuple(map(float, l.split()[1:4])) for l in open(o) if l.startswith("v ")]
    w = worlds(sdoc)
    pts = []
    for n, node in enumerate(sdoc["nodes"]):
        for _ in ([0] if node.get("mesh") == 0 else [0, 1] if node.get("mesh") == 1 else []):
            for p in cube()[0]:
                m = w[n]
                pts.append(tuple(m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k] for k in range(3)))
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    glo = [min(p[k] for p in vs) for k in range(3)]
    ghi = [max(p[k] for p in vs) for k in range(3)]
    check("scene -> .obj: 4 instances placed at their world matrices (bounding box within 1e-4)",
          max(abs(a - b) for a, b in zip(lo + hi, glo + ghi)) < 1e-4, "%s %s vs %s %s" % (lo, hi, glo, ghi))
    corner_hits = sum(1 for p in pts if any(max(abs(a - b) for a, b in zip(p, v)) < 1e-4 for v in vs))
    check("scene -> .obj: every instance's cube corners present", corner_hits == len(pts),
          "%d of %d" % (corner_hits, len(pts)))

finish()
