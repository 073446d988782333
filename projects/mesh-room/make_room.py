#!/usr/bin/env python3
"""Writes room.obj and room.mtl of the mesh-room project: a Cornell-like room whose walls, floor and
ceiling are quads in their own groups, a ceiling lamp quad whose material emits (Ke), a short box,
and a smooth ball: an icosphere subdivided twice (320 triangles) with per-vertex normals (vn).
Run from this folder; the files it writes are committed, so the project needs no Python."""
import math

def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
             (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
             (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache, out = {}, []
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][i] + verts[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = out
    return verts, faces

lines = ["# mesh-room: written by make_room.py", "mtllib room.mtl"]
positions, normals = [], []

def quad(name, material, corner, e1, e2):
    """Parallelogram corner + s e1 + t e2, normal e1 x e2 (the side it faces)."""
    base = len(positions)
    for s, t in ((0, 0), (1, 0), (1, 1), (0, 1)):
        positions.append(tuple(corner[i] + s * e1[i] + t * e2[i] for i in range(3)))
    return (name, material, [[base + k for k in range(4)]], False)

groups = [
    quad("floor", "white", (-1, -1, -1), (0, 0, 2), (2, 0, 0)),
    quad("ceiling", "white", (-1, 1, -1), (2, 0, 0), (0, 0, 2)),
    quad("back-wall", "white", (-1, -1, -1), (2, 0, 0), (0, 2, 0)),
    quad("left-wall", "red", (-1, -1, -1), (0, 2, 0), (0, 0, 2)),
    quad("right-wall", "green", (1, -1, -1), (0, 0, 2), (0, 2, 0)),
    quad("lamp", "lamp", (-0.23, 0.99, -0.18), (0.46, 0, 0), (0, 0, 0.38)),
]
# Short box [0.05, 0.65] x [-1, -0.4] x [-0.1, 0.5], faces outward.
lo, hi = (0.05, -1.0, -0.1), (0.65, -0.4, 0.5)
d = tuple(hi[i] - lo[i] for i in range(3))
box = [quad("", "", lo, (0, 0, d[2]), (0, d[1], 0)), quad("", "", (hi[0], lo[1], lo[2]), (0, d[1], 0), (0, 0, d[2])),
       quad("", "", lo, (d[0], 0, 0), (0, 0, d[2])), quad("", "", (lo[0], hi[1], lo[2]), (0, 0, d[2]), (d[0], 0, 0)),
       quad("", "", lo, (0, d[1], 0), (d[0], 0, 0)), quad("", "", (lo[0], lo[1], hi[2]), (d[0], 0, 0), (0, d[1], 0))]
groups.append(("short-box", "white", [f for q in box for f in q[2]], False))
# Ball of radius 0.38 resting on the floor at the back left, smooth.
verts, faces = icosphere(2)
centre, r = (-0.42, -1 + 0.38, -0.3), 0.38
base = len(positions)
for v in verts:
    positions.append(tuple(centre[i] + r * v[i] for i in range(3)))
    normals.append(v)
groups.append(("ball", "ivory", [[base + a, base + b, base + c] for a, b, c in faces], True))

for p in positions:
    lines.append("v %.6f %.6f %.6f" % p)
for n in normals:
    lines.append("vn %.6f %.6f %.6f" % n)
nbase = len(positions) - len(normals)  # normal k belongs to position nbase + k
for name, material, faces, smooth in groups:
    lines += ["g " + name, "usemtl " + material]
    for f in faces:
        lines.append("f " + " ".join("%d//%d" % (i + 1, i - nbase + 1) if smooth else str(i + 1) for i in f))
open("room.obj", "w").write("\n".join(lines) + "\n")
open("room.mtl", "w").write("""# mesh-room materials: the Cornell box's colours; the lamp emits (Ke) and reflects nothing.
newmtl white
Kd 0.885809 0.698859 0.666422
newmtl red
Kd 0.570068 0.0430135 0.0443706
newmtl green
Kd 0.105421 0.37798 0.076425
newmtl ivory
Kd 0.8 0.78 0.7
newmtl lamp
Kd 0 0 0
Ke 18.387 13.9873 6.75357
""")
