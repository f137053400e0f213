"""Shared by the end-to-end tests of the tlod command (cli_test.py,
play_test.py, tests/vtk/vtk_cli_test.py): running it, one "ok"/"FAIL" line
per check, the one-line error rule, exact closedness of an OBJ output, and the
closing "N passed, N failed" line and exit code.
Call init(TLOD) before run()."""
import json, os, shutil, struct, subprocess, sys

TLOD = None
passed = failed = 0


def init(tlod):
    global TLOD
    TLOD = tlod


def setup(argv):
    """The common command line of the end-to-end tests, TLOD DATA_DIR WORK_DIR [gl|nogl]: init(TLOD), WORK made
    empty; returns (TLOD, DATA, WORK, built_with_gl) with absolute paths. "gl": the build has the GL backend and a
    GL context must work (a failure, never a skip); "nogl": it has none, and the GL checks are left out for that
    reason alone."""
    tlod, data, work = (os.path.abspath(a) for a in argv[1:4])
    init(tlod)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    return tlod, data, work, (argv[4] if len(argv) > 4 else "gl") == "gl"


def run(*args, cwd=None, timeout=300, env=None):
    p = subprocess.run([TLOD, *args], capture_output=True, text=True, timeout=timeout, cwd=cwd,
                       env=dict(os.environ, **env) if env else None)
    return p.returncode, p.stdout, p.stderr


def check(name, cond, detail=""):
    global passed, failed
    if cond:
        passed += 1
        print("ok   " + name)
    else:
        failed += 1
        print("FAIL " + name + (": " + str(detail)[:2000] if detail else ""))
    return cond


def load_json(path):
    """The parsed file, or the exception that reading it raised."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        return e


def one_error_line(err):
    lines = [l for l in err.splitlines() if l.strip()]
    return len(lines) == 1 and lines[0].startswith("tlod: error: ")


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                verts.append(tuple(struct.unpack("<3I", struct.pack("<3f", *map(float, t[1:4])))))
            elif t[0] == "f":
                tris.append(tuple(int(x.split("/")[0]) - 1 for x in t[1:4]))
    return verts, tris


def closed_after_weld(verts, tris):
    """Welds by exact float bits; every undirected edge must have exactly two
    triangles, traversed in opposite directions."""
    ids = {}
    weld = [ids.setdefault(v, len(ids)) for v in verts]
    directed = {}
    for a, b, c in tris:
        a, b, c = weld[a], weld[b], weld[c]
        if a == b or b == c or c == a:
            return False, "degenerate triangle after welding"
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
    for (a, b), n in directed.items():
        if n != 1 or directed.get((b, a), 0) != 1:
            return False, "edge %d-%d used %d/%d times" % (a, b, n, directed.get((b, a), 0))
    return True, ""


def finish():
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)
