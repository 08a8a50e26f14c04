#!/usr/bin/env python3
"""Builds the seed corpora of the fuzz targets in OUT/<target>/ at run time.

Seeds come from fuzz/seeds/<format>/ (tiny hand-made files kept in the
repo) and from the shared test meshes (../shared/meshes, never copied into
the repo): small OBJ and GLB files as they are, multi-file glTF with its
buffers inlined as data URIs and also repacked as GLB, and small OBJ meshes
converted to PLY (ASCII, both binary byte orders), OFF and STL (ASCII,
binary) so every reader starts from valid files of its own format.

Usage: corpus.py OUT [MESHES_DIR]
"""
import base64
import json
import pathlib
import struct
import sys

MAX_SEED = 16 * 1024  # bytes; larger seeds slow every execution down

here = pathlib.Path(__file__).resolve().parent
out = pathlib.Path(sys.argv[1])
meshes = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else here.parent.parent / "shared" / "meshes"


def put(target, name, data):
    if len(data) > MAX_SEED:
        return
    path = out / target / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)


def small(pattern):
    if not meshes.is_dir():
        return []
    return sorted(p for p in meshes.glob(pattern) if p.is_file() and p.stat().st_size <= MAX_SEED)


def parse_obj(data):
    """Vertices and polygons (0-based) of a simple OBJ, or None."""
    vs, fs = [], []
    for line in data.decode("latin-1").splitlines():
        w = line.split()
        if not w:
            continue
        try:
            if w[0] == "v" and len(w) >= 4:
                vs.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "f" and len(w) >= 4:
                idx = [int(x.split("/")[0]) for x in w[1:]]
                fs.append([i - 1 if i > 0 else len(vs) + i for i in idx])
        except ValueError:
            return None
    if not vs or not fs or any(len(f) > 255 or i < 0 or i >= len(vs) for f in fs for i in f):
        return None
    return vs, fs


def ply(vs, fs, fmt):
    head = f"ply\nformat {fmt} 1.0\nelement vertex {len(vs)}\nproperty float x\nproperty float y\n" \
           f"property float z\nelement face {len(fs)}\nproperty list uchar int vertex_indices\nend_header\n"
    if fmt == "ascii":
        body = "".join("%g %g %g\n" % v for v in vs) + "".join(
            " ".join(map(str, [len(f)] + f)) + "\n" for f in fs)
        return (head + body).encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(e + "3f", *v) for v in vs)
    body += b"".join(struct.pack(e + "B%di" % len(f), len(f), *f) for f in fs)
    return head.encode() + body


def off(vs, fs):
    return (f"OFF\n{len(vs)} {len(fs)} 0\n" + "".join("%g %g %g\n" % v for v in vs) +
            "".join(" ".join(map(str, [len(f)] + f)) + "\n" for f in fs)).encode()


def triangles(fs):
    return [(f[0], f[i], f[i + 1]) for f in fs for i in range(1, len(f) - 1)]


def stl_ascii(vs, fs):
    text = "solid seed\n"
    for t in triangles(fs):
        text += " facet normal 0 0 0\n  outer loop\n" + "".join(
            "   vertex %g %g %g\n" % vs[i] for i in t) + "  endloop\n endfacet\n"
    return (text + "endsolid seed\n").encode()


def stl_binary(vs, fs):
    tris = triangles(fs)
    data = b"binary seed".ljust(80, b"\0") + struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *vs[i]) for i in t) + b"\0\0"
    return data


def inline_gltf(path):
    """The .gltf with every external buffer as a data URI, and as a GLB."""
    doc = json.loads(path.read_text())
    bins = []
    for buf in doc.get("buffers", []):
        uri = buf.get("uri", "")
        if uri and not uri.startswith("data:"):
            f = path.parent / uri
            if not f.is_file() or f.stat().st_size > MAX_SEED:
                return []
            bins.append(f.read_bytes())
            buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bins[-1]).decode()
    seeds = [("inline-" + path.stem + ".gltf", json.dumps(doc).encode())]
    if len(doc.get("buffers", [])) == 1 and bins:
        doc["buffers"][0].pop("uri")
        js = json.dumps(doc).encode()
        js += b" " * (-len(js) % 4)
        bn = bins[0] + b"\0" * (-len(bins[0]) % 4)
        glb = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(js) + 8 + len(bn))
        glb += struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(bn), b"BIN\0") + bn
        seeds.append(("packed-" + path.stem + ".glb", glb))
    return seeds


for fmt in ("obj", "gltf", "ply", "stl", "off", "pipeline"):
    for seed in sorted((here / "seeds" / fmt).glob("*")):
        put(fmt, "repo-" + seed.name, seed.read_bytes())

objs = small("robust/obj/*.obj") + small("smooth/*.obj") + small("cad/*.obj")
for p in objs:
    put("obj", p.name, p.read_bytes())
    parsed = parse_obj(p.read_bytes())
    if parsed:
        vs, fs = parsed
        for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
            put("ply", f"{p.stem}-{fmt}.ply", ply(vs, fs, fmt))
        put("off", p.stem + ".off", off(vs, fs))
        put("stl", p.stem + "-ascii.stl", stl_ascii(vs, fs))
        put("stl", p.stem + "-binary.stl", stl_binary(vs, fs))
for p in small("robust/gltf/**/*.glb") + small("glb/*.glb"):
    put("gltf", p.name, p.read_bytes())
for p in small("robust/gltf/**/*.gltf") + small("gltf/**/*.gltf"):
    for name, data in inline_gltf(p):
        put("gltf", name, data)

for d in sorted(out.iterdir()):
    print(f"{d.name}: {len(list(d.iterdir()))} seeds")
