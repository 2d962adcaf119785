# Imports a Sylva export made with `--wind SECONDS` into Blender and checks the wind (issue 17):
# an armature of at most 64 bones, a "wind" action, skinned meshes that move between the loop's
# start and its middle, and a loop whose last frame is its first.
#
#   blender -b --factory-startup --python tools/blender/check_wind.py -- TREE.glb
#
# Prints one line of numbers; exit status 1 when a check fails.
import os
import sys

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses the alias NumPy 1.24 removed

import bpy  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) < 1:
    print("usage: blender -b --factory-startup --python check_wind.py -- TREE.glb")
    sys.exit(2)
path = os.path.abspath(args[0])
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.import_scene.gltf(filepath=path)

failures = []
armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
bones = sum(len(a.data.bones) for a in armatures)
if not armatures:
    failures.append("no armature imported")
if bones > 64:
    failures.append(f"{bones} bones (at most 64)")
actions = [a for a in bpy.data.actions if "wind" in a.name]
if not actions:
    failures.append("no wind action; actions: " + ", ".join(a.name for a in bpy.data.actions))
skinned = [o for o in bpy.data.objects if o.type == "MESH" and any(m.type == "ARMATURE" for m in o.modifiers)]
if not skinned:
    failures.append("no mesh has an armature modifier")

scene = bpy.context.scene


def positions(frame):
    scene.frame_set(frame)
    dg = bpy.context.evaluated_depsgraph_get()
    out = []
    for o in skinned:
        ev = o.evaluated_get(dg)
        m = ev.to_mesh()
        out.extend((o.matrix_world @ v.co).copy() for v in m.vertices)
        ev.to_mesh_clear()
    return out


moved = loop_gap = 0.0
if actions and skinned and armatures:
    act = actions[0]
    for a in armatures:   # play the wind action on the armature
        if a.animation_data is None:
            a.animation_data_create()
        a.animation_data.action = act
    start, end = (int(round(f)) for f in act.frame_range)
    p0, pm, p1 = positions(start), positions((start + end) // 2), positions(end)
    moved = max((a - b).length for a, b in zip(p0, pm))
    loop_gap = max((a - b).length for a, b in zip(p0, p1))
    size = max((v - p0[0]).length for v in p0) or 1.0
    if moved < 1e-4 * size:
        failures.append(f"the tree does not move between frames {start} and {(start + end) // 2}")
    if loop_gap > 1e-4 * size:
        failures.append(f"the loop is not seamless: frame {end} is {loop_gap:.2e} m from frame {start}")
    print(f"check_wind: {os.path.basename(path)}: {bones} bones, action {act.name} frames {start}-{end}, "
          f"{len(skinned)} skinned meshes, max move {moved:.4f} m, loop gap {loop_gap:.2e} m")
for f in failures:
    print("check_wind: FAIL " + f)
sys.exit(1 if failures else 0)
