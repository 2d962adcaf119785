# Imports a Sylva export into Blender as an artist would, lists every material with its image
# textures and blend/alpha settings, checks that the bark has a base colour image and a normal map
# and that every leaf material has an image with alpha clipping, and renders a small PNG.
#
#   blender -b --factory-startup --python tools/blender/check_glb.py -- TREE.glb OUT.png [SIZE]
#
# TREE may also be a .gltf or an .obj (+ .mtl). Exit status 1 when a check fails. See docs/EXPORTS.md.
import math
import os
import sys

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses the alias NumPy 1.24 removed

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) < 2:
    print("usage: blender -b --factory-startup --python check_glb.py -- TREE.glb OUT.png [SIZE]")
    sys.exit(2)
tree_path, out_png = os.path.abspath(args[0]), os.path.abspath(args[1])
size = int(args[2]) if len(args) > 2 and args[2].isdigit() else 480

# An empty scene.
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)

ext = os.path.splitext(tree_path)[1].lower()
if ext in (".glb", ".gltf"):
    bpy.ops.import_scene.gltf(filepath=tree_path)
elif ext == ".obj":
    bpy.ops.wm.obj_import(filepath=tree_path)
elif ext == ".fbx":
    bpy.ops.import_scene.fbx(filepath=tree_path)
else:
    print(f"cannot import {tree_path}: use .glb, .gltf, .obj or .fbx")
    sys.exit(2)
# FBX only: --lods N demands the levels <tree>_LOD0 .. N-1, --wind an armature with an action.
want_lods = int(args[args.index("--lods") + 1]) if "--lods" in args else 0
want_wind = "--wind" in args
args = [a for i, a in enumerate(args) if a not in ("--lods", "--wind") and (i == 0 or args[i - 1] != "--lods")]


def upstream_images(socket, seen=None):
    """Image texture nodes feeding `socket`, through any nodes between (Normal Map, Separate RGB...)."""
    seen = seen if seen is not None else set()
    found = []
    for link in socket.links:
        node = link.from_node
        if node.name in seen:
            continue
        seen.add(node.name)
        if node.type == "TEX_IMAGE":
            found.append((node, link.from_socket.name))
        for inp in node.inputs:
            found += upstream_images(inp, seen)
    return found


def describe(mat):
    """Prints the material; returns {input name: [(image, output socket, via nodes)]}."""
    print(f"material {mat.name}: blend_method={mat.blend_method} alpha_threshold={mat.alpha_threshold:.2f} "
          f"shadow_method={mat.shadow_method} backface_culling={mat.use_backface_culling}")
    inputs = {}
    if not mat.use_nodes:
        return inputs
    bsdf = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        print("  (no Principled BSDF)")
        return inputs
    for name in ("Base Color", "Alpha", "Normal", "Roughness", "Metallic"):
        sock = bsdf.inputs.get(name)
        if sock is None or not sock.is_linked:
            continue
        via = sock.links[0].from_node.type
        for node, out in upstream_images(sock):
            img = node.image
            desc = f"{img.name} {img.size[0]}x{img.size[1]}" if img else "(no image)"
            print(f"  {name:<10} <- image {desc} [{out}] via {via}")
            inputs.setdefault(name, []).append(img)
    for name in ("Metallic", "Roughness"):
        sock = bsdf.inputs.get(name)
        if sock is not None and not sock.is_linked:
            print(f"  {name:<10} = {sock.default_value:.2f}")
    return inputs


problems = []
materials = sorted({slot.material for obj in bpy.data.objects if obj.type == "MESH"
                    for slot in obj.material_slots if slot.material}, key=lambda m: m.name)
print(f"imported {tree_path}: {sum(o.type == 'MESH' for o in bpy.data.objects)} mesh objects, "
      f"{len(materials)} materials")
for mat in materials:
    inputs = describe(mat)
    if mat.name.startswith("bark"):
        if not inputs.get("Base Color"):
            problems.append(f"{mat.name}: no base colour image")
        if not inputs.get("Normal") and not mat.name.endswith("custom"):
            problems.append(f"{mat.name}: no normal map")
    elif mat.name.startswith("leaves"):
        if not inputs.get("Base Color"):
            problems.append(f"{mat.name}: no base colour image")
        if not inputs.get("Alpha"):
            problems.append(f"{mat.name}: alpha not linked to an image")
        # glTF says MASK, which Blender imports as Alpha Clip. MTL cannot say "clip": Blender's OBJ
        # importer makes any material with map_d Alpha Blend, which renders the same in Cycles.
        # Blender's FBX importer, given a TransparentColor texture, makes the material Alpha Blend too.
        wanted = ("CLIP", "BLEND") if ext in (".obj", ".fbx") else ("CLIP",)
        if mat.blend_method not in wanted:
            problems.append(f"{mat.name}: blend_method {mat.blend_method}, not {' or '.join(wanted)}")
if ext == ".fbx":
    import re
    levels = sorted({int(m.group(1)) for o in bpy.data.objects if (m := re.search(r"_LOD(\d+)$", o.name))})
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    lo_z = min((o.matrix_world @ Vector(c)).z for o in meshes for c in o.bound_box) if meshes else 0
    hi_z = max((o.matrix_world @ Vector(c)).z for o in meshes for c in o.bound_box) if meshes else 0
    print(f"fbx: {len(meshes)} mesh objects, height {hi_z - lo_z:.2f} m, LOD levels {levels}")
    for lv in levels:
        node = next(o for o in bpy.data.objects if o.name.endswith(f"_LOD{lv}"))
        kids = [c for c in node.children_recursive if c.type == "MESH"] + ([node] if node.type == "MESH" else [])
        tris = sum(len(p.vertices) - 2 for k in kids for p in k.data.polygons)
        print(f"  {node.name}: {len(kids)} meshes, {tris} triangles")
    if want_lods and levels != list(range(want_lods)):
        problems.append(f"LOD levels {levels}, wanted 0..{want_lods - 1}")
    if want_lods:
        # The FBX LOD group (a LodGroup model) comes in as an empty whose children are the levels.
        parents = {o.parent.name if o.parent else None for o in bpy.data.objects if re.search(r"_LOD\d+$", o.name)}
        group = bpy.data.objects.get(next(iter(parents))) if len(parents) == 1 and None not in parents else None
        print(f"  LOD group: {group.name + ' (' + group.type + ')' if group else 'none'}, levels' parents {sorted(map(str, parents))}")
        if not group or group.type != "EMPTY":
            problems.append(f"the levels do not share one empty parent (the LOD group): parents {sorted(map(str, parents))}")
    arms = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    for a in arms:
        act = a.animation_data.action if a.animation_data else None
        print(f"  armature {a.name}: {len(a.data.bones)} bones, action "
              + (f"{act.name} frames {act.frame_range[0]:.0f}-{act.frame_range[1]:.0f}, {len(act.fcurves)} curves" if act else "none"))
    skinned = [o for o in meshes if any(m.type == "ARMATURE" for m in o.modifiers)]
    if want_wind:
        if not arms or not any(a.animation_data and a.animation_data.action for a in arms):
            problems.append("no armature with an action")
        if not skinned:
            problems.append("no mesh is skinned to the armature")
    if not (1.0 < hi_z - lo_z < 200.0):
        problems.append(f"height {hi_z - lo_z:.2f} m: the unit scale is off")
if not any(m.name.startswith("bark") for m in materials):
    problems.append("no bark material")
if not any(m.name.startswith("leaves") for m in materials):
    problems.append("no leaf material")

# Frame the tree: bounds of every mesh in world space (the importers turn glTF's +Y up into +Z).
lo, hi = Vector((math.inf,) * 3), Vector((-math.inf,) * 3)
for obj in bpy.data.objects:
    if obj.type != "MESH":
        continue
    for corner in obj.bound_box:
        w = obj.matrix_world @ Vector(corner)
        lo = Vector(map(min, lo, w))
        hi = Vector(map(max, hi, w))
centre, extent = (lo + hi) / 2, hi - lo
radius = max(extent.length / 2, 0.1)
half_fov = math.atan(18 / 50)  # 50 mm lens on a 36 mm sensor
scene = bpy.context.scene
cam_data = bpy.data.cameras.new("camera")
cam_data.lens = 50
cam = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(cam)
direction = Vector((0.5, -1.0, 0.2)).normalized()
# Far enough that the larger of the width and the height fills about 85% of the frame.
fit = max(extent.x, extent.y, extent.z) / 2 / math.tan(half_fov) / 0.85
cam.location = centre + direction * (fit + max(extent.x, extent.y) / 2)
cam.rotation_euler = (centre - cam.location).to_track_quat("-Z", "Y").to_euler()
cam_data.clip_end = radius * 20
scene.camera = cam
sun_data = bpy.data.lights.new("sun", "SUN")
sun_data.energy = 3.0
sun_data.angle = math.radians(3)
sun = bpy.data.objects.new("sun", sun_data)
sun.rotation_euler = (math.radians(45), 0, math.radians(35))
scene.collection.objects.link(sun)
world = scene.world or bpy.data.worlds.new("world")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.55, 0.68, 0.85, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 24
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 4
scene.cycles.transparent_max_bounces = 16
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = out_png
bpy.ops.render.render(write_still=True)
print(f"rendered {out_png} ({size}x{size}, Cycles CPU, 24 samples)")

if problems:
    print("CHECK FAILED:\n  " + "\n  ".join(problems))
    sys.exit(1)
print("CHECK OK: bark has a base colour image (and a normal map unless it is the user's own); every leaf "
      "material has an image with its alpha "
      + ("linked (MTL, FBX: Alpha Blend)" if ext in (".obj", ".fbx") else "clipped (Alpha Clip)"))
