#!/usr/bin/env python3
"""Builds the seed corpora of the fuzz targets (docs/fuzzing.md).

Usage: fuzz/seeds.py OUT_DIR   (fuzz/run calls it; OUT_DIR/<target>/ is rebuilt each time)

Seeds come from the repository only:
  - tests/data: every .gltf (external buffers inlined as base64 data URIs, so a seed is one
    self-contained file like a fuzz input; the original is kept too), .glb, .obj; the invalid
    corpora (glTF-Validator, obj_bad) are in there;
  - generated here: a GLB packed from each .gltf with one external buffer, PLY meshes in
    ascii and both binary byte orders, a glTF scene with an animated camera, PNGs of every
    colour type and depth with truncated and oversized variants (fuzz_image);
  - fuzz/seeds/<target>/: small hand-made files (valid and invalid) for each target;
  - tests/data/fuzz/<target>/: every crash found so far (not the open/ folder: those still
    crash and would stop a run at start).
fuzz_mesh's inputs are an option byte and a file (fuzz/fuzz_mesh.c): its seeds are the small
obj/ply/glb/gltf seeds and the small VTK seeds behind a few option bytes. fuzz_vtk's inputs are a format byte and a
file (fuzz/fuzz_vtk.c): the VTK files of tests/data and generated legacy files (ASCII and
binary) holding one cell of every type the importer reads, with point and cell data.
"""
import base64
import json
import pathlib
import shutil
import struct
import sys
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data"
TARGETS = ["fuzz_gltf", "fuzz_glb", "fuzz_obj", "fuzz_ply", "fuzz_mesh", "fuzz_camera_path", "fuzz_gltf_camera",
           "fuzz_image", "fuzz_run_trace", "fuzz_vtk"]
MAX_INLINE = 256 * 1024  # larger external buffers are left as they are
MESH_SEED_MAX = 16 * 1024  # fuzz_mesh: only small meshes (fuzz_mesh.c skips big ones)


def data_files(suffix):
    """Files under tests/data with this extension, fuzz reproducers excluded."""
    return sorted(p for p in DATA.rglob("*" + suffix) if p.is_file() and "fuzz" not in p.relative_to(DATA).parts)


def inline_buffers(path):
    """The glTF JSON with its external buffers as data URIs, and the list of their bytes;
    None when it is not JSON (an invalid seed, kept raw) or a buffer is missing."""
    try:
        doc = json.loads(path.read_text(encoding="utf-8-sig"))
        blobs = []
        for buf in doc.get("buffers", []):
            uri = buf.get("uri", "")
            if not uri or uri.startswith("data:"):
                blobs.append(None)
                continue
            blob = (path.parent / uri).read_bytes()
            if len(blob) > MAX_INLINE:
                return None
            blobs.append(blob)
            buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
        return doc, blobs
    except (ValueError, OSError, AttributeError, TypeError):
        return None


def glb(doc, bin_blob):
    """A GLB container: 12-byte header, JSON chunk (space-padded), optional BIN chunk."""
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    chunks = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_blob is not None:
        b = bin_blob + b"\0" * (-len(bin_blob) % 4)
        chunks += struct.pack("<II", len(b), 0x004E4942) + b
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def gltf_seeds(out):
    for p in data_files(".gltf"):
        name = p.relative_to(DATA).as_posix().replace("/", "_")
        shutil.copy(p, out["fuzz_gltf"] / name)
        inlined = inline_buffers(p)
        if not inlined:
            continue
        doc, blobs = inlined
        (out["fuzz_gltf"] / ("inline_" + name)).write_text(json.dumps(doc))
        if len(blobs) == 1 and blobs[0] is not None:
            packed = json.loads(json.dumps(doc))
            del packed["buffers"][0]["uri"]
            (out["fuzz_glb"] / (name[:-5] + ".glb")).write_bytes(glb(packed, blobs[0]))
        if "cameras" in doc:
            (out["fuzz_gltf_camera"] / ("inline_" + name)).write_text(json.dumps(doc))
    for p in data_files(".glb"):
        shutil.copy(p, out["fuzz_glb"] / p.relative_to(DATA).as_posix().replace("/", "_"))
        if b'"cameras"' in p.read_bytes()[:65536]:
            shutil.copy(p, out["fuzz_gltf_camera"] / p.name)


CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_F = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5, 1)]


def ply(fmt, normals):
    """The unit cube (last face a degenerate pentagon) as PLY in fmt."""
    props = ["x", "y", "z"] + (["nx", "ny", "nz"] if normals else [])
    head = ["ply", "format %s 1.0" % fmt, "element vertex %d" % len(CUBE_V)]
    head += ["property float %s" % p for p in props]
    head += ["element face %d" % len(CUBE_F), "property list uchar int vertex_indices", "end_header"]
    text = ("\n".join(head) + "\n").encode()
    rows = [v + ((0.0, 0.0, 1.0) if normals else ()) for v in CUBE_V]
    if fmt == "ascii":
        body = "".join(" ".join("%g" % c for c in r) + "\n" for r in rows)
        body += "".join(" ".join(str(i) for i in (len(f),) + f) + "\n" for f in CUBE_F)
        return text + body.encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(e + "%df" % len(r), *r) for r in rows)
    body += b"".join(struct.pack(e + "B%di" % len(f), len(f), *f) for f in CUBE_F)
    return text + body


def ply_seeds(out):
    for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
        for normals in (False, True):
            (out["fuzz_ply"] / ("cube_%s%s.ply" % (fmt, "_n" if normals else ""))).write_bytes(ply(fmt, normals))


def camera_scene():
    """A glTF scene: a triangle and camera 0 on a node moved by a translation and a rotation
    channel (one embedded buffer)."""
    times = struct.pack("<3f", 0.0, 1.0, 2.0)
    moves = struct.pack("<9f", 0, 1, 5, 3, 1, 4, 0, 2, 3)
    turns = struct.pack("<12f", 0, 0, 0, 1, 0, 0.3826834, 0, 0.9238795, 0, 0.7071068, 0, 0.7071068)
    blob = times + moves + turns
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12}, {"buffer": 0, "byteOffset": 12, "byteLength": 36},
             {"buffer": 0, "byteOffset": 48, "byteLength": 48}]
    acc = [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
           {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
           {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}]
    return {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "rig", "translation": [0, 0.5, 0], "children": [2]}, {"name": "still", "camera": 1},
                  {"name": "cam", "camera": 0}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100}},
                    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
        "animations": [{"samplers": [{"input": 0, "output": 1}, {"input": 0, "output": 2, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}},
                                     {"sampler": 1, "target": {"node": 2, "path": "rotation"}}]}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(blob).decode()}],
        "bufferViews": views, "accessors": acc,
    }, blob


def camera_seeds(out):
    doc, blob = camera_scene()
    (out["fuzz_gltf_camera"] / "animated_camera.gltf").write_text(json.dumps(doc, indent=1))
    packed = json.loads(json.dumps(doc))
    del packed["buffers"][0]["uri"]
    (out["fuzz_gltf_camera"] / "animated_camera.glb").write_bytes(glb(packed, blob))
    still = {k: v for k, v in doc.items() if k not in ("animations", "buffers", "bufferViews", "accessors")}
    (out["fuzz_gltf_camera"] / "still_camera.gltf").write_text(json.dumps(still))


def run_trace_seeds(out):
    """fuzz_run_trace: a trace.json of two frames, cut at several points, and a wrong schema."""
    frame = {"frame": 0, "time_s": 0, "eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fovy": 45,
             "near": 0.1, "far": 100, "frame_ms": 2.5, "anim_ms": 0, "scheduler_ms": 0.5,
             "stage_ms": {"silhouette": 0.1, "metric": 0.1, "levels": 0.1, "morph": 0.1, "strips": 0.1},
             "backend_cpu_ms": 1, "backend_gpu_ms": -1, "backend_wall_ms": 1.5, "screenshot_ms": 0,
             "screenshot": "screenshots/frame_00000.png", "patches": 8, "visible": 6, "culled": 2, "strips": 3,
             "pattern_triangles": 10, "strip_triangles": 4, "triangles": 14, "drawn_triangles": 14,
             "draw_calls": 0, "effective_epsilon": 1, "level_histogram": [1, 2, 3] + [0] * 8,
             "objects": [{"name": "o\u00e9", "patches": 8}]}
    doc = {"schema": "tlod-play-trace/2", "tool": "tlod 1.0.0", "scene": "demo:scene", "mode": "adaptive",
           "backend": "cpu", "objects": [{"name": "a", "source": "demo:cube", "vertices": 8, "faces": 6,
                                          "patches": 12}],
           "frames": [frame, dict(frame, frame=1, screenshot="", backend_gpu_ms=None)],
           "frames_completed": 2, "stopped": "completed", "wall_s": 0.01}
    text = json.dumps(doc)
    d = out["fuzz_run_trace"]
    (d / "trace.json").write_text(text)
    for cut in (len(text) // 3, len(text) // 2, len(text) - 40):
        (d / ("cut_%d.json" % cut)).write_text(text[:cut])
    (d / "schema1.json").write_text(json.dumps(dict(doc, schema="tlod-play-trace/1")))


def mesh_seeds(out):
    """fuzz_mesh: option byte (format in bits 0-1) + file."""
    sources = [(0, out["fuzz_obj"]), (1, out["fuzz_ply"]), (2, out["fuzz_glb"]), (3, out["fuzz_gltf"])]
    options = (0x04, 0x08, 0x20, 0x0C | 0x40 | 0x80, 0x34, 0x00)  # two a file, in turn
    n = 0
    for fmt, folder in sources:
        for p in sorted(folder.iterdir()):
            body = p.read_bytes()
            if len(body) > MESH_SEED_MAX:
                continue
            for opt in (options[n % 6], options[(n + 3) % 6]):
                (out["fuzz_mesh"] / ("%02x_%s" % (opt | fmt, p.name))).write_bytes(bytes([opt | fmt]) + body)
            n += 1
    # VTK files go in as they are (fuzz_mesh.c reads them as VTK by their first bytes), so the
    # second-order cells' face_nodes reach core; bits 2-3 = 2/3 pick QUADRATIC surfaces.
    for p in sorted(out["fuzz_vtk"].iterdir()):
        body = p.read_bytes()[1:]
        if len(body) > MESH_SEED_MAX or not (body.startswith(b"# vtk DataFile") or body.startswith(b"<?xml")):
            continue
        for opt in (0x08, 0x0C | 0x40, 0x04 | 0x80):
            (out["fuzz_mesh"] / ("%02x_vtk_%s" % (opt, p.name))).write_bytes(bytes([opt]) + body)


VTK_EXT = {".vtk": 0, ".vtu": 1, ".vtp": 2, ".stl": 3, ".pvd": 6, ".pvtu": 7}  # fuzz/fuzz_vtk.c's format byte


def vtk_cells():
    """One cell of every type the importer reads: (VTK type, corner points, node count); the
    nodes past the corners sit at the centre of the cell's corners (not exact, fine for fuzzing)."""
    hexc = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    tet = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    wedge = [(0, 0, 0), (0, 1, 0), (1, 0, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1)]
    pyr = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
    quad = hexc[:4]
    return [(10, tet, 4), (12, hexc, 8), (11, hexc, 8), (13, wedge, 6), (14, pyr, 5), (24, tet, 10), (25, hexc, 20),
            (29, hexc, 27), (33, hexc, 24), (26, wedge, 15), (32, wedge, 18), (31, wedge, 12), (27, pyr, 13),
            (5, quad[:3], 3), (9, quad, 4), (8, quad, 4), (22, quad[:3], 6), (23, quad, 8), (28, quad, 9), (30, quad, 6),
            (7, quad + [(0.5, -0.5, 0)], 5), (6, quad, 4), (3, quad[:2], 2), (1, quad[:1], 1)]


def vtk_legacy(binary):
    """Every cell of vtk_cells() (shifted apart) as a legacy 3.0 unstructured grid."""
    pts, cells, types = [], [], []
    for i, (t, corners, n) in enumerate(vtk_cells()):
        base = len(pts)
        c = [sum(p[k] for p in corners) / len(corners) for k in range(3)]
        pts += [(x + 2 * i, y, z) for x, y, z in corners] + [(c[0] + 2 * i, c[1], c[2])] * (n - len(corners))
        cells.append([n] + list(range(base, base + n)))
        types.append(t)
    size = sum(len(c) for c in cells)
    head = "# vtk DataFile Version 3.0\nall cells\n%s\nDATASET UNSTRUCTURED_GRID\n" % ("BINARY" if binary else "ASCII")
    if not binary:
        body = "POINTS %d float\n" % len(pts) + "".join("%g %g %g\n" % p for p in pts)
        body += "CELLS %d %d\n" % (len(cells), size) + "".join(" ".join(map(str, c)) + "\n" for c in cells)
        body += "CELL_TYPES %d\n" % len(types) + "".join("%d\n" % t for t in types)
        body += "POINT_DATA %d\nSCALARS temperature float 1\nLOOKUP_TABLE default\n" % len(pts)
        body += "".join("%d\n" % i for i in range(len(pts)))
        body += "VECTORS velocity float\n" + "".join("%d 1 0\n" % i for i in range(len(pts)))
        body += "CELL_DATA %d\nFIELD f 1\nstress 2 %d double\n" % (len(types), len(types))
        body += "".join("%d 0.5\n" % i for i in range(len(types)))
        return (head + body).encode()
    out = (head + "POINTS %d float\n" % len(pts)).encode() + b"".join(struct.pack(">3f", *p) for p in pts)
    out += ("\nCELLS %d %d\n" % (len(cells), size)).encode() + b"".join(struct.pack(">%di" % len(c), *c) for c in cells)
    out += ("\nCELL_TYPES %d\n" % len(types)).encode() + struct.pack(">%di" % len(types), *types)
    out += ("\nPOINT_DATA %d\nSCALARS temperature float 1\nLOOKUP_TABLE default\n" % len(pts)).encode()
    return out + struct.pack(">%df" % len(pts), *range(len(pts))) + b"\n"


def vtk_seeds(out):
    d = out["fuzz_vtk"]
    for suffix, code in VTK_EXT.items():
        for p in data_files(suffix):
            (d / p.relative_to(DATA).as_posix().replace("/", "_")).write_bytes(bytes([code]) + p.read_bytes())
    for binary in (False, True):
        (d / ("all_cells_%s.vtk" % ("binary" if binary else "ascii"))).write_bytes(bytes([0]) + vtk_legacy(binary))
    pvd = b'<?xml version="1.0"?><VTKFile type="Collection"><Collection><DataSet timestep="0" file="input.vtu"/>'
    (d / "self.pvd").write_bytes(bytes([6]) + pvd + b"</Collection></VTKFile>\n")
    pvtu = b'<?xml version="1.0"?><VTKFile type="PUnstructuredGrid"><PUnstructuredGrid><Piece Source="input.pvtu"/>'
    (d / "self.pvtu").write_bytes(bytes([7]) + pvtu + b"</PUnstructuredGrid></VTKFile>\n")


def png(width, height, color_type, depth, rows=None, interlace=0, extra=b""):
    """A PNG of this colour type and bit depth; rows: raw scanline bytes (filter byte added)."""
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[color_type]
    row_bytes = (width * channels * depth + 7) // 8
    if rows is None:
        rows = [bytes((x * 37 + y * 11) & 0xFF for x in range(row_bytes)) for y in range(height)]

    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)

    raw = b"".join(b"\0" + r for r in rows)
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color_type, 0, 0, interlace)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + extra + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def image_seeds(out):
    """fuzz_image: the images of tests/data, a PNG per colour type and depth (palette with
    tRNS, Adam7), truncated copies, and headers that claim more pixels than the limit."""
    d = out["fuzz_image"]
    for suffix in (".png", ".jpg", ".jpeg"):
        for p in data_files(suffix):
            if p.stat().st_size <= 32768:
                shutil.copy(p, d / p.relative_to(DATA).as_posix().replace("/", "_"))
    for ct, depths in ((0, (1, 2, 4, 8, 16)), (2, (8, 16)), (3, (1, 4, 8)), (4, (8, 16)), (6, (8, 16))):
        for depth in depths:
            extra = b""
            if ct == 3:
                pal = bytes(range(48)) * 16
                plte = pal[: 3 * (1 << depth)]
                extra = struct.pack(">I", len(plte)) + b"PLTE" + plte + struct.pack(">I", zlib.crc32(b"PLTE" + plte))
                trns = bytes([0, 128])
                extra += struct.pack(">I", 2) + b"tRNS" + trns + struct.pack(">I", zlib.crc32(b"tRNS" + trns))
            (d / ("ct%d_d%d.png" % (ct, depth))).write_bytes(png(7, 5, ct, depth, extra=extra))
    # Adam7: the seven passes' scanlines one after the other (RGBA8, 9 x 9).
    passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
    rows = []
    for x0, y0, dx, dy in passes:
        cols, nrows = max(0, (9 - x0 + dx - 1) // dx), max(0, (9 - y0 + dy - 1) // dy)
        if cols:
            rows += [bytes((i * 7 + y) & 0xFF for i in range(4 * cols)) for y in range(nrows)]
    (d / "adam7.png").write_bytes(png(9, 9, 6, 8, rows=rows, interlace=1))
    whole = png(16, 16, 6, 8)
    (d / "truncated.png").write_bytes(whole[: len(whole) // 2])
    (d / "huge_header.png").write_bytes(png(65536, 65536, 0, 8, rows=[b""]))  # 2^32 pixels claimed
    for p in sorted((ROOT / "fuzz" / "seeds" / "fuzz_image").glob("*.jpg")):
        blob = p.read_bytes()
        (d / ("truncated_" + p.name)).write_bytes(blob[: len(blob) * 2 // 3])


def copy_dir(src, dst):
    if src.is_dir():
        for p in sorted(src.iterdir()):
            if p.is_file():
                shutil.copy(p, dst / p.name)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    base = pathlib.Path(sys.argv[1])
    out = {t: base / t for t in TARGETS}
    for d in out.values():
        shutil.rmtree(d, ignore_errors=True)
        d.mkdir(parents=True)
    for p in data_files(".obj"):
        shutil.copy(p, out["fuzz_obj"] / p.relative_to(DATA).as_posix().replace("/", "_"))
    gltf_seeds(out)
    ply_seeds(out)
    camera_seeds(out)
    image_seeds(out)
    run_trace_seeds(out)
    vtk_seeds(out)
    for t in TARGETS:
        copy_dir(ROOT / "fuzz" / "seeds" / t, out[t])
    mesh_seeds(out)
    for t in TARGETS:
        copy_dir(DATA / "fuzz" / t, out[t])
    for t in TARGETS:
        print("seeds: %-18s %4d files" % (t, len(list(out[t].iterdir()))))


if __name__ == "__main__":
    main()
