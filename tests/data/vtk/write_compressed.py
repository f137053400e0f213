#!/usr/bin/env python3
"""Writes the zlib-compressed .vtp files of tests/data (SOURCES.md section 3): two triangles on
4 points, every array in 4-byte blocks (so the offsets' last value sits in a block of its own, the
one the pre-flight inflates), appended data base64 or raw, laid out as VTK 9.1's XML writer lays it
out (UInt32 header [blocks, block size, last block size, compressed sizes...], then the blocks; in
base64 the header and the blocks are two runs). Usage: write_compressed.py OUT_DIR FUZZ_DIR."""
import base64
import struct
import sys
import zlib


def compressed(data, block=4):
    blocks = [data[i:i + block] for i in range(0, len(data), block)]
    packed = [zlib.compress(b) for b in blocks]
    last = len(blocks[-1]) if len(blocks[-1]) != block else 0
    head = struct.pack("<%dI" % (3 + len(packed)), len(packed), block, last, *[len(c) for c in packed])
    return head, b"".join(packed)


def vtp(encoding, last_offset):
    arrays = [("Points", "Float32", 3, struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)),
              ("connectivity", "Int32", 1, struct.pack("<6i", 0, 1, 2, 1, 3, 2)),
              ("offsets", "Int32", 1, struct.pack("<2i", 3, last_offset))]
    appended, tags = b"", []
    for name, kind, comps, data in arrays:
        head, body = compressed(data)
        tags.append('<DataArray type="%s" Name="%s" NumberOfComponents="%d" format="appended" offset="%d"/>' %
                    (kind, name, comps, len(appended)))
        appended += base64.b64encode(head) + base64.b64encode(body) if encoding == "base64" else head + body
    xml = ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian" '
           'compressor="vtkZLibDataCompressor">\n<PolyData><Piece NumberOfPoints="4" NumberOfVerts="0" '
           'NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="2">\n<Points>%s</Points>\n<Polys>%s%s</Polys>\n'
           '</Piece></PolyData>\n<AppendedData encoding="%s">\n_' % (tags[0], tags[1], tags[2], encoding))
    return xml.encode() + appended + b"\n</AppendedData>\n</VTKFile>\n"


for enc in ("base64", "raw"):
    with open("%s/compressed_%s.vtp" % (sys.argv[1], enc), "wb") as f:
        f.write(vtp(enc, 6))
    with open("%s/compressed_offsets_past_connectivity_%s.vtp" % (sys.argv[2], enc), "wb") as f:
        f.write(b"\x02" + vtp(enc, 2**31 - 1))  # first byte 2: fuzz_vtk reads it as .vtp
