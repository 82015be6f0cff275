"""Portable Float Map (PFM) images as numpy arrays, for the benchmark harness.

vkpath writes colour PFMs ("PF", little endian, scale -1.0, rows from the bottom of the image to the
top, as the format says). read_pfm() returns the rows top first (row 0 = top, as vkpath's Image);
write_pfm() writes them back bottom first, so vkpath reads exactly the array it was given.
"""
import os
import pathlib

import numpy as np


def read_pfm(path):
    """A (height, width, 3) float32 array, row 0 = top. Raises ValueError on a malformed file."""
    data = pathlib.Path(path).read_bytes()
    tokens = []
    pos = 0
    while len(tokens) < 4:  # magic, width, height, scale; single white space after the scale
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while pos < len(data) and not data[pos:pos + 1].isspace():
            pos += 1
        if start == pos:
            raise ValueError("%s: truncated PFM header" % path)
        tokens.append(data[start:pos].decode("ascii"))
    pos += 1
    magic, width, height, scale = tokens[0], int(tokens[1]), int(tokens[2]), float(tokens[3])
    if magic != "PF":
        raise ValueError("%s: not a colour PFM (magic %r)" % (path, magic))
    dtype = "<f4" if scale < 0 else ">f4"
    count = width * height * 3
    pixels = np.frombuffer(data, dtype=dtype, count=count, offset=pos)
    return pixels.reshape(height, width, 3)[::-1].astype(np.float32)


def write_pfm(path, image):
    """Writes a (height, width, 3) array (row 0 = top) atomically (temporary file + rename)."""
    image = np.asarray(image, dtype="<f4")
    if image.ndim != 3 or image.shape[2] != 3:
        raise ValueError("write_pfm: need a (height, width, 3) array, got %s" % (image.shape,))
    height, width = image.shape[:2]
    path = pathlib.Path(path)
    tmp = path.with_name("." + path.name + ".tmp-%d" % os.getpid())
    with open(tmp, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(np.ascontiguousarray(image[::-1]).tobytes())
    tmp.replace(path)
