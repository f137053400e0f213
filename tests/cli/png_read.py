"""A small 8-bit PNG reader for the CLI tests (screenshots of tlod play)."""
import struct, zlib


def _unfilter(ft, line, prev, bpp):
    if ft == 1:
        for i in range(bpp, len(line)):
            line[i] = (line[i] + line[i - bpp]) & 255
    elif ft == 2:
        line = bytearray((a + b) & 255 for a, b in zip(line, prev))
    elif ft == 3:
        for i in range(len(line)):
            left = line[i - bpp] if i >= bpp else 0
            line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
    elif ft == 4:
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else (b if pb <= pc else c))) & 255
    return line


def png_rows(path):
    """(width, height, bytes per pixel, colour type, rows top first) of an 8-bit PNG; CRCs checked."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("no PNG signature")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]:
            raise ValueError("bad CRC in " + kind.decode())
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, ctype = ihdr[0], ihdr[1], ihdr[2], ihdr[3]
    bpp = {6: 4, 2: 3, 0: 1, 4: 2}[ctype]
    if depth != 8:
        raise ValueError("bit depth %d" % depth)
    raw = zlib.decompress(idat)
    stride = w * bpp
    prev, rows = bytearray(stride), []
    for y in range(h):
        start = y * (stride + 1)
        prev = _unfilter(raw[start], bytearray(raw[start + 1:start + 1 + stride]), prev, bpp)
        rows.append(bytes(prev))
    return w, h, bpp, ctype, rows


def pixel(image, x, y):
    """RGB of pixel (x, y), y from the top, of png_rows()' result."""
    w, h, bpp, _, rows = image
    return tuple(rows[y][x * bpp:x * bpp + 3])
