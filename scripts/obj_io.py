"""The OBJ reader of the picture scripts (side_view.py, capture_heat_map.py): vertices and the
polygons fanned into triangles, 0-based."""


def load(path):
    vertices, triangles = [], []
    for line in open(path):
        s = line.split()
        if not s:
            continue
        if s[0] == 'v':
            vertices.append(tuple(map(float, s[1:4])))
        elif s[0] == 'f':
            idx = [int(t.split('/')[0]) - 1 for t in s[1:]]
            for k in range(1, len(idx) - 1):
                triangles.append((idx[0], idx[k], idx[k + 1]))
    return vertices, triangles
