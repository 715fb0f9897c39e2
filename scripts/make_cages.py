#!/usr/bin/env python3
"""Writes the subdivision control cages of data/cages/ (small OBJ files, faces counter-clockwise
seen from outside; crease tags in OpenSubdiv's shape format with 0-based vertex indices).

    python3 scripts/make_cages.py            # from the repository root
"""
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "cages")


def fmt(x):
    r = round(x, 12)
    return repr(0.0 if r == 0 else r)


def write(name, comment, vertices, faces, tags=()):
    with open(os.path.join(OUT, name), "w") as f:
        f.write("# %s (scripts/make_cages.py)\n" % comment)
        for v in vertices:
            f.write("v %s\n" % " ".join(fmt(c) for c in v))
        for face in faces:
            f.write("f %s\n" % " ".join(str(i + 1) for i in face))
        for t in tags:
            f.write(t + "\n")


CUBE_V = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
# vertex index = 4x + 2y + z with x, y, z in {0, 1}
CUBE_F = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def torus(n_major=8, n_minor=4, r_major=2.0, r_minor=0.75):
    vertices, faces = [], []
    for i in range(n_major):
        a = 2 * math.pi * i / n_major
        for j in range(n_minor):
            b = 2 * math.pi * j / n_minor
            r = r_major + r_minor * math.cos(b)
            vertices.append((r * math.cos(a), r * math.sin(a), r_minor * math.sin(b)))
    idx = lambda i, j: (i % n_major) * n_minor + (j % n_minor)
    for i in range(n_major):
        for j in range(n_minor):
            faces.append((idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)))
    return vertices, faces


def octahedron():
    vertices = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return vertices, faces


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write("cube.obj", "cube cage: Catmull-Clark gives a closed genus-0 limit surface", CUBE_V, CUBE_F)
    v, f = torus()
    write("torus.obj", "torus-shaped quad cage, 8 x 4 quads, every vertex regular: a genus-1 limit surface", v, f)
    v, f = octahedron()
    write("octahedron.obj", "triangle cage: Loop gives a closed genus-0 limit surface", v, f)
    # The top square's four edges infinitely sharp and two of its corners sharp.
    write("creased_cube.obj", "cube cage with the edges of the top face (+z) infinitely sharp and corners 1, 7 sharp",
          CUBE_V, CUBE_F, ["t crease 8/1 1 3 3 7 7 5 5 1 10", "t corner 2/1 1 7 10"])
