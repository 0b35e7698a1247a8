#!/usr/bin/env python3
"""Front view of a pose's displacement beside ICT-FaceKit's captured one, as heat maps of the
magnitude (blue 0, red the larger peak of the two) with the x-y part drawn as strokes (x2).
Needs python3-pil; no GPU.

    python3 scripts/capture_heat_map.py NEUTRAL.obj POSED.obj CAPTURE OUT.png [MM_PER_UNIT]

NEUTRAL must be the ICT narrow face (assets/ict_narrow_face_4loop.obj, whose vertices are the
first ones of ICT's head), POSED a `facebem pose` of it, CAPTURE a file name of
tests/data/calibration/ict_head_deltas without `.txt` (e.g. cheekSquint_L; several joined by
`+` are summed, as ARKit's browInnerUp is ICT's browInnerUp_L+browInnerUp_R). MM_PER_UNIT: 10
(ICT is in cm)."""
import math
import os
import sys
from PIL import Image, ImageDraw

from obj_io import load

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')


def colour(t):
    t = min(1.0, t)
    return (int(255 * min(1.0, 2 * t)), int(255 * (1 - abs(t - 0.5) * 2)), int(255 * max(0.0, 1 - 2 * t)))


def main():
    neutral, posed, capture, out = sys.argv[1:5]
    mm = float(sys.argv[5]) if len(sys.argv) > 5 else 10.0
    v, tris = load(neutral)
    p, _ = load(posed)
    n = len(v)
    ours = [tuple((p[i][k] - v[i][k]) * mm for k in range(3)) for i in range(n)]
    cap = [(0.0, 0.0, 0.0)] * n
    for part in capture.split('+'):
        path = os.path.join(ROOT, 'tests/data/calibration/ict_head_deltas', part + '.txt')
        for line in open(path):
            if line.startswith('#'):
                continue
            s = line.split()
            i = int(s[0])
            if i < n:
                cap[i] = tuple(c + float(x) for c, x in zip(cap[i], s[1:4]))
    size = lambda d: math.sqrt(sum(c * c for c in d))
    peak = max(max(map(size, cap)), max(map(size, ours)))
    w = 500
    xs = [q[0] for q in v]
    ys = [q[1] for q in v]
    x0, y1 = min(xs), max(ys)
    scale = (w - 20) / max(max(xs) - x0, y1 - min(ys))
    project = lambda q: (10 + (q[0] - x0) * scale, 10 + (y1 - q[1]) * scale)
    img = Image.new('RGB', (2 * w, w + 30), 'white')
    draw = ImageDraw.Draw(img)
    order = sorted(range(len(tris)), key=lambda f: sum(v[i][2] for i in tris[f]))
    for panel, field in enumerate([ours, cap]):
        off = panel * w
        for f in order:
            a, b, c = tris[f]
            nz = (v[b][0] - v[a][0]) * (v[c][1] - v[a][1]) - (v[b][1] - v[a][1]) * (v[c][0] - v[a][0])
            if nz <= 0:
                continue
            m = sum(size(field[i]) for i in tris[f]) / 3
            draw.polygon([(project(v[i])[0] + off, project(v[i])[1]) for i in tris[f]],
                         fill=colour(m / peak if peak > 0 else 0.0))
        for i in range(0, n, 7):
            dx, dy = field[i][0], field[i][1]
            if math.hypot(dx, dy) < 0.3:
                continue
            x, y = project(v[i])
            x += off
            draw.line([(x, y), (x + dx * scale / mm * 2, y - dy * scale / mm * 2)], fill='black')
        label = ('facebem ' if panel == 0 else 'captured ') + capture
        draw.text((off + 10, w + 5), f'{label}  red = {peak:.1f} mm (strokes x2)', fill='black')
    img.save(out)


if __name__ == '__main__':
    main()
