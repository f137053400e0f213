"""A small glTF 2.0 writer for the CLI tests (play_scene_test.py, play_vulkan_test.py): buffers embedded as data URIs,
accessors with min/max, meshes, materials, nodes, and the shapes and camera files the tests draw."""
import base64, json, math, struct, zlib


class Gltf:
    def __init__(self):
        self.blob, self.views, self.accessors = b"", [], []
        self.g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                  "materials": []}

    def accessor(self, fmt, values, kind, ctype=5126, minmax=None):
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        self.blob += b"\0" * (-len(self.blob) % 4)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
        self.blob += data
        n = len(values) // {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[kind]
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": n, "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def mesh(self, pos, nrm, idx, material=None, uv=None):
        lo = [min(pos[i::3]) for i in range(3)]
        hi = [max(pos[i::3]) for i in range(3)]
        attrs = {"POSITION": self.accessor("f", pos, "VEC3", minmax=(lo, hi)), "NORMAL": self.accessor("f", nrm, "VEC3")}
        if uv:
            attrs["TEXCOORD_0"] = self.accessor("f", uv, "VEC2")
        prim = {"attributes": attrs, "indices": self.accessor("H", idx, "SCALAR", ctype=5123)}
        if material is not None:
            prim["material"] = material
        self.g["meshes"].append({"primitives": [prim]})
        return len(self.g["meshes"]) - 1

    def material(self, rgba, texture=None):
        pbr = {"baseColorFactor": list(rgba), "metallicFactor": 0}
        if texture is not None:
            pbr["baseColorTexture"] = {"index": texture}
        self.g["materials"].append({"pbrMetallicRoughness": pbr})
        return len(self.g["materials"]) - 1

    def node(self, root=True, **kw):
        self.g["nodes"].append(kw)
        if root:
            self.g["scenes"][0]["nodes"].append(len(self.g["nodes"]) - 1)
        return len(self.g["nodes"]) - 1

    def save(self, path):
        self.g["accessors"], self.g["bufferViews"] = self.accessors, self.views
        self.g["buffers"] = [{"byteLength": len(self.blob),
                              "uri": "data:application/octet-stream;base64," + base64.b64encode(self.blob).decode()}]
        with open(path, "w") as f:
            json.dump(self.g, f)


def cube(half):
    """24 vertices (flat normals), 36 indices, counter-clockwise seen from outside."""
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = [0, 0, 0], [0, 0, 0]
            u[(axis + 1) % 3], v[(axis + 2) % 3] = 1, sign
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos += [half * (n[k] + a * u[k] + b * v[k]) for k in range(3)]
                nrm += n
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def png_bytes(w, h, rgba_rows):
    raw = b"".join(b"\0" + bytes(r) for r in rgba_rows)
    def chunk(t, c):
        return struct.pack(">I", len(c)) + t + c + struct.pack(">I", zlib.crc32(t + c))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def camera_file(path, eye, target, fovy):
    with open(path, "w") as f:
        json.dump({"keyframes": [{"time": 0, "eye": eye, "target": target, "fovy": fovy},
                                 {"time": 10, "eye": eye, "target": target, "fovy": fovy}]}, f)


def sphere(r, nlat=8, nlon=12):
    """A UV sphere with smooth normals, counter-clockwise seen from outside."""
    pos, nrm, idx = [], [], []
    for i in range(nlat + 1):
        th = math.pi * i / nlat
        for j in range(nlon + 1):
            ph = 2 * math.pi * j / nlon
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            pos += [r * c for c in n]
            nrm += n
    for i in range(nlat):
        for j in range(nlon):
            a, b = i * (nlon + 1) + j, (i + 1) * (nlon + 1) + j
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, idx
