#!/usr/bin/env python3
"""Writes the sample meshes of data/meshes/ (run from the repository root; standard library only).

  cube.obj (+ cube.mtl)   6 quads, per-corner uvs, 6 face normals, two groups, two materials,
                          vertex colours
  sphere.obj              a slightly bumpy UV sphere: quads, triangle fans at the poles, per-vertex
                          normals and uvs, one group (closed: the seam shares its vertices, so the
                          uvs wrap from u = 23/24 back to 0 on the last column of faces)
  sphere.ply              the same vertices and faces, binary little-endian float, with normals,
                          uvs and uchar colours
  sphere.off              the same, as OFF (NOFF with normals)
  sphere.stl              the same surface as binary STL triangles (quads split)
  sphere.gltf + .bin      the same vertices, triangles, float normals and uvs, a material, in glTF's
                          own axes: Y up (the specification), so a point (x, y, z) of the other files
                          is stored as (x, z, -y) and the poles lie along +-y; read Y up, turned by
                          (x, y, z) -> (x, -z, y), it is the same sphere as the others, poles along z
  sphere.glb              the same as one binary glTF

The files are written by this script, not by the library, so tests can read them as independent data.
"""

import json
import math
import os
import struct

OUT = os.path.join("data", "meshes")
SEGMENTS, RINGS = 24, 12


def sphere():
    """Vertices (position, normal, uv, colour) and faces (lists of indices) of a bumpy UV sphere."""
    verts = []

    def radius(theta, phi):
        return 1.0 + 0.05 * math.sin(5 * phi) * math.sin(3 * theta)

    def add(theta, phi, u, v):
        # Position on the bumpy surface; the normal from central differences of the parametrisation.
        def point(t, p):
            r = radius(t, p)
            return (r * math.sin(t) * math.cos(p), r * math.sin(t) * math.sin(p), r * math.cos(t))

        x = point(theta, phi)
        if theta in (0.0, math.pi):
            n = (0.0, 0.0, 1.0 if theta == 0.0 else -1.0)
        else:
            h = 1e-5
            dt = [(a - b) / (2 * h) for a, b in zip(point(theta + h, phi), point(theta - h, phi))]
            dp = [(a - b) / (2 * h) for a, b in zip(point(theta, phi + h), point(theta, phi - h))]
            c = (dt[1] * dp[2] - dt[2] * dp[1], dt[2] * dp[0] - dt[0] * dp[2], dt[0] * dp[1] - dt[1] * dp[0])
            length = math.sqrt(sum(k * k for k in c))
            n = tuple(k / length for k in c)
        colour = (int(255 * (0.5 + 0.5 * n[0])), int(255 * (0.5 + 0.5 * n[1])), int(255 * (0.5 + 0.5 * n[2])))
        verts.append((tuple(round(k, 6) for k in x), tuple(round(k, 6) for k in n), (u, v), colour))
        return len(verts) - 1

    top = add(0.0, 0.0, 0.5, 1.0)
    rows = []
    for i in range(1, RINGS):
        theta = math.pi * i / RINGS
        rows.append([add(theta, 2 * math.pi * j / SEGMENTS, j / SEGMENTS, 1 - i / RINGS) for j in range(SEGMENTS)])
    bottom = add(math.pi, 0.0, 0.5, 0.0)
    faces = []
    for j in range(SEGMENTS):
        faces.append([top, rows[0][j], rows[0][(j + 1) % SEGMENTS]])
    for i in range(RINGS - 2):
        for j in range(SEGMENTS):
            k = (j + 1) % SEGMENTS
            faces.append([rows[i][j], rows[i + 1][j], rows[i + 1][k], rows[i][k]])
    for j in range(SEGMENTS):
        faces.append([bottom, rows[-1][(j + 1) % SEGMENTS], rows[-1][j]])
    return verts, faces


def triangles(faces):
    return [[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)]


def fmt(x):
    return repr(float(x)) if x != int(x) else str(int(x))


def write_cube():
    with open(os.path.join(OUT, "cube.mtl"), "w") as f:
        f.write("newmtl red\nKd 0.8 0.1 0.1\n\nnewmtl blue\nKd 0.1 0.1 0.8\n")
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    lines = ["# unit cube: quads, per-corner uvs, face normals, groups, materials, vertex colours",
             "mtllib cube.mtl", "o Cube"]
    for x, y, z in corners:
        lines.append("v %s %s %s %s %s %s" % (fmt(x - 0.5), fmt(y - 0.5), fmt(z - 0.5), fmt(x), fmt(y), fmt(z)))
    lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    lines += ["vn 0 0 -1", "vn 0 0 1", "vn 0 -1 0", "vn 1 0 0", "vn 0 1 0", "vn -1 0 0"]
    lines += ["g caps", "usemtl red", "s off",
              "f 1/1/1 4/2/1 3/3/1 2/4/1", "f 5/1/2 6/2/2 7/3/2 8/4/2",
              "g sides", "usemtl blue",
              "f 1/1/3 2/2/3 6/3/3 5/4/3", "f 2/1/4 3/2/4 7/3/4 6/4/4",
              "f 3/1/5 4/2/5 8/3/5 7/4/5", "f 4/1/6 1/2/6 5/3/6 8/4/6"]
    with open(os.path.join(OUT, "cube.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")


def write_sphere(verts, faces):
    tris = triangles(faces)
    # OBJ
    lines = ["# bumpy UV sphere: %d vertices, %d faces (quads and triangles)" % (len(verts), len(faces)), "o Sphere", "g sphere"]
    lines += ["v %s %s %s" % tuple(fmt(k) for k in v[0]) for v in verts]
    lines += ["vt %s %s" % tuple(fmt(k) for k in v[2]) for v in verts]
    lines += ["vn %s %s %s" % tuple(fmt(k) for k in v[1]) for v in verts]
    lines += ["f " + " ".join("%d/%d/%d" % (i + 1, i + 1, i + 1) for i in f) for f in faces]
    with open(os.path.join(OUT, "sphere.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # PLY, binary little-endian float
    header = ("ply\nformat binary_little_endian 1.0\ncomment bumpy UV sphere, made by scripts/make_sample_meshes.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
              "property float ny\nproperty float nz\nproperty float s\nproperty float t\nproperty uchar red\n"
              "property uchar green\nproperty uchar blue\nelement face %d\nproperty list uchar int vertex_indices\n"
              "end_header\n" % (len(verts), len(faces)))
    body = b"".join(struct.pack("<8f3B", *v[0], *v[1], *v[2], *v[3]) for v in verts)
    body += b"".join(struct.pack("<B%di" % len(f), len(f), *f) for f in faces)
    with open(os.path.join(OUT, "sphere.ply"), "wb") as f:
        f.write(header.encode() + body)

    # OFF with normals
    lines = ["NOFF", "%d %d 0" % (len(verts), len(faces))]
    lines += ["%s %s %s %s %s %s" % tuple(fmt(k) for k in v[0] + v[1]) for v in verts]
    lines += ["%d %s" % (len(f), " ".join(str(i) for i in f)) for f in faces]
    with open(os.path.join(OUT, "sphere.off"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # STL, binary
    data = bytearray(b"binary STL: bumpy UV sphere".ljust(80, b" "))
    data += struct.pack("<I", len(tris))
    for t in tris:
        a, b, c = (verts[i][0] for i in t)
        u = [b[k] - a[k] for k in range(3)]
        w = [c[k] - a[k] for k in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        length = math.sqrt(sum(k * k for k in n)) or 1.0
        data += struct.pack("<12fH", *(k / length for k in n), *a, *b, *c, 0)
    with open(os.path.join(OUT, "sphere.stl"), "wb") as f:
        f.write(bytes(data))

    # glTF: positions, normals, uvs, uint16 indices; Y up (glTF's axes): (x, y, z) -> (x, z, -y),
    # a rotation, so the triangles keep their orientation. (The negation is exact in float.)
    def y_up(p):
        return (p[0], p[2], -p[1] if p[1] != 0 else 0.0)

    verts = [(y_up(v[0]), y_up(v[1]), v[2], v[3]) for v in verts]
    pos = b"".join(struct.pack("<3f", *v[0]) for v in verts)
    nor = b"".join(struct.pack("<3f", *v[1]) for v in verts)
    uv = b"".join(struct.pack("<2f", v[2][0], 1 - v[2][1]) for v in verts)
    idx = b"".join(struct.pack("<3H", *t) for t in tris)
    idx += b"\0" * (-len(idx) % 4)
    buffer = pos + nor + uv + idx
    views, offset = [], 0
    for part, target in ((pos, 34962), (nor, 34962), (uv, 34962), (idx, 34963)):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part), "target": target})
        offset += len(part)
    views[3]["byteLength"] = 6 * len(tris)
    lo = [min(struct.unpack("<f", struct.pack("<f", v[0][k]))[0] for v in verts) for k in range(3)]
    hi = [max(struct.unpack("<f", struct.pack("<f", v[0][k]))[0] for v in verts) for k in range(3)]
    doc = {
        "asset": {"version": "2.0", "generator": "scripts/make_sample_meshes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "Sphere", "extras": {"note": "bumpy UV sphere"}}],
        "materials": [{"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1.0],
                                                                 "metallicFactor": 0.0}}],
        "meshes": [{"name": "sphere", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                      "indices": 3, "material": 0}]}],
        "buffers": [{"uri": "sphere.bin", "byteLength": len(buffer)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(verts), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": len(verts), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": len(verts), "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 3 * len(tris), "type": "SCALAR"},
        ],
    }
    with open(os.path.join(OUT, "sphere.bin"), "wb") as f:
        f.write(buffer)
    with open(os.path.join(OUT, "sphere.gltf"), "w") as f:
        f.write(json.dumps(doc, indent=2) + "\n")
    del doc["buffers"][0]["uri"]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(buffer))
    glb += struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(buffer), 0x004E4942) + buffer
    with open(os.path.join(OUT, "sphere.glb"), "wb") as f:
        f.write(glb)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_cube()
    write_sphere(*sphere())
