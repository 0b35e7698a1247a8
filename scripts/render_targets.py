"""Renders named morph targets of a GLB with Blender's workbench, each framed on what it moves.

blender -b --factory-startup --python-exit-code 1 --python scripts/render_targets.py -- head.glb out_prefix NAME:AZIMUTH_DEG:DISTANCE_M ...

Writes out_prefix_NAME.png per shot (docs/head_gaze_tongue.png: jawOpen:35:0.45 eyeLookUpLeft:0:0.2
tongueOut:30:0.22 mouthSmileLeft:0:0.35, joined with ImageMagick montage). For the picture only, the
eye overlays (occlusion, blend, tear film) and the cornea in front of the iris are left out: the
workbench draws them opaque.
"""
import bpy, sys, math, mathutils
argv = sys.argv[sys.argv.index("--") + 1:]
glb, out = argv[0], argv[1]
shots = [s.split(":") for s in argv[2:]]  # name:azimuth:distance_m
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb, import_shading='SMOOTH')
meshes = [o for o in bpy.context.scene.objects if o.type == 'MESH']
import bmesh
# Render only: ICT's eye overlays (occlusion, blend, tear film) are transparent shadows in
# its own renderer; the workbench draws them opaque, so they are left out of the picture.
colours = {"Iris": (0.1, 0.2, 0.5, 1), "Gums": (0.75, 0.35, 0.4, 1), "Teeth": (0.95, 0.95, 0.9, 1), "Sclera": (0.95, 0.95, 0.95, 1), "Lashes": (0.1, 0.1, 0.1, 1)}
for o in meshes:
    names = [m.name for m in o.data.materials]

    for m in o.data.materials:
        for k, c in colours.items():
            if k in m.name:
                m.diffuse_color = c
    bm = bmesh.new(); bm.from_mesh(o.data)
    kill = [f for f in bm.faces if any(k in names[f.material_index] for k in ("EyeBlend", "EyeOcclusion", "Lacrimal"))]
    # The cornea (the sclera's bulge in front of the iris) is drawn opaque too: leave it out.
    for side in ("ScleraLeft", "ScleraRight"):
        faces = [f for f in bm.faces if side in names[f.material_index]]
        if faces:
            vs = {v for f in faces for v in f.verts}
            c = sum((v.co for v in vs), mathutils.Vector()) / len(vs)
            rs = sorted((v.co - c).length for v in vs)
            med = rs[len(rs) // 2]
            apex = mathutils.Vector((0, -1, 0))  # glTF +z, the face's forward, in Blender
            kill += [f for f in faces if (f.calc_center_median() - c).angle(apex) < math.radians(35)]
    bmesh.ops.delete(bm, geom=kill, context='FACES')
    bm.to_mesh(o.data); bm.free()
scene = bpy.context.scene
scene.render.engine = 'BLENDER_WORKBENCH'
scene.display.shading.light = 'STUDIO'
scene.display.shading.color_type = 'MATERIAL'
scene.render.resolution_x = 360
scene.render.resolution_y = 360
cam_data = bpy.data.cameras.new("cam")
cam = bpy.data.objects.new("cam", cam_data)
scene.collection.objects.link(cam)
scene.camera = cam
cam_data.lens = 60
cam_data.clip_start = 0.001
for name, az, dist in shots:
    moved = []
    for o in meshes:
        sk = o.data.shape_keys
        if not sk:
            continue
        basis = sk.key_blocks[0]
        for kb in sk.key_blocks[1:]:
            kb.value = 1.0 if kb.name == name else 0.0
            if kb.name == name:
                for a, b in zip(basis.data, kb.data):
                    d = (b.co - a.co).length
                    if d > 0.001:
                        moved.append((o.matrix_world @ a.co, d))
    if moved:
        w = sum(d for _, d in moved)
        c = sum((p * d for p, d in moved), mathutils.Vector()) / w
    else:
        pts = [o.matrix_world @ mathutils.Vector(b) for o in meshes for b in o.bound_box]
        c = sum(pts, mathutils.Vector()) / len(pts)
    a = math.radians(float(az)); dist = float(dist)
    cam.location = c + mathutils.Vector((math.sin(a) * dist, -math.cos(a) * dist, 0.0))
    cam.rotation_euler = (c - cam.location).to_track_quat('-Z', 'Y').to_euler()
    scene.render.filepath = f"{out}_{name}.png"
    bpy.ops.render.render(write_still=True)
