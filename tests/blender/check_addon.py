# Run by crates/cli/tests/blender_addon.rs in Blender's background mode:
#   blender -b --factory-startup --python-exit-code 1 --python check_addon.py -- \
#       ADDON.zip FACEBEM FACE.obj OUT.json [SNIPPET.py]
# Installs and enables the add-on zip, imports FACE.obj keeping its coordinates and vertex
# order, gives it a UV map with a seam and a material, runs Generate Expressions (or the
# README's snippet), and writes what a user would check to OUT.json: the keys, their deltas,
# the UVs and materials before and after.
import json
import sys

import bpy
import numpy as np

args = sys.argv[sys.argv.index("--") + 1 :]
addon_zip, facebem, face_obj, out_json = args[:4]
snippet = args[4] if len(args) > 4 else None

bpy.ops.preferences.addon_install(filepath=addon_zip, overwrite=True)
bpy.ops.preferences.addon_enable(module="facebem_blender")
bpy.context.preferences.addons["facebem_blender"].preferences.facebem_path = facebem

for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
# Blender is Z-up, Y-forward: with these axes the importer keeps the file's coordinates.
bpy.ops.wm.obj_import(filepath=face_obj, forward_axis="Y", up_axis="Z")
obj = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = obj
mesh = obj.data
n = len(mesh.vertices)
co = np.empty(n * 3, dtype=np.float32)
mesh.vertices.foreach_get("co", co)

# A UV map with a seam down the middle: loops of faces left of x = 0 get u + 2, so the
# vertices on the midline carry two texture coordinates.
uv = mesh.uv_layers.new(name="seamed")
cx = co.reshape(-1, 3)[:, 0].mean()
for poly in mesh.polygons:
    left = np.mean([co[3 * v] for v in poly.vertices]) < cx
    for li in poly.loop_indices:
        p = co[3 * mesh.loops[li].vertex_index : 3 * mesh.loops[li].vertex_index + 3]
        uv.data[li].uv = (p[0] + (2.0 if left else 0.0), p[1])
seam_vertices = set()
by_vertex = {}
for li, loop in enumerate(mesh.loops):
    u = tuple(round(c, 6) for c in uv.data[li].uv)
    by_vertex.setdefault(loop.vertex_index, set()).add(u)
seam_vertices = [v for v, us in by_vertex.items() if len(us) > 1]
material = bpy.data.materials.new("user_skin")
mesh.materials.clear()
mesh.materials.append(material)


def uv_array():
    a = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    mesh.uv_layers["seamed"].data.foreach_get("uv", a)
    return a


uv_before = uv_array()
if snippet:
    exec(compile(open(snippet).read(), snippet, "exec"))
else:
    result = bpy.ops.facebem.generate_expressions(names="ARKIT_VRM")
    assert result == {"FINISHED"}, result

keys = mesh.shape_keys.key_blocks if mesh.shape_keys else []
basis = np.empty(n * 3, dtype=np.float32)
if keys:
    mesh.shape_keys.reference_key.data.foreach_get("co", basis)
report = {
    "vertices": n,
    "positions": co.tolist(),
    "seam_vertices": len(seam_vertices),
    "uv_unchanged": bool(np.array_equal(uv_before, uv_array())),
    "materials": [m.name for m in mesh.materials],
    "basis_is_mesh": bool(np.array_equal(basis, co)),
    "keys": {},
}
for key in list(keys)[1:]:
    k = np.empty(n * 3, dtype=np.float32)
    key.data.foreach_get("co", k)
    report["keys"][key.name] = (k.astype(np.float64) - basis.astype(np.float64)).tolist()
report["key_order"] = [k.name for k in keys]
with open(out_json, "w") as f:
    json.dump(report, f)

# A mesh that is no face: the operator is cancelled with facebem's one-line reason.
bpy.ops.mesh.primitive_cube_add()
cube = bpy.context.active_object
try:
    bpy.ops.facebem.generate_expressions()
    report["cube_error"] = None
except RuntimeError as e:
    report["cube_error"] = str(e)
report["cube_keys"] = 0 if cube.data.shape_keys is None else len(cube.data.shape_keys.key_blocks)
with open(out_json, "w") as f:
    json.dump(report, f)
