#!/usr/bin/env python3
"""Flat-shaded views of a face and its poses side by side, for looking at a shape from angles the
contact sheet does not show (the side, from below). Triangles whose normal turned over against
the first mesh are red. Needs python3-pil; painter's algorithm, no GPU.

    YAW=60 PITCH=0 python3 scripts/side_view.py NEUTRAL.obj POSED.obj [MORE.obj ...] OUT.png

Every mesh must have the first one's vertex order (e.g. `facebem pose` output, or ICT's captured
expressions in tests/data/calibration). YAW turns about the vertical axis (90 = side view),
PITCH then about the horizontal (negative looks from below), in degrees."""
import math
import os
import sys
from PIL import Image, ImageDraw

from obj_io import load


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


if len(sys.argv) < 3:
    sys.exit(__doc__)
base, triangles = load(sys.argv[1])
out = sys.argv[-1]
poses = [load(p)[0] for p in sys.argv[2:-1]]
for i, pose in enumerate(poses):
    if len(pose) != len(base):
        sys.exit('%s has %d vertices, %s %d' % (sys.argv[2 + i], len(pose), sys.argv[1], len(base)))
yaw = math.radians(float(os.environ.get('YAW', '90')))
pitch = math.radians(float(os.environ.get('PITCH', '0')))


def view_from_face(v):
    x, y, z = (math.cos(yaw) * v[0] + math.sin(yaw) * v[2], v[1],
               -math.sin(yaw) * v[0] + math.cos(yaw) * v[2])
    return (x, math.cos(pitch) * y - math.sin(pitch) * z, math.sin(pitch) * y + math.cos(pitch) * z)


turned = [view_from_face(v) for v in base]
min_x, max_x = min(v[0] for v in turned), max(v[0] for v in turned)
min_y, max_y = min(v[1] for v in turned), max(v[1] for v in turned)
size = int(os.environ.get("SIZE", "500"))
scale = size * 0.8 / max(max_x - min_x, max_y - min_y)
meshes = [base] + poses
img = Image.new('RGB', (size * len(meshes), size), 'white')
draw = ImageDraw.Draw(img)
light = (0.3, 0.4, 0.87)
for k, vertices in enumerate(meshes):
    view = [view_from_face(v) for v in vertices]
    polygons = []
    for t in triangles:
        a, b, c = (view[i] for i in t)
        n = cross(sub(b, a), sub(c, a))
        length = math.sqrt(dot(n, n)) or 1.0
        shade = abs(dot(n, light)) / length
        before = cross(sub(base[t[1]], base[t[0]]), sub(base[t[2]], base[t[0]]))
        after = cross(sub(vertices[t[1]], vertices[t[0]]), sub(vertices[t[2]], vertices[t[0]]))
        if dot(before, after) < 0:
            colour = (255, int(60 * shade), int(60 * shade))
        else:
            colour = (int(60 + 180 * shade), int(60 + 170 * shade), int(60 + 160 * shade))
        points = [(k * size + size * 0.1 + (p[0] - min_x) * scale, size * 0.9 - (p[1] - min_y) * scale)
                  for p in (a, b, c)]
        polygons.append(((a[2] + b[2] + c[2]) / 3, points, colour))
    polygons.sort(key=lambda p: p[0])
    for _, points, colour in polygons:
        draw.polygon(points, fill=colour)
img.save(out)
print('wrote', out)
