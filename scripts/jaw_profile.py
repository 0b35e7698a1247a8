#!/usr/bin/env python3
"""Side view of the ICT 13k face's midline: neutral (grey), ICT's captured jawOpen (green) and
the rig's jawOpen (blue), as docs/jaw_open_profile.png. Needs python3-pil.

    cargo run --release -p facebem-cli -- pose assets/ict_narrow_face_4loop.obj --preset jawOpen -o /tmp/jaw.obj
    python3 scripts/jaw_profile.py /tmp/jaw.obj docs/jaw_open_profile.png

Also prints the motion of the mesh's lowest midline vertex (the lower edge under the jaw), in mm
(the ICT mesh is in cm)."""
import sys
from PIL import Image, ImageDraw


def load(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith('v ')]


posed_path, out = sys.argv[1], sys.argv[2]
base = load('assets/ict_narrow_face_4loop.obj')
cap = load('tests/data/calibration/ict_narrow_face_jawOpen.obj')
rig = load(posed_path)
if not len(base) == len(cap) == len(rig):
    sys.exit('vertex counts differ: %d %d %d' % (len(base), len(cap), len(rig)))
xs = [v[0] for v in base]
xm = (max(xs) + min(xs)) / 2
mid = [i for i, v in enumerate(base) if abs(v[0] - xm) < 0.15]
low = min(mid, key=lambda i: base[i][1])
for name, vs in [('captured', cap), ('rig', rig)]:
    d = [10 * (vs[low][k] - base[low][k]) for k in range(3)]
    print('%s: lowest midline vertex moves %.1f mm down, %.1f mm back' % (name, -d[1], -d[2]))
W = H = 900
ys = [v[1] for src in (base, cap, rig) for v in (src[i] for i in mid)]
zs = [v[2] for src in (base, cap, rig) for v in (src[i] for i in mid)]
y0, y1, z0, z1 = min(ys) - 1, max(ys) + 1, min(zs) - 1, max(zs) + 1
s = min(W / (z1 - z0), H / (y1 - y0))
img = Image.new('RGB', (W, H), 'white')
d = ImageDraw.Draw(img)
for src, colour in [(base, (170, 170, 170)), (cap, (0, 150, 0)), (rig, (0, 0, 200))]:
    for i in mid:
        x, y = (src[i][2] - z0) * s, H - (src[i][1] - y0) * s
        d.ellipse([x - 2, y - 2, x + 2, y + 2], fill=colour)
d.text((10, 10), 'ICT 13k midline, side view (face looks right): grey neutral, '
       'green captured jawOpen, blue rig jawOpen', fill=(0, 0, 0))
img.save(out)
print('wrote', out)
