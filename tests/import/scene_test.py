#!/usr/bin/env python3
"""Scene import (issue 11) checked against the files themselves.

Usage: scene_test.py IMPORT_DUMP DATA_DIR WORK_DIR

import_dump (tests/import/import_dump.c) prints a tlod_import_file_desc() result as JSON with
floats as bit patterns; every expected value here is read from the file independently (json +
struct for glTF accessors, our own PNG decoder for the Duck's texture, hand-computed matrices),
so a broken importer fails the comparison. Hostile files are generated at run time in WORK_DIR.
"""
import base64
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

DUMP, DATA, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(WORK, ignore_errors=True)
MODEL = os.path.join(WORK, "model")
os.makedirs(MODEL)
failures = []
NONE = -1  # TLOD_IMPORT_NONE as import_dump prints it (int)


def check(name, cond, detail=""):
    print(("ok   " if cond else "FAIL ") + name + ("" if cond else "  " + str(detail)[:600]))
    if not cond:
        failures.append(name)


def dump(path, keep=False, limit=None):
    args = [DUMP] + (["--keep-scene"] if keep else []) + (["--limit", str(limit)] if limit else []) + [path]
    out = subprocess.run(args, capture_output=True, text=True, timeout=120)
    return json.loads(out.stdout)


def f32(bits):
    return struct.unpack("<f", struct.pack("<I", bits))[0]


def bits_of(values):
    return [struct.unpack("<I", struct.pack("<f", v))[0] for v in values]


def attribute(res, name):
    for a in res.get("attributes", []):
        if a["name"] == name:
            return a
    return None


# --- glTF accessors read independently -------------------------------------------------

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
FORMATS = {5121: "B", 5123: "H", 5125: "I", 5126: "f"}


def buffer_bytes(gltf, folder, index):
    uri = gltf["buffers"][index]["uri"]
    if uri.startswith("data:"):
        return base64.b64decode(uri.split(",", 1)[1])
    with open(os.path.join(folder, uri), "rb") as f:
        return f.read()


def accessor_raw(gltf, folder, index):
    """Elements of an accessor as stored (ints stay ints), per element a tuple."""
    a = gltf["accessors"][index]
    bv = gltf["bufferViews"][a["bufferView"]]
    data = buffer_bytes(gltf, folder, bv["buffer"])
    fmt = FORMATS[a["componentType"]]
    n = COMPONENTS[a["type"]]
    size = struct.calcsize("<" + fmt)
    stride = bv.get("byteStride", size * n)
    base = bv.get("byteOffset", 0) + a.get("byteOffset", 0)
    return [struct.unpack_from("<%d%s" % (n, fmt), data, base + i * stride) for i in range(a["count"])]


def load_gltf(path):
    with open(path) as f:
        return json.load(f)


# --- our own PNG decoder (8-bit RGB/RGBA, not interlaced): the Duck's texture --------------


def png_rgba(path):
    """8-bit RGB, RGBA or palette (with tRNS), not interlaced, to RGBA8."""
    with open(path, "rb") as f:
        d = f.read()
    pos, idat, plte, trns = 8, b"", b"", b""
    while pos < len(d):
        n, tag = struct.unpack(">I4s", d[pos:pos + 8])
        body = d[pos + 8:pos + 8 + n]
        if tag == b"IHDR":
            w, h, depth, ct, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        elif tag == b"PLTE":
            plte = body
        elif tag == b"tRNS":
            trns = body
        pos += 12 + n
    assert depth == 8 and ct in (2, 3, 6) and interlace == 0
    bpp = {2: 3, 3: 1, 6: 4}[ct]
    raw, out, prev = zlib.decompress(idat), bytearray(), bytearray(w * bpp)
    for y in range(h):
        ft, line = raw[y * (w * bpp + 1)], bytearray(raw[y * (w * bpp + 1) + 1:(y + 1) * (w * bpp + 1)])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        for x in range(w):
            if ct == 3:
                k = line[x]
                out += plte[3 * k:3 * k + 3] + bytes([trns[k] if k < len(trns) else 255])
            else:
                out += line[x * bpp:x * bpp + 3] + (line[x * bpp + 3:x * bpp + 4] if bpp == 4 else b"\xff")
        prev = line
    return w, h, bytes(out)


def fnv(data):
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def zero_png(width, height):
    z, row = zlib.compressobj(9), b"\0" * (width + 1)
    comp = b"".join(z.compress(row) for _ in range(height)) + z.flush()

    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", comp) + chunk(b"IEND", b""))


# --- 1. The Duck: texture decoded, material, TEXCOORD_0 bitwise ------------------------------

duck_dir = os.path.join(DATA, "glTF-Sample-Models", "Duck", "glTF")
duck = load_gltf(os.path.join(duck_dir, "Duck.gltf"))
prim = duck["meshes"][0]["primitives"][0]
uv_expected = [c for e in accessor_raw(duck, duck_dir, prim["attributes"]["TEXCOORD_0"]) for c in e]
w, h, rgba = png_rgba(os.path.join(duck_dir, "DuckCM.png"))
for name, path in (("Duck.gltf", os.path.join(duck_dir, "Duck.gltf")),
                   ("Duck.glb", os.path.join(DATA, "glTF-Sample-Models", "Duck", "glTF-Binary", "Duck.glb"))):
    res = dump(path)
    check(name + ": imports", res["result"] == 0, res.get("error"))
    uv = attribute(res, "TEXCOORD_0")
    check(name + ": TEXCOORD_0 bitwise equal to the accessor (every vertex)",
          uv is not None and uv["components"] == 2 and uv["data"] == bits_of(uv_expected),
          uv and [f32(b) for b in uv["data"][:6]])
    mats = res.get("materials", [])
    tex_ok = len(mats) == 1 and mats[0]["texture"] == 0 and res["textures"][0][0] == 0
    check(name + ": material with base colour texture 0 on TEXCOORD_0",
          tex_ok and mats[0]["texcoord"] == res["attributes"].index(uv), mats)
    img = res.get("images", [{}])[0]
    check(name + ": DuckCM.png decoded %dx%d, pixels equal to our own PNG decode" % (w, h),
          img.get("decoded") == 1 and img["width"] == w == 512 and img["height"] == h == 512 and
          img["hash"] == fnv(rgba) and img["mime"] == "image/png", img)
    check(name + ": encoded bytes kept", img.get("encoded_size") == os.path.getsize(os.path.join(duck_dir, "DuckCM.png")))
    check(name + ": parts name mesh, material and node",
          res["parts"] == [{"mesh": 0, "node": 2, "material": 0, "first_vertex": 0, "vertex_count": 2399}], res["parts"])

# --- 2. SimpleSkin: skin, joints, weights, animation channel ---------------------------------

skin_dir = os.path.join(DATA, "glTF-Sample-Models", "SimpleSkin")
skin_path = os.path.join(skin_dir, "SimpleSkin.gltf")
sk = load_gltf(skin_path)
sp = sk["meshes"][0]["primitives"][0]["attributes"]
res = dump(skin_path, keep=True)
check("SimpleSkin: imports with keep_scene", res["result"] == 0, res.get("error"))
check("SimpleSkin: no bind-pose warning with keep_scene", "bind pose" not in res.get("warnings", ""), res.get("warnings"))
skins = res.get("skins", [])
ib = [c for e in accessor_raw(sk, skin_dir, sk["skins"][0]["inverseBindMatrices"]) for c in e]
check("SimpleSkin: skin joints and inverse bind matrices as in the file",
      len(skins) == 1 and skins[0]["joints"] == sk["skins"][0]["joints"] and skins[0]["inverse_bind"] == bits_of(ib),
      skins)
joints = [c for e in accessor_raw(sk, skin_dir, sp["JOINTS_0"]) for c in e]
weights = [c for e in accessor_raw(sk, skin_dir, sp["WEIGHTS_0"]) for c in e]
check("SimpleSkin: JOINTS_0 per vertex", res.get("joints") == joints, res.get("joints"))
check("SimpleSkin: WEIGHTS_0 per vertex (bitwise)", res.get("weights") == bits_of(weights))
check("SimpleSkin: node 0 uses skin 0 and mesh 0", res["nodes"][0]["skin"] == 0 and res["nodes"][0]["mesh"] == 0)
samp = sk["animations"][0]["samplers"][0]
times = [e[0] for e in accessor_raw(sk, skin_dir, samp["input"])]
values = [c for e in accessor_raw(sk, skin_dir, samp["output"]) for c in e]
anims = res.get("animations", [])
ch = anims[0][0] if anims and anims[0] else {}
check("SimpleSkin: rotation channel of node 2, LINEAR, key times and values as in the file",
      len(anims) == 1 and len(anims[0]) == 1 and ch["node"] == 2 and ch["path"] == 1 and ch["interp"] == 0 and
      ch["times"] == bits_of(times) and ch["values"] == bits_of(values), ch)
flat = dump(skin_path)
check("SimpleSkin: flattened mode keeps the bind-pose warning", "bind pose" in flat.get("warnings", ""), flat)


# --- 3. A generated scene: 3 nodes, 2 meshes, one instanced twice ----------------------------


def mat_mul(a, b):  # column-major 4x4
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def trs(t, q, s):
    x, y, z, w_ = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w_), 2 * (x * z + y * w_)],
         [2 * (x * y + z * w_), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w_)],
         [2 * (x * z - y * w_), 2 * (y * z + x * w_), 1 - 2 * (x * x + y * y)]]
    m = [0.0] * 16
    for c in range(3):
        for row in range(3):
            m[c * 4 + row] = r[row][c] * s[c]
    m[12:15] = t
    m[15] = 1.0
    return m


def gltf_with(nodes, scenes_nodes, meshes_positions, extra=None, prim_extra=None):
    """Meshes from lists of triangle positions; extra(g, add_accessor) may add more."""
    blob, views, accessors = bytearray(), [], []

    def add(values, fmt, ctype, type_, normalized=False, count=None):
        while len(blob) % 4:
            blob.append(0)
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        blob.extend(data)
        a = {"bufferView": len(views) - 1, "componentType": ctype, "type": type_,
             "count": count if count is not None else len(values) // COMPONENTS[type_]}
        if normalized:
            a["normalized"] = True
        accessors.append(a)
        return len(accessors) - 1

    meshes = []
    for i, pos in enumerate(meshes_positions):
        attrs = {"POSITION": add(pos, "f", 5126, "VEC3")}
        p = {"attributes": attrs}
        if prim_extra:
            prim_extra(i, p, add)
        meshes.append({"primitives": [p]})
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": scenes_nodes}], "nodes": nodes,
         "meshes": meshes}
    if extra:
        extra(g, add)
    g["accessors"], g["bufferViews"] = accessors, views
    g["buffers"] = [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]
    return g


def write(name, obj, folder=MODEL):
    path = os.path.join(folder, name)
    with open(path, "w" if isinstance(obj, (dict, str)) else "wb") as f:
        if isinstance(obj, dict):
            json.dump(obj, f)
        else:
            f.write(obj)
    return path


tri0 = [0, 0, 0, 1, 0, 0, 0, 1, 0]
tri1 = [0, 0, 0, 2, 0, 0, 0, 0, 3]
h2 = math.sqrt(0.5)
n0 = {"translation": [1, 2, 3], "rotation": [0, 0, h2, h2], "scale": [2, 2, 2], "mesh": 0, "children": [1]}
m1 = [0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 5, 1]  # 90 degrees about y, then (0, 0, 5)
n1 = {"matrix": m1, "mesh": 1}
n2 = {"translation": [-4, 0, 0], "mesh": 0}
scene_path = write("three_nodes.gltf", gltf_with([n0, n1, n2], [0, 2], [tri0, tri1]))
w0 = trs([1, 2, 3], [0, 0, h2, h2], [2, 2, 2])
expected_world = [w0, mat_mul(w0, m1), trs([-4, 0, 0], [0, 0, 0, 1], [1, 1, 1])]
for keep in (True, False):
    tag = "scene (keep_scene)" if keep else "scene (flattened)"
    res = dump(scene_path, keep=keep)
    check(tag + ": imports", res["result"] == 0, res.get("error"))
    got = [[f32(b) for b in n["world"]] for n in res.get("nodes", [])]
    check(tag + ": node world matrices equal hand-computed T*R*S, matrix and parent products",
          len(got) == 3 and all(abs(a - b) < 1e-6 for g_, e in zip(got, expected_world) for a, b in zip(g_, e)), got)
    check(tag + ": node parents", [n["parent"] for n in res["nodes"]] == [NONE, 0, NONE])
    check(tag + ": node 0 TRS as written",
          [f32(b) for b in res["nodes"][0]["trs"]] == [1, 2, 3] and
          max(abs(f32(b) - e) for b, e in zip(res["nodes"][0]["rotation"], [0, 0, h2, h2])) < 1e-7)
    r1 = [f32(b) for b in res["nodes"][1]["rotation"]]
    check(tag + ": matrix node decomposed to TRS (90 degrees about y, t = (0, 0, 5))",
          [f32(b) for b in res["nodes"][1]["trs"]] == [0, 0, 5] and
          min(max(abs(a - b) for a, b in zip(r1, q)) for q in ([0, h2, 0, h2], [0, -h2, 0, -h2])) < 1e-6, r1)
parts = dump(scene_path, keep=True)["parts"]
check("scene (keep_scene): each mesh once, in mesh space, no node",
      [(p["mesh"], p["node"], p["vertex_count"]) for p in parts] == [(0, NONE, 3), (1, NONE, 3)], parts)
res = dump(scene_path, keep=True)
check("scene (keep_scene): mesh-space positions bitwise as in the accessors",
      res["positions"] == bits_of(tri0 + tri1) and res["meshes"] == [[0, 1], [1, 1]], res["meshes"])
parts = dump(scene_path)["parts"]
check("scene (flattened): mesh 0 instanced at nodes 0 and 2, mesh 1 at node 1",
      sorted((p["mesh"], p["node"]) for p in parts) == [(0, 0), (0, 2), (1, 1)], parts)


# --- 4. Hostile images: loads with a warning naming the image, never decoded past the rules ---


def textured(image, name):
    """A triangle whose material's base colour texture is image (a glTF image object)."""
    def extra(g, add):
        g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        g["textures"] = [{"source": 0}]
        g["images"] = [image]

    def prim_extra(i, p, add):
        p["material"] = 0
        p["attributes"]["TEXCOORD_0"] = add([0, 0, 1, 0, 0, 1], "f", 5126, "VEC2")
    return write(name, gltf_with([{"mesh": 0}], [0], [tri0], extra, prim_extra))


def data_uri(blob, mime="image/png"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(blob).decode())


# 9000 x 9000 (81M pixels > 64M): would need 324 MB of RGBA if decoded.
res = dump(textured({"uri": data_uri(zero_png(9000, 9000))}, "huge_image.gltf"))
check("image past TLOD_IMPORT_MAX_IMAGE_PIXELS: model loads, image 0 refused with a warning",
      res["result"] == 0 and "image 0" in res["warnings"] and "pixel limit" in res["warnings"] and
      res["images"][0]["decoded"] == 0, res.get("warnings", res.get("error")))
check("image past the pixel limit: refused before decoding (peak RSS %d KB < 200 MB)" % res["rss_kb"],
      res["rss_kb"] < 200 * 1024)
# 4000 x 4000 (16M pixels: under the limit, 64 MB decoded) against a 48 MB budget.
res = dump(textured({"uri": data_uri(zero_png(4000, 4000))}, "budget_image.gltf"), limit=48 << 20)
check("image past the memory budget: model loads, image 0 refused naming the budget",
      res["result"] == 0 and "memory budget" in res["warnings"] and res["images"][0]["decoded"] == 0,
      res.get("warnings", res.get("error")))
check("image past the budget: refused before allocating (peak RSS %d KB < 60 MB)" % res["rss_kb"],
      res["rss_kb"] < 60 * 1024)
with open(os.path.join(duck_dir, "DuckCM.png"), "rb") as f:
    duck_png = f.read()
with open(os.path.join(DATA, "images", "rgb16.jpg"), "rb") as f:
    jpeg = f.read()
write("trunc.png", duck_png[:len(duck_png) // 2])
write("trunc.jpg", jpeg[:len(jpeg) * 2 // 3])
write("whole.jpg", jpeg)
for uri in ("trunc.png", "trunc.jpg"):
    res = dump(textured({"uri": uri}, uri + ".gltf"))
    check("truncated %s: loads, warning names the URI, no pixels" % uri[-3:].upper(),
          res["result"] == 0 and ("'%s'" % uri) in res["warnings"] and res["images"][0]["decoded"] == 0 and
          res["images"][0]["encoded_size"] > 0, res.get("warnings", res.get("error")))
res = dump(textured({"uri": "whole.jpg"}, "jpeg.gltf"))
img = res["images"][0]
check("JPEG texture decoded (16x16, first pixel near (0, 0, 128))",
      img["decoded"] == 1 and img["width"] == 16 and abs(img["px0"][2] - 128) <= 12 and img["mime"] == "image/jpeg", img)
with open(os.path.join(WORK, "outside.png"), "wb") as f:
    f.write(duck_png)
for uri in ("../outside.png", "%2e%2e/outside.png", "/etc/passwd"):
    res = dump(textured({"uri": uri}, "escape.gltf"))
    check("image URI %s escaping the folder: loads, warning names the URI, nothing read" % uri,
          res["result"] == 0 and ("'%s'" % uri) in res["warnings"] and res["images"][0]["decoded"] == 0 and
          res["images"][0]["encoded_size"] == 0 and str(len(duck_png)) not in res["warnings"],
          res.get("warnings", res.get("error")))
res = dump(textured({"bufferView": 0, "mimeType": "image/png"}, "bad_view.gltf"))  # the positions, not a PNG
check("image whose bufferView holds no image: loads, warning names image 0", res["result"] == 0 and
      "image 0: not a PNG or JPEG image" in res["warnings"] and res["images"][0]["encoded_size"] == 36,
      res.get("warnings", res.get("error")))


# --- 5. Hostile skins and animations: errors naming the accessor or node ---------------------


def skinned(name, joints, weights, ib=None, joints_type=(5121, "B")):
    def extra(g, add):
        g["nodes"][0]["skin"] = 0
        skin = {"joints": [1, 2]}
        if ib is not None:
            skin["inverseBindMatrices"] = add(ib, "f", 5126, "MAT4")
        g["skins"] = [skin]

    def prim_extra(i, p, add):
        p["attributes"]["JOINTS_0"] = add(joints, joints_type[1], joints_type[0], "VEC4")
        p["attributes"]["WEIGHTS_0"] = add(weights, "f", 5126, "VEC4")
    return write(name, gltf_with([{"mesh": 0}, {"children": [2]}, {}], [0, 1], [tri0], extra, prim_extra))


ident = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
good_w = [1, 0, 0, 0, 0.5, 0.5, 0, 0, 0.25, 0.75, 0, 0]
res = dump(skinned("skin_ok.gltf", [0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0], good_w, ident * 2), keep=True)
check("valid generated skin imports (u8 joints)", res["result"] == 0 and res["joints"][:8] == [0, 0, 0, 0, 0, 1, 0, 0],
      res.get("error"))
joints_acc = 1  # accessor 0 is POSITION, then JOINTS_0, WEIGHTS_0, inverse binds
for label, args, words in (
        ("joint index 2 with 2 joints", ([0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0], good_w, ident * 2),
         ["JOINTS_0 accessor 1", "out of range"]),
        ("negative weight", ([0] * 12, [1.5, -0.5, 0, 0] + good_w[4:], ident * 2), ["WEIGHTS_0 accessor 2", "negative"]),
        ("weights summing to 1.05", ([0] * 12, [1.05, 0, 0, 0] + good_w[4:], ident * 2), ["WEIGHTS_0 accessor 2", "sum"]),
        ("singular inverse bind matrix", ([0] * 12, good_w, ident + [1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]),
         ["inverseBindMatrices", "accessor 3", "not invertible"]),
        ("non-finite inverse bind matrix", ([0] * 12, good_w, ident + [float("nan")] + ident[1:]),
         ["inverseBindMatrices", "accessor 3"])):
    res = dump(skinned("skin_bad.gltf", *args), keep=True)
    check("refused: %s (error names the accessor)" % label,
          res["result"] != 0 and all(w_ in res["error"] for w_ in words), res.get("error"))
res = dump(skinned("skin_renorm.gltf", [0] * 12, [0.995, 0, 0, 0] + good_w[4:], ident * 2), keep=True)
wts = [f32(b) for b in res.get("weights", [])]
check("weights summing to 0.995: renormalised to 1 and counted in a warning",
      res["result"] == 0 and res["weights_renormalised"] == 1 and wts[0] == 1.0 and "renormalised" in res["warnings"],
      res.get("error") or res.get("warnings"))


def animated(name, times, values, path="translation", interp="LINEAR", node=0):
    def extra(g, add):
        t = add(times, "f", 5126, "SCALAR")
        v = add(values, "f", 5126, "VEC4" if path == "rotation" else "VEC3")
        g["animations"] = [{"channels": [{"sampler": 0, "target": {"node": node, "path": path}}],
                            "samplers": [{"input": t, "output": v, "interpolation": interp}]}]
    return write(name, gltf_with([{"mesh": 0}], [0], [tri0], extra))


res = dump(animated("anim_step.gltf", [0, 1, 2], [0, 0, 0, 1, 0, 0, 2, 0, 0], interp="STEP"), keep=True)
ch = res["animations"][0][0] if res.get("animations") else {}
check("STEP translation channel imported with its keys", res["result"] == 0 and ch.get("interp") == 1 and
      ch.get("times") == bits_of([0, 1, 2]), res.get("error"))
res = dump(animated("anim_cubic.gltf", [0, 1], list(range(18)), interp="CUBICSPLINE"), keep=True)
check("CUBICSPLINE channel keeps in-tangent, value, out-tangent (18 floats for 2 keys)",
      res["result"] == 0 and res["animations"][0][0]["values"] == bits_of(list(range(18))), res.get("error"))
for label, args, words in (
        ("non-increasing times", ([0, 1, 1], [0] * 9), ["input accessor 1", "does not increase"]),
        ("non-finite time", ([0, float("inf")], [0] * 6), ["input accessor 1", "not finite"]),
        ("value count not matching the keys", ([0, 1, 2], [0] * 6), ["output accessor 2"])):
    res = dump(animated("anim_bad.gltf", *args), keep=True)
    check("refused: animation with %s (error names the accessor)" % label,
          res["result"] != 0 and all(w_ in res["error"] for w_ in words), res.get("error"))
res = dump(animated("anim_node.gltf", [0, 1], [0] * 6, node=7), keep=True)
check("refused: channel targeting node 7 of 1 (error names the node)", res["result"] != 0 and "node 7" in res["error"],
      res.get("error"))
res = dump(animated("anim_weights.gltf", [0, 1], [0] * 6, path="weights"), keep=True)
check("weights channel: warning 'morph target animation ignored'",
      res["result"] == 0 and "morph target animation ignored" in res["warnings"], res.get("warnings"))


def morph(g, add):
    g["meshes"][0]["name"] = "blob"
    g["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 0}]


res = dump(write("morph.gltf", gltf_with([{"mesh": 0}], [0], [tri0], morph)))
check("morph targets: warning naming the mesh", res["result"] == 0 and "mesh 0 'blob'" in res["warnings"] and
      "morph targets ignored" in res["warnings"], res.get("warnings"))

# --- 6. OBJ with vt and mtllib map_Kd; PLY with u v and colours ------------------------------

shutil.copy(os.path.join(duck_dir, "DuckCM.png"), os.path.join(MODEL, "duck.png"))
write("tex.mtl", "newmtl skin\nKd 0.5 0.25 1\nd 0.75\nmap_Kd duck.png\n")
obj = write("tex.obj", "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 0.25\nvt 0.5 0.5\n"
            "usemtl skin\nf 1/1 2/2 3/3\nf 2/4 4/2 3/3\n")
res = dump(obj)
uv = attribute(res, "TEXCOORD_0")
# Corners (v, vt): (1,1) (2,2) (3,3) (2,4) (4,2): five vertices, ordered by v then vt.
want = [0, 1 - 0.0, 1, 1 - 0.0, 0.5, 1 - 0.5, 0, 1 - 0.25, 1, 1 - 0.0]
check("OBJ: one vertex per (v, vt, vn): v 2 with two vt gives 5 vertices", res.get("vertex_count") == 5,
      res.get("vertex_count"))
check("OBJ: vt as TEXCOORD_0 with v' = 1 - v (bitwise)", uv is not None and uv["data"] == bits_of(want),
      uv and [f32(b) for b in uv["data"]])
mat = res.get("materials", [{}])[0]
check("OBJ: Kd, d and map_Kd make a material with texture on TEXCOORD_0",
      [f32(b) for b in mat.get("base_color", [])] == [0.5, 0.25, 1, 0.75] and mat.get("texture") == 0 and
      mat.get("texcoord") == 0 and mat.get("alpha_mode") == 2 and res["parts"][0]["material"] == 0, mat)
check("OBJ: map_Kd image decoded like the glTF one", res.get("images", [{}])[0].get("hash") == fnv(rgba),
      res.get("images"))
write("escape.mtl", "newmtl x\nKd 1 1 1\nmap_Kd ../outside.png\n")
res = dump(write("escape.obj", "mtllib escape.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n"))
check("OBJ: map_Kd escaping the folder: loads, warning names it", res["result"] == 0 and
      "map_Kd '../outside.png'" in res["warnings"] and res["images"][0]["decoded"] == 0, res.get("warnings"))

ply_text = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "property float u\nproperty float v\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "property uchar alpha\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 0.1 0.2 255 0 51 128\n1 0 0 0.3 0.4 1 2 3 4\n0 1 0 0.5 0.6 10 20 30 40\n3 0 1 2\n")
res = dump(write("uv.ply", ply_text))
uv, col = attribute(res, "TEXCOORD_0"), attribute(res, "COLOR_0")
check("PLY: u v as TEXCOORD_0 (bitwise)", uv is not None and uv["data"] == bits_of([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]),
      res.get("error"))
rgba_ply = [255, 0, 51, 128, 1, 2, 3, 4, 10, 20, 30, 40]
check("PLY: red green blue alpha uchar / 255 as COLOR_0 (bitwise)",
      col is not None and col["components"] == 4 and col["data"] == bits_of([c / 255.0 for c in rgba_ply]), col)
body = b"".join(struct.pack("<3f2fBBB", x, y, 0, s, t, 9, 8, 7) for x, y, s, t in
                ((0, 0, 0.25, 0.5), (1, 0, 0.75, 1.0), (0, 1, 0, 0)))
hdr = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nproperty float s\nproperty float t\nproperty uchar red\nproperty uchar green\n"
       "property uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").encode()
res = dump(write("st.ply", hdr + body + struct.pack("<B3i", 3, 0, 1, 2)))
uv, col = attribute(res, "TEXCOORD_0"), attribute(res, "COLOR_0")
check("PLY (binary): s t as TEXCOORD_0, RGB without alpha gets alpha 1",
      uv is not None and uv["data"] == bits_of([0.25, 0.5, 0.75, 1.0, 0, 0]) and col is not None and
      col["data"][:4] == bits_of([9 / 255.0, 8 / 255.0, 7 / 255.0, 1.0]), res.get("error"))

print("%d failed" % len(failures))
sys.exit(1 if failures else 0)
