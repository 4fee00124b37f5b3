"""Writes seed inputs for fuzz/mesh_fuzzer.cpp into the folder given: the first byte of each
picks the reader (0 OBJ, 1 PLY, 2 .serialized), the rest is a small valid mesh file."""
import glob
import os
import struct
import sys
import zlib

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
here = os.path.join(os.path.dirname(__file__), "..")


def write(name, kind, data):
    with open(os.path.join(out, name), "wb") as f:
        f.write(bytes([kind]) + data)


for path in glob.glob(os.path.join(here, "scenes", "**", "*.obj"), recursive=True):
    if os.path.getsize(path) < 64 * 1024:
        write("obj-" + os.path.basename(path), 0, open(path, "rb").read())

verts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
faces = [(0, 1, 2), (1, 3, 2)]
header = ("ply\nformat {}\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
          "element face 2\nproperty list uchar int vertex_indices\nend_header\n")
ascii = header.format("ascii 1.0")
for x, y, z in verts:
    ascii += f"{x} {y} {z} 0 0 1 {x} {y}\n"
for f in faces:
    ascii += "3 %d %d %d\n" % f
write("ascii.ply", 1, ascii.encode())
binary = header.format("binary_little_endian 1.0").encode()
for x, y, z in verts:
    binary += struct.pack("<8f", x, y, z, 0, 0, 1, x, y)
for f in faces:
    binary += struct.pack("<B3i", 3, *f)
write("binary.ply", 1, binary)
# PLY files with vertex and face properties (mesh attributes: colours, grouped runs).
for path in glob.glob(os.path.join(here, "scenes", "**", "*.ply"), recursive=True):
    if os.path.getsize(path) < 64 * 1024:
        write("ply-" + os.path.basename(path), 1, open(path, "rb").read())
write("attributes.ply", 1, b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      b"property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty float foo_x\n"
      b"property short bar_0\nelement face 1\nproperty list uchar int vertex_indices\nproperty float id_1\n"
      b"property uchar r\nproperty uchar g\nproperty uchar b\nend_header\n0 0 0 255 0 128 1 -5\n"
      b"1 0 0 0 255 0 2 7\n0 1 0 0 0 255 3 9\n3 0 1 2 0.5 10 20 30\n")


def serialized_shape(name):
    body = struct.pack("<I", 0x1000 | 0x1 | 0x2) + name + b"\0" + struct.pack("<QQ", len(verts), len(faces))
    body += b"".join(struct.pack("<3f", *v) for v in verts)
    body += b"".join(struct.pack("<3f", 0, 0, 1) for _ in verts)
    body += b"".join(struct.pack("<2f", v[0], v[1]) for v in verts)
    body += b"".join(struct.pack("<3I", *f) for f in faces)
    return struct.pack("<HH", 0x041C, 4) + zlib.compress(body)


first, second = serialized_shape(b"a"), serialized_shape(b"b")
write("two.serialized", 2 + 3, first + second + struct.pack("<QQI", 0, len(first), 2))
write("one.serialized", 2, first)


# Issue 23's reproductions: a number past a float's range, a vt index past the file's, and a
# shape whose counts declare 2^28 vertices over 8 MiB of zeros (inflated only so far, then
# "truncated"; it once inflated all of a stream before reading a count).
write("obj-1e39.obj", 0, b"v 0 0 0\nv 1 0 0\nv 0 1 1e39\nf 1 2 3\n")
write("obj-vt-out-of-range.obj", 0, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/7\n")
bomb = struct.pack("<I", 0x1000) + b"bomb\0" + struct.pack("<QQ", 1 << 28, 1) + bytes(8 << 20)
write("serialized-declares-2pow28.serialized", 2, struct.pack("<HH", 0x041C, 4) + zlib.compress(bomb, 9))
