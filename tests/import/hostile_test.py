#!/usr/bin/env python3
"""Hostile model files (issue #10, docs/security.md), made here at run time in a
scratch folder and fed to the scene importer (`tlod info FILE`) and to the
glTF camera-path reader (`tlod play FILE --path gltf`, which reads the
cameras before the scene). Each check fails on a build without the
hardening: a crash, a hang (every run has a timeout), a file read from
outside the model's folder, an import that costs hundreds of megabytes (peak
RSS of the child, from wait4), or a wrong field silently read as 0.
Usage: hostile_test.py TLOD WORK_DIR"""
import base64, json, os, shutil, signal, struct, subprocess, sys, time, zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from tlod_cli import check, finish, init, one_error_line  # noqa: E402

TLOD, WORK = (os.path.abspath(a) for a in sys.argv[1:3])
init(TLOD)
shutil.rmtree(WORK, ignore_errors=True)
MODEL = os.path.join(WORK, "model")  # the model's folder; WORK itself is "outside"
os.makedirs(MODEL)
RSS_BOUND_MB = 200  # an import of a few-KB file must stay below this peak


def run_rss(args, timeout=60):
    """(rc, stderr, peak RSS in MB, seconds) of one run; rc None on a timeout (child killed).
    The child is polled with wait4 so that its own peak RSS is known."""
    t0 = time.time()
    p = subprocess.Popen([TLOD, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    deadline = t0 + timeout
    while True:
        pid, status, ru = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        if time.time() > deadline:
            os.killpg(p.pid, signal.SIGKILL)
            os.wait4(p.pid, 0)
            return None, "timed out", 0.0, time.time() - t0
        time.sleep(0.01)
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    rc = os.waitstatus_to_exitcode(status)
    return rc, err, ru.ru_maxrss / 1024.0, time.time() - t0


def info(path, timeout=30):
    return run_rss(["info", path], timeout)


def play(path, timeout=30):
    out = os.path.join(WORK, "runs", os.path.basename(path))
    return run_rss(["play", path, "--backend", "cpu", "--path", "gltf", "--frames", "2", "-q", "--out", out], timeout)


def refused(res, *words):
    """Exit 1 (never a signal or timeout), one error line containing every word."""
    rc, err, _, _ = res
    return rc == 1 and one_error_line(err) and all(w in err for w in words)


def detail(res):
    rc, err, rss, secs = res
    return "rc %s, %.0f MB, %.1f s: %s" % (rc, rss, secs, err.strip()[:600])


# ---- file makers ------------------------------------------------------------

TRI = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"  # 44 bytes


def data_uri(blob):
    return "data:application/octet-stream;base64," + base64.b64encode(blob).decode()


def triangle(buffer_uri=None, extra=None):
    """A one-triangle glTF (positions, u16 indices) with a camera on node 1."""
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
         "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
         "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                        "min": [0, 0, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
         "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
         "buffers": [{"byteLength": len(TRI), "uri": buffer_uri or data_uri(TRI)}]}
    if extra:
        extra(g)
    return g


def write_gltf(name, g, folder=MODEL):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        json.dump(g, f)
    return path


def write_text(name, text, folder=MODEL):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def glb(json_obj, bin_blob, bin_length_field=None):
    j = json.dumps(json_obj).encode()
    j += b" " * (-len(j) % 4)
    b = bin_blob + b"\0" * (-len(bin_blob) % 4)
    bl = len(b) if bin_length_field is None else bin_length_field
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", bl, 0x004E4942) + b
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


# ---- 1. the camera-path reader: the loader's guards apply to it too ---------

def huge_animation(g):
    # Rotation output: VEC4 float, count 2^62 + 1, stride 16. An unchecked
    # count x stride wraps to 0 ("fits"), count x 4 floats wraps to 4: the
    # copy loop then writes 2^62 elements into a 4-float vector.
    keys = struct.pack("<2f", 0, 1) + struct.pack("<8f", 0, 0, 0, 1, 0, 0, 0, 1)
    g["buffers"].append({"byteLength": len(keys), "uri": data_uri(keys)})
    g["bufferViews"] += [{"buffer": 1, "byteLength": 8}, {"buffer": 1, "byteOffset": 8, "byteLength": 32,
                                                           "byteStride": 16}]
    g["accessors"] += [{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                       {"bufferView": 3, "componentType": 5126, "count": 2 ** 62 + 1, "type": "VEC4"}]
    g["animations"] = [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}],
                        "samplers": [{"input": 2, "output": 3}]}]


res = play(write_gltf("huge_animation.gltf", triangle(extra=huge_animation)))
check("camera path: animation accessor with count 2^62+1 refused (no crash)",
      refused(res, "animation output", "runs past"), detail(res))

deep = write_gltf("deep_extras.gltf", triangle())
with open(deep) as f:
    text = f.read()
with open(deep, "w") as f:  # {"extras": [[[...]]]} 200000 deep on node 1
    f.write(text.replace('"camera": 0,', '"extras": ' + "[" * 200000 + "]" * 200000 + ', "camera": 0,', 1))
res = play(deep)
check("camera path: extras nested 200000 deep refused (no stack overflow)", refused(res, "nested deeper"),
      detail(res))

blob = TRI
g = triangle()
del g["buffers"][0]["uri"]
glb_path = os.path.join(MODEL, "overlong_bin.glb")
with open(glb_path, "wb") as f:  # BIN length field 8 past the file: tinygltf 2.7 misses the chunk header
    f.write(glb(g, blob, bin_length_field=len(blob) + 8))
res = play(glb_path)
# The camera reader runs first and names the file by the path it was given;
# the scene importer (which always checked GLB chunks) names it by its base name.
check("camera path: GLB whose BIN chunk runs past the file refused by the camera reader",
      refused(res, "BIN chunk", "runs past") and ("error: " + glb_path + ":") in res[1], detail(res))

# PNG bomb: a 16000x16000 grey image in 250 KB. Nothing uses images, so nothing decodes it.
# Compressed row by row: the test itself stays small (a child's ru_maxrss counts
# what it inherited from this process before exec).
z = zlib.compressobj(9)
row = b"\0" * (16000 + 1)
raw = b"".join(z.compress(row) for _ in range(16000)) + z.flush()
png = b"\x89PNG\r\n\x1a\n"
for tag, body in ((b"IHDR", struct.pack(">IIBBBBB", 16000, 16000, 8, 0, 0, 0, 0)), (b"IDAT", raw), (b"IEND", b"")):
    png += struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body))


def png_bomb(g):
    g["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]
    g["textures"] = [{"source": 0}]


bomb = write_gltf("png_bomb.gltf", triangle(extra=png_bomb))
res = play(bomb, timeout=60)
check("camera path and scene: an embedded PNG bomb is not decoded (peak RSS < %d MB)" % RSS_BOUND_MB,
      res[0] == 0 and res[2] < RSS_BOUND_MB, detail(res))

# ---- 2. external buffers stay inside the model's folder ---------------------

with open(os.path.join(WORK, "outside.bin"), "wb") as f:
    f.write(TRI)  # a valid triangle: read, it would import without complaint
with open(os.path.join(WORK, "outside_odd.bin"), "wb") as f:
    f.write(b"secret bytes, 31 of them......")
os.makedirs(os.path.join(MODEL, "a"))
os.symlink(os.path.join(WORK, "outside.bin"), os.path.join(MODEL, "link.bin"))
os.symlink(WORK, os.path.join(MODEL, "up"))
for uri in ("../outside.bin", "a/../../outside.bin", "./../outside.bin", "%2e%2e/outside.bin",
            "%2E%2E%2Foutside.bin", "a/%2e%2e/%2e%2e/outside.bin", "link.bin", "up/outside.bin",
            "../outside_odd.bin", "../no_such_file.bin"):
    name = "uri_%d.gltf" % len(os.listdir(MODEL))
    path = write_gltf(name, triangle(buffer_uri=uri))
    for what, res in (("scene", info(path)), ("camera path", play(path))):
        rc, err = res[0], res[1]
        tail = err.split("'" + uri + "'")[-1] if ("'" + uri + "'") in err else err
        # Named by its URI only: no size, no byte of the foreign file.
        ok = refused(res, uri, "outside the model's folder") and not any(c.isdigit() for c in tail) \
            and "secret" not in err
        check("%s: buffer uri '%s' refused (outside the model's folder), message without size or bytes" %
              (what, uri), ok, detail(res))

for what, uri in (("absolute", os.path.join(WORK, "outside.bin")), ("file: scheme", "file:///etc/passwd")):
    res = info(write_gltf("abs_%d.gltf" % len(os.listdir(MODEL)), triangle(buffer_uri=uri)))
    check("scene: %s buffer uri refused" % what, refused(res, "not a relative reference"), detail(res))

# ---- 3. no hangs: FIFOs and devices are not files ---------------------------

os.mkfifo(os.path.join(MODEL, "fifo.bin"))
fifo_gltf = write_gltf("fifo_buffer.gltf", triangle(buffer_uri="fifo.bin"))
for what, res in (("scene", info(fifo_gltf, timeout=20)), ("camera path", play(fifo_gltf, timeout=20))):
    check("%s: a FIFO as buffer uri refused promptly" % what,
          refused(res, "fifo.bin", "not a regular file") and res[3] < 10, detail(res))

OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
os.mkfifo(os.path.join(MODEL, "fifo.mtl"))
res = info(write_text("fifo_mtl.obj", "mtllib fifo.mtl\n" + OBJ), timeout=20)
check("OBJ: a FIFO as mtllib refused promptly", refused(res, "fifo.mtl", "not a regular file") and res[3] < 10,
      detail(res))
os.symlink("/dev/zero", os.path.join(MODEL, "zero.mtl"))
for mtl, why in (("/dev/zero", "not a relative reference"), ("zero.mtl", "outside the model's folder"),
                 ("../outside.mtl", "outside the model's folder")):
    write_text("outside.mtl", "newmtl red\nKd 1 0 0\n", folder=WORK)
    res = info(write_text("mtl_%d.obj" % len(os.listdir(MODEL)), "mtllib %s\nusemtl red\n%s" % (mtl, OBJ)))
    check("OBJ: mtllib %s refused (%s)" % (mtl, why), refused(res, "mtllib '%s'" % mtl, why), detail(res))
write_text("inside.mtl", "newmtl red\nKd 1 0 0\n")
res = info(write_text("mtl_inside.obj", "mtllib inside.mtl\nusemtl red\n" + OBJ))
check("OBJ: mtllib inside the folder still read", res[0] == 0, detail(res))

# ---- 4. memory amplification fails fast, within the budget ------------------


def zero_filled_instances(g):
    # POSITION: 2^20 elements without a bufferView (zeros), in 64 primitives:
    # ~6 GB of output from a 2 KB file.
    g["accessors"].append({"componentType": 5126, "count": 1 << 20, "type": "VEC3"})
    g["meshes"][0]["primitives"] = [{"attributes": {"POSITION": 2}} for _ in range(64)]


def empty_materials(g):
    g["materials"] = [{} for _ in range(100000)]  # 3 bytes of JSON, 2 KB of tinygltf::Material each


for name, maker, words in (("zero_filled_instances.gltf", zero_filled_instances, ("memory budget",)),
                           ("empty_materials.gltf", empty_materials, ("glTF model", "memory budget"))):
    path = write_gltf(name, triangle(extra=maker))
    res = info(path, timeout=120)
    check("scene: %s (%d KB) refused within the budget, peak RSS < %d MB" %
          (name, os.path.getsize(path) // 1024, RSS_BOUND_MB),
          refused(res, *words) and res[2] < RSS_BOUND_MB, detail(res))

# ---- 6. integer fields that are not non-negative integers are refused -------

for field, target in (("byteOffset", "accessors"), ("byteStride", "bufferViews")):
    for value in (-4, 1.5, "8"):
        def bad(g, field=field, target=target, value=value):
            g[target][0][field] = value
        res = info(write_gltf("bad_%s_%s.gltf" % (field, len(os.listdir(MODEL))), triangle(extra=bad)))
        check("scene: %s[0].%s = %s refused naming the field" % (target, field, json.dumps(value)),
              refused(res, "%s[0].%s: not a non-negative integer" % (target, field)), detail(res))


def bad_index(g):
    g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = -1


res = info(write_gltf("bad_attribute.gltf", triangle(extra=bad_index)))
check("scene: a negative attribute index refused naming it",
      refused(res, "meshes[0].primitives[0].attributes.POSITION: not a non-negative integer"), detail(res))

# ---- 7. OBJ exponents tinyobjloader would overflow --------------------------

res = info(write_text("exponent.obj", "v 0e2147483649 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"))
check("OBJ: exponent 2147483649 refused naming the line", refused(res, "line 1", "exponent out of range"),
      detail(res))
write_text("exponent.mtl", "newmtl red\nKd 1e-2147483649 0 0\n")
res = info(write_text("exponent_mtl.obj", "mtllib exponent.mtl\nusemtl red\n" + OBJ))
check("OBJ: exponent 2147483649 in a material file refused", refused(res, "exponent.mtl", "exponent out of range"),
      detail(res))
res = info(write_text("exponent_ok.obj", "v 1e-0005 0 0\nv 1E+1 0 0\nv 0 1.5e1 0\nf 1 2 3\n"))
check("OBJ: ordinary exponents still read", res[0] == 0, detail(res))

finish()
