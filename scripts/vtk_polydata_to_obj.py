#!/usr/bin/env python3
"""Converts a legacy ASCII VTK POLYDATA file's points and polygons into an OBJ
(positions printed with %.9g so they round-trip). Used once to bring the
scanned face of the VTK test data into tests/data/derived/.
Usage: vtk_polydata_to_obj.py IN.vtk OUT.obj"""
import sys

def main():
    src, dst = sys.argv[1:3]
    tokens = open(src).read().split()
    i = tokens.index('POINTS')
    n = int(tokens[i + 1])
    pts = [float(t) for t in tokens[i + 3:i + 3 + 3 * n]]
    j = tokens.index('POLYGONS')
    cells = int(tokens[j + 1])
    k = j + 3
    faces = []
    for _ in range(cells):
        c = int(tokens[k])
        faces.append([int(t) for t in tokens[k + 1:k + 1 + c]])
        k += 1 + c
    with open(dst, 'w') as f:
        f.write('# converted from %s by scripts/vtk_polydata_to_obj.py\n' % src.split('/')[-1])
        for p in range(n):
            f.write('v %.9g %.9g %.9g\n' % tuple(pts[3 * p:3 * p + 3]))
        for face in faces:
            f.write('f ' + ' '.join(str(v + 1) for v in face) + '\n')
    print('%s: %d points, %d faces' % (dst, n, len(faces)))

main()
