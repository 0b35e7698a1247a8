# SPDX-License-Identifier: MIT OR Apache-2.0
"""facebem for Blender: ARKit / VRM / muscle shape keys on the selected mesh, in place.

*Generate Expressions* writes the active mesh's vertices and faces (its own vertex order, object
space) to a temporary OBJ, runs the facebem command line on it (`facebem export`, found on PATH
or set in the add-on's preferences), reads the morph targets back from the GLB it writes and adds
each one as a shape key of the same object. Vertices, UV maps, seams and materials are not
touched; running it again replaces the keys it made. Errors are reported in one line (facebem's
own message when it refuses the mesh).

Scripted use (what the repository's test runs in Blender's background mode):

    bpy.ops.facebem.generate_expressions(names='ARKIT_VRM')
"""

bl_info = {
    "name": "facebem expressions",
    "author": "facebem contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Object > Generate Expressions (facebem); Sidebar > facebem",
    "description": "Physically based ARKit / VRM / muscle shape keys for a face mesh",
    "category": "Animation",
}

import json
import os
import shutil
import struct
import subprocess
import tempfile

import bpy
import numpy as np

FLOAT = 5126
INDEX_DTYPES = {5121: "<u1", 5123: "<u2", 5125: "<u4"}


class FacebemError(Exception):
    """A one-line reason the expressions could not be made."""


def facebem_executable(context):
    """The facebem command: the path set in the preferences, else `facebem` on PATH."""
    prefs = context.preferences.addons[__name__].preferences if __name__ in context.preferences.addons else None
    path = bpy.path.abspath(prefs.facebem_path) if prefs and prefs.facebem_path else ""
    if path:
        if not os.path.isfile(path):
            raise FacebemError(f"the facebem path in the add-on preferences does not exist: {path}")
        return path
    found = shutil.which("facebem")
    if not found:
        raise FacebemError(
            "facebem was not found on PATH: install it (cargo install --path crates/cli) "
            "or set its path in the add-on preferences"
        )
    return found


def write_obj(mesh, path):
    """The mesh's vertices (object space, in order) and polygons as a plain OBJ."""
    count = len(mesh.vertices)
    co = np.empty(count * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3).astype(np.float64)
    with open(path, "w", encoding="utf-8") as f:
        f.write("# written by the facebem Blender add-on\n")
        for x, y, z in co:
            f.write(f"v {x!r} {y!r} {z!r}\n")
        for poly in mesh.polygons:
            f.write("f " + " ".join(str(v + 1) for v in poly.vertices) + "\n")
    return co


def read_glb(path):
    """(target names, metres per input unit, position deltas per target [count x 3], count)."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 20 or data[:4] != b"glTF":
        raise FacebemError(f"{path} is not a GLB")
    json_len = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20 : 20 + json_len])
    bin_start = 20 + json_len + 8
    blob = data[bin_start:]
    views = doc.get("bufferViews", [])

    def view_bytes(index):
        v = views[index]
        start = v.get("byteOffset", 0)
        return blob[start : start + v["byteLength"]]

    def vec3(accessor_index):
        a = doc["accessors"][accessor_index]
        if a["componentType"] != FLOAT or a["type"] != "VEC3":
            raise FacebemError("unexpected accessor type in the GLB")
        n = a["count"]
        out = np.zeros((n, 3), dtype=np.float64)
        if "bufferView" in a:
            raw = view_bytes(a["bufferView"])[a.get("byteOffset", 0) :]
            out[:] = np.frombuffer(raw, dtype="<f4", count=n * 3).reshape(n, 3)
        sparse = a.get("sparse")
        if sparse:
            k = sparse["count"]
            ind = sparse["indices"]
            idx = np.frombuffer(
                view_bytes(ind["bufferView"])[ind.get("byteOffset", 0) :],
                dtype=INDEX_DTYPES[ind["componentType"]],
                count=k,
            )
            val = sparse["values"]
            values = np.frombuffer(
                view_bytes(val["bufferView"])[val.get("byteOffset", 0) :], dtype="<f4", count=k * 3
            )
            out[idx.astype(np.int64)] = values.reshape(k, 3)
        return out

    mesh = doc["meshes"][0]
    prim = mesh["primitives"][0]
    names = mesh.get("extras", {}).get("targetNames", [])
    deltas = [vec3(t["POSITION"]) for t in prim.get("targets", [])]
    if len(names) != len(deltas):
        raise FacebemError("the GLB's target names do not match its targets")
    metres = doc["asset"].get("extras", {}).get("metresPerInputUnit", 1.0)
    count = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
    return names, float(metres), deltas, count


def add_shape_keys(obj, names, deltas, metres_per_unit):
    """One shape key per target on `obj` (a Basis first if it has none); existing keys of the
    same names are overwritten."""
    mesh = obj.data
    if mesh.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    basis = mesh.shape_keys.reference_key
    n = len(mesh.vertices)
    base = np.empty(n * 3, dtype=np.float32)
    basis.data.foreach_get("co", base)
    base = base.reshape(n, 3).astype(np.float64)
    for name, delta in zip(names, deltas):
        key = mesh.shape_keys.key_blocks.get(name) or obj.shape_key_add(name=name, from_mix=False)
        key.slider_min = min(key.slider_min, 0.0)
        co = base + delta[:n] / metres_per_unit
        key.data.foreach_set("co", co.astype(np.float32).ravel())
    mesh.update()


def generate(context, obj, names_option, units, progress=lambda f, text: None):
    """Runs facebem on `obj`'s mesh and adds the keys; returns the count added."""
    if obj is None or obj.type != "MESH":
        raise FacebemError("select a mesh object")
    mesh = obj.data
    if len(mesh.polygons) == 0:
        raise FacebemError(f"{obj.name} has no faces")
    exe = facebem_executable(context)
    with tempfile.TemporaryDirectory(prefix="facebem_") as tmp:
        obj_path = os.path.join(tmp, "face.obj")
        glb_path = os.path.join(tmp, "face.glb")
        progress(0.05, "writing the mesh")
        write_obj(mesh, obj_path)
        progress(0.1, "computing the rig (a few seconds)")
        cmd = [exe, "export", obj_path, "--gltf", glb_path, "--names", names_option]
        if units != "auto":
            cmd += ["--units", units]
        try:
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=3600)
        except (OSError, subprocess.TimeoutExpired) as e:
            raise FacebemError(f"could not run {exe}: {e}") from e
        if run.returncode != 0:
            lines = [l for l in run.stderr.splitlines() if l.strip()]
            raise FacebemError(lines[-1] if lines else f"facebem exited with {run.returncode}")
        progress(0.8, "adding shape keys")
        names, metres, deltas, count = read_glb(glb_path)
        if count < len(mesh.vertices):
            raise FacebemError(
                f"the export has {count} vertices for the mesh's {len(mesh.vertices)}"
            )
        add_shape_keys(obj, names, deltas, metres)
        progress(1.0, "done")
        return len(names)


class FACEBEM_OT_generate_expressions(bpy.types.Operator):
    """Add ARKit / VRM (and facebem muscle) shape keys to the active mesh, computed by facebem"""

    bl_idname = "facebem.generate_expressions"
    bl_label = "Generate Expressions (facebem)"
    bl_options = {"REGISTER", "UNDO"}

    names: bpy.props.EnumProperty(
        name="Names",
        items=[
            ("ARKIT_VRM", "ARKit + VRM", "ARKit's blendshapes and VRM 1.0's presets"),
            ("ARKIT", "ARKit", "ARKit's blendshapes only"),
            ("ALL", "All", "ARKit, VRM and facebem's own muscle and preset keys"),
        ],
        default="ARKIT_VRM",
    )
    units: bpy.props.EnumProperty(
        name="Units",
        description="Length unit of the mesh's coordinates (auto: from the distance between the eyes)",
        items=[(u, u, "") for u in ("auto", "mm", "cm", "m", "in")],
        default="auto",
    )

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH" and obj.mode == "OBJECT"

    def execute(self, context):
        names_option = {"ARKIT_VRM": "arkit,vrm", "ARKIT": "arkit", "ALL": "all"}[self.names]
        wm = context.window_manager
        wm.progress_begin(0, 100)

        def progress(fraction, text):
            wm.progress_update(int(100 * fraction))
            if context.workspace is not None:
                context.workspace.status_text_set(f"facebem: {text}")
            print(f"facebem: {int(100 * fraction)}% {text}", flush=True)

        try:
            added = generate(context, context.active_object, names_option, self.units, progress)
        except FacebemError as e:
            self.report({"ERROR"}, f"facebem: {e}")
            return {"CANCELLED"}
        finally:
            wm.progress_end()
            if context.workspace is not None:
                context.workspace.status_text_set(None)
        self.report({"INFO"}, f"facebem: {added} shape keys on {context.active_object.name}")
        return {"FINISHED"}


class FACEBEM_PT_panel(bpy.types.Panel):
    bl_label = "facebem"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "facebem"

    def draw(self, context):
        self.layout.operator(FACEBEM_OT_generate_expressions.bl_idname, text="Generate Expressions")


class FacebemPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__

    facebem_path: bpy.props.StringProperty(
        name="facebem executable",
        description="Path of the facebem command (empty: found on PATH)",
        subtype="FILE_PATH",
        default="",
    )

    def draw(self, context):
        self.layout.prop(self, "facebem_path")


def menu_entry(self, context):
    self.layout.operator(FACEBEM_OT_generate_expressions.bl_idname)


CLASSES = (FACEBEM_OT_generate_expressions, FACEBEM_PT_panel, FacebemPreferences)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(menu_entry)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_entry)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
