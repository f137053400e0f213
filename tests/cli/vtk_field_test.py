#!/usr/bin/env python3
"""tlod with VTK input (issue 14): a rendered result field, its legend, the field in summary.json, `tlod info` of
volume meshes, `--surface auto` and the field options' errors.

Usage: vtk_field_test.py TLOD DATA_DIR WORK_DIR gl|nogl vtk|novtk [vk|novk]

Every mesh is written here (small XML .vtu files), so the counts are known by construction. The colour checks use
the test's own copy of published colour-map values (matplotlib's viridis at 0, 1/4, 1/2, 3/4, 1; Moreland's cool-warm
ends and centre) times the built-in material's lighting (tesslod/backend.h), never the tool's table.

"novtk": the build has TLOD_WITH_VTK off: only the refusal naming VTK is checked. "nogl": the rendered checks are
left out for that reason alone (never a skip of a build that has GL)."""
import math, os, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_read import png_rows
from tlod_cli import check, finish, load_json, one_error_line, run, setup

TLOD, DATA, WORK, HAS_GL = setup(sys.argv)
HAS_VTK = (sys.argv[5] if len(sys.argv) > 5 else "vtk") == "vtk"
HAS_VK = (sys.argv[6] if len(sys.argv) > 6 else "novk") == "vk"

# matplotlib's viridis (_cm_listed.py: entries 0, 64, 128, 192, 255), as 8-bit sRGB.
VIRIDIS = {0.0: "440154", 0.25: "3b528b", 0.5: "21918c", 0.75: "5ec962", 1.0: "fde725"}
# K. Moreland, "Diverging Color Maps for Scientific Visualization" (2009), table of the cool-warm map.
COOL_WARM = {0.0: (59, 76, 192), 0.5: (221, 221, 221), 1.0: (180, 4, 38)}


def rgb(hexv):
    return tuple(int(hexv[i:i + 2], 16) for i in (0, 2, 4))


def lambert(normal):
    """The built-in material's light factor: 0.15 + 0.85 max(n.l, 0), default light (0.3, 0.8, 0.5) normalised."""
    l = (0.3, 0.8, 0.5)
    n = math.sqrt(sum(c * c for c in l))
    return 0.15 + 0.85 * max(sum(a * b for a, b in zip(normal, l)) / n, 0.0)


# ---- VTK files written by the test ----------------------------------------------------------------------------------

def vtu(path, points, cells, point_data=(), cell_data=()):
    """An ASCII .vtu: points [(x, y, z)], cells [(vtk_type, [ids])], point/cell data [(name, components, values)]."""
    def arrays(items):
        out = ""
        for name, comps, values in items:
            out += ('<DataArray type="Float32" Name="%s" NumberOfComponents="%d" format="ascii">%s</DataArray>\n'
                    % (name, comps, " ".join("%.9g" % v for v in values)))
        return out
    conn = " ".join(str(i) for _, ids in cells for i in ids)
    offsets, o = [], 0
    for _, ids in cells:
        o += len(ids)
        offsets.append(str(o))
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
                '<UnstructuredGrid><Piece NumberOfPoints="%d" NumberOfCells="%d">\n' % (len(points), len(cells)))
        f.write('<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">%s</DataArray></Points>\n'
                % " ".join("%.9g" % c for p in points for c in p))
        f.write('<Cells><DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>\n'
                '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray>\n'
                '<DataArray type="UInt8" Name="types" format="ascii">%s</DataArray></Cells>\n'
                % (conn, " ".join(offsets), " ".join(str(t) for t, _ in cells)))
        f.write("<PointData>\n%s</PointData>\n<CellData>\n%s</CellData>\n" % (arrays(point_data), arrays(cell_data)))
        f.write("</Piece></UnstructuredGrid></VTKFile>\n")
    return path


def flat_quad(path):
    """One quad (VTK_QUAD) x, y in [-1, 1] at z = 0 facing +z; temperature [K] = x, velocity = (x + 1, 2, 0)."""
    pts = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    return vtu(path, pts, [(9, [0, 1, 2, 3])],
               point_data=[("temperature [K]", 1, [p[0] for p in pts]),
                           ("velocity", 3, [c for p in pts for c in (p[0] + 1.0, 2.0, 0.0)])])


def hex_pair(path):
    """Two unit hexahedra side by side (x in [0, 2]): 12 points, 10 boundary quads, 1 interior face."""
    def p(x, y, z):
        return x + 3 * y + 6 * z
    pts = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1, 2)]
    cells = [(12, [p(i, 0, 0), p(i + 1, 0, 0), p(i + 1, 1, 0), p(i, 1, 0),
                   p(i, 0, 1), p(i + 1, 0, 1), p(i + 1, 1, 1), p(i, 1, 1)]) for i in (0, 1)]
    return vtu(path, pts, cells, point_data=[("height", 1, [q[2] for q in pts])],
               cell_data=[("pressure", 1, [1.0, 3.0])])


def quadratic_hex(path):
    """One 20-node hexahedron (VTK_QUADRATIC_HEXAHEDRON, type 25) of the unit cube: 6 second-order boundary quads."""
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    mids = [tuple((corners[a][k] + corners[b][k]) / 2 for k in range(3)) for a, b in edges]
    mids[4] = (0.5, 0.0, 1.15)  # the top face bulges: a curved face
    return vtu(path, corners + mids, [(25, list(range(20)))])


# ---- rendered field ---------------------------------------------------------------------------------------------------

SIZE = 256
EYE_Z = 3.0
FOCAL = 1.0 / math.tan(math.radians(22.5))  # fovy 45 (the keyframe default)
BACKGROUND = (28, 31, 36)  # tlod play's clear colour (0.11, 0.12, 0.14)
ROW = 215  # below the legend (its box ends at row 3 H / 4 + 4)


def camera_path(path):
    with open(path, "w") as f:
        f.write('{"keyframes": [{"time": 0, "eye": [0, 0, %g], "target": [0, 0, 0]},'
                ' {"time": 1, "eye": [0, 0, %g], "target": [0, 0, 0]}]}\n' % (EYE_Z, EYE_Z))
    return path


def column_of(x):
    """The pixel column showing world x on the quad (z = 0) for the camera on the +z axis."""
    return int((x * FOCAL / EYE_Z + 1.0) / 2.0 * SIZE)


def play_shot(name, mesh, backend, *extra):
    out = os.path.join(WORK, name)
    rc, so, se = run("play", mesh, "--backend", backend, "--path", camera_path(os.path.join(WORK, "path.json")),
                     "--frames", "1", "--size", "%dx%d" % (SIZE, SIZE), "--screenshot-every", "1", "--out", out,
                     "-q", *(["--shader-cache", os.path.join(WORK, "shaders")] if backend == "vulkan" else []), *extra,
                     timeout=120)
    check(name + ": plays", rc == 0, se)
    shot = os.path.join(out, "screenshots", "frame_00000.png")
    return (png_rows(shot) if os.path.exists(shot) else None), load_json(os.path.join(out, "summary.json"))


def pixel(img, x, y):
    w, h, bpp, _, rows = img
    return tuple(rows[y][x * bpp:x * bpp + 3])


def near(a, b, tol):
    return all(abs(p - q) <= tol for p, q in zip(a, b))


def check_field_pixels(name, img, expected):
    """expected: [(world x, rgb before lighting)]; each pixel at (column_of(x), ROW) within 3 of it lit."""
    lit = lambert((0.0, 0.0, 1.0))
    for x, colour in expected:
        want = tuple(round(c * lit) for c in colour)
        got = pixel(img, column_of(x), ROW)
        check("%s: pixel at x = %g is %s (lit %s)" % (name, x, want, colour), near(got, want, 3), got)


def legend_geometry(w, h):
    """The bar of tools/tlod/field/field_legend.h: (x0, x1, y0, y1), columns [x0, x1), rows [y0, y1)."""
    s = max(1, h // 360)
    x1 = w - 12 * s
    return x1 - 12 * s, x1, h // 4, h // 4 + h // 2, s


def check_legend(name, img, ends):
    """The colour bar holds the unlit map (top: the maximum), white text above it and beside it."""
    w, h = img[0], img[1]
    x0, x1, y0, y1, s = legend_geometry(w, h)
    xc = (x0 + x1) // 2
    for t, colour in ends:
        y = round(y1 - 1 - t * (y1 - y0 - 1))
        check("%s: legend bar at t = %g is %s" % (name, t, colour), near(pixel(img, xc, y), colour, 2),
              pixel(img, xc, y))
    above = [pixel(img, x, y) for y in range(y0 - 4 * s - 7 * s, y0 - 4 * s) for x in range(x0 - 120, x1)]
    beside = [pixel(img, x, y) for y in range(y0, y0 + 7 * s) for x in range(x0 - 60, x0)]
    check(name + ": legend has its name above the bar (white text)", above.count((255, 255, 255)) > 20)
    check(name + ": legend has the maximum beside the bar", beside.count((255, 255, 255)) > 5)


def rendered(backend):
    quad = flat_quad(os.path.join(WORK, "quad.vtu"))
    tag = backend
    # --range -0.5,0.5 on temperature = x: x = -0.75 clamps to 0, x = 0.75 to 1, the rest in between.
    img, summary = play_shot(tag + "-viridis", quad, backend, "--field", "temperature", "--range", "-0.5,0.5")
    if img:
        check_field_pixels(tag + " viridis", img, [(-0.75, rgb(VIRIDIS[0.0])), (-0.25, rgb(VIRIDIS[0.25])),
                                                   (0.0, rgb(VIRIDIS[0.5])), (0.25, rgb(VIRIDIS[0.75])),
                                                   (0.75, rgb(VIRIDIS[1.0]))])
        check_legend(tag + " viridis", img, [(t, rgb(VIRIDIS[t])) for t in (0.0, 1.0)])
    f = summary.get("field", {}) if isinstance(summary, dict) else {}
    check(tag + ": summary.json describes the field",
          f.get("name") == "temperature" and f.get("units") == "K" and f.get("min") == -0.5 and f.get("max") == 0.5
          and f.get("colormap") == "viridis" and f.get("from_cells") is False, summary)
    check(tag + ": a linear VTK mesh plays phong under --surface auto",
          isinstance(summary, dict) and summary.get("surface") == "phong", summary)
    page = os.path.join(WORK, tag + "-page.html")
    rc, so, se = run("dashboard", os.path.join(WORK, tag + "-viridis"), "-o", page)
    html = open(page).read() if rc == 0 and os.path.exists(page) else ""
    check(tag + ": the dashboard shows the field", "temperature [K] -0.5..0.5 viridis" in html, se)
    if backend != "gl":
        return
    # The default range is the field's (x in [-1, 1]); the diverging map's centre is its neutral grey.
    img, summary = play_shot("gl-diverging", quad, backend, "--field", "temperature", "--colormap", "diverging")
    if img:
        check_field_pixels("gl diverging", img, [(0.0, COOL_WARM[0.5])])
        check_legend("gl diverging", img, [(0.0, COOL_WARM[0.0]), (1.0, COOL_WARM[1.0])])
    f = summary.get("field", {}) if isinstance(summary, dict) else {}
    check("default --range is the field's range", f.get("min") == -1.0 and f.get("max") == 1.0, f)
    # A vector's magnitude at the corners: |(x + 1, 2, 0)| is 2 (x = -1) and sqrt(8) (x = 1); component y is 2
    # everywhere (the map's middle with --range 0,4).
    _, summary = play_shot("gl-magnitude", quad, backend, "--field", "velocity")
    f = summary.get("field", {}) if isinstance(summary, dict) else {}
    check("a vector field defaults to its magnitude",
          f.get("component") == "magnitude" and abs(f.get("min", 0) - 2.0) < 1e-5
          and abs(f.get("max", 0) - math.sqrt(8)) < 1e-5, f)
    img, _ = play_shot("gl-component", quad, backend, "--field", "velocity:y", "--range", "0,4")
    if img:
        check_field_pixels("gl velocity:y", img, [(-0.5, rgb(VIRIDIS[0.5])), (0.5, rgb(VIRIDIS[0.5]))])


def series():
    """A .pvd of 3 steps (times 0, 1, 2 s): step k moves the quad up by 0.2 k and adds k to temperature. Played at
    1 fps, frame k shows step k: the pixel at x = 0 inside the quad is viridis((k + 1) / 4) with --range -1,3."""
    names = []
    for k in range(3):
        pts = [(-1, -1 + 0.2 * k, 0), (1, -1 + 0.2 * k, 0), (1, 1 + 0.2 * k, 0), (-1, 1 + 0.2 * k, 0)]
        names.append(vtu(os.path.join(WORK, "step_%d.vtu" % k), pts, [(9, [0, 1, 2, 3])],
                         point_data=[("temperature", 1, [p[0] + k for p in pts])]))
    pvd = os.path.join(WORK, "series.pvd")
    with open(pvd, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1"><Collection>\n')
        for k, n in enumerate(names):
            f.write('<DataSet timestep="%d" part="0" file="%s"/>\n' % (k, os.path.basename(n)))
        f.write("</Collection></VTKFile>\n")
    out = os.path.join(WORK, "series-run")
    rc, so, se = run("play", pvd, "--path", camera_path(os.path.join(WORK, "path.json")), "--frames", "3", "--fps",
                     "1", "--size", "%dx%d" % (SIZE, SIZE), "--screenshot-every", "1", "--out", out, "-q",
                     "--field", "temperature", "--range", "-1,3", timeout=120)
    check("series: plays", rc == 0, se)
    lit = lambert((0.0, 0.0, 1.0))
    for k, t in enumerate((0.25, 0.5, 0.75)):
        shot = os.path.join(out, "screenshots", "frame_%05d.png" % k)
        if not os.path.exists(shot):
            check("series: frame %d written" % k, False)
            continue
        img = png_rows(shot)
        want = tuple(round(c * lit) for c in rgb(VIRIDIS[t]))
        got = pixel(img, column_of(0.0), 100)
        check("series: frame %d shows step %d's field (%s)" % (k, k, want), near(got, want, 3), got)
        # The quad's top edge y = 1 + 0.2 k (frames 0, 1; frame 2's is above the image): background just above it.
        top = (1.0 - (1.0 + 0.2 * k) * FOCAL / EYE_Z) / 2.0 * SIZE
        if top > 3:
            x = column_of(-0.9)
            check("series: frame %d's quad top is at row %.1f (step %d's positions)" % (k, top, k),
                  pixel(img, x, math.floor(top) - 2) == BACKGROUND and pixel(img, x, math.ceil(top) + 1) != BACKGROUND,
                  (pixel(img, x, math.floor(top) - 2), pixel(img, x, math.ceil(top) + 1)))
    s = load_json(os.path.join(out, "summary.json"))
    check("series: summary.json counts its steps", isinstance(s, dict) and s.get("field", {}).get("steps") == 3, s)


# ---- errors, info, auto --------------------------------------------------------------------------------------------

def errors():
    quad = flat_quad(os.path.join(WORK, "quad.vtu"))
    cases = [
        ("unknown --field", ["--field", "nosuch"], ["nosuch", "temperature", "velocity"]),
        ("--field component out of range", ["--field", "velocity:3"], ["velocity", "3 components"]),
        ("--range MIN >= MAX", ["--field", "temperature", "--range", "1,0"], ["MIN must be below MAX"]),
        ("--range not numbers", ["--field", "temperature", "--range", "a,b"], ["--range", "a,b"]),
        ("--range one number", ["--field", "temperature", "--range", "3"], ["expected MIN,MAX"]),
        ("--range without --field", ["--range", "0,1"], ["needs --field"]),
        ("--colormap unknown", ["--field", "temperature", "--colormap", "jet"], ["viridis|diverging"]),
    ]
    for name, args, words in cases:
        rc, so, se = run("play", quad, "--backend", "null", "--frames", "1", "--out",
                         os.path.join(WORK, "err"), "-q", *args)
        check(name + ": one error line naming it", rc != 0 and one_error_line(se) and all(w in se for w in words),
              (rc, se))
    check("no run folder after refused options", not os.path.exists(os.path.join(WORK, "err")))


def number_after(text, pattern):
    m = re.search(pattern, text)
    return int(m.group(1)) if m else None


def info():
    rc, so, se = run("info", hex_pair(os.path.join(WORK, "hex2.vtu")))
    check("info hex pair: runs", rc == 0, se)
    check("info hex pair: 12 points, 2 cells, 2 hexahedra",
          re.search(r"vtk:\s+12 points, 2 cells: 2 \w+", so) is not None, so)
    check("info hex pair: 10 boundary quads, no triangles, 1 interior face dropped",
          re.search(r"boundary:\s+0 triangles, 10 quads .*1 interior faces? dropped", so) is not None, so)
    check("info hex pair: 10 quad patches", re.search(r"patches:\s+0 triangles, 10 quads", so) is not None, so)
    check("info hex pair: the point field and its range",
          re.search(r"height: 1 component, point data, range \[0, 1\]", so) is not None, so)
    check("info hex pair: the cell field, averaged", re.search(r"pressure: 1 component, cell", so) is not None, so)
    check("info hex pair: auto draws phong", "auto draws phong" in so, so)
    # The 2x1x1 box's 16 edge segments (8 along x, 8 along y and z) are sharp under the VTK default of 40 degrees;
    # the 4 seams between the hexes' coplanar faces are not.
    check("info hex pair: the VTK crease default splits the box's 16 edges",
          re.search(r"0 non-manifold, 16 crease edges", so) is not None, so)
    rc, so0, se = run("info", os.path.join(WORK, "hex2.vtu"), "--crease", "0")
    check("info hex pair: --crease 0 turns the default off", re.search(r"0 non-manifold, 0 crease edges", so0) is not None,
          so0)
    check("info hex pair: the import's timings", re.search(r"vtk time:\s+read [0-9.]+ ms", so) is not None, so)
    q = quadratic_hex(os.path.join(WORK, "hex20.vtu"))
    rc, so, se = run("info", q)
    check("info quadratic hex: 6 second-order boundary quads",
          rc == 0 and re.search(r"boundary:\s+0 triangles, 6 quads \(6 second-order\)", so) is not None, (so, se))
    check("info quadratic hex: 6 curved faces", re.search(r"6 curved", so) is not None, so)
    check("info quadratic hex: auto draws quadratic", "auto draws quadratic" in so, so)
    rc, so, se = run("tessellate", q, "-o", os.path.join(WORK, "hex20.obj"))
    check("tessellate --surface auto picks quadratic for a quadratic file", rc == 0 and "-> quadratic" in so,
          (so, se))
    out = os.path.join(WORK, "hex20-play")
    rc, so, se = run("play", q, "--backend", "gl" if HAS_GL else "null", "--frames", "2", "--out", out, "-q")
    s = load_json(os.path.join(out, "summary.json"))
    check("play --surface auto plays quadratic for a quadratic file",
          rc == 0 and isinstance(s, dict) and s.get("surface") == "quadratic", (se, s))
    rc, so, se = run("tessellate", q, "-o", os.path.join(WORK, "hex20p.obj"), "--surface", "phong")
    check("tessellate --surface phong overrides auto", rc == 0 and "-> phong" in so, (so, se))


def without_vtk():
    quad = flat_quad(os.path.join(WORK, "quad.vtu"))
    rc, so, se = run("info", quad)
    check("without VTK: .vtu refused naming the file and VTK", rc != 0 and one_error_line(se) and "quad.vtu" in se
          and "VTK" in se, se)


if HAS_VTK:
    errors()
    info()
    if HAS_GL:
        rendered("gl")
        series()
    if HAS_VK:
        rendered("vulkan")
else:
    without_vtk()
finish()
