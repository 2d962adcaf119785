# Renders Sylva GLB exports one after another in Blender's Cycles, as an artist would import them
# (Blender's own glTF importer, factory settings), under a sun and a sky-coloured world, and
# measures "black leaves": the share of leaf pixels darker than a threshold. Issue 23 asks that
# every species renders in Cycles without black leaves; scripts/blender-sheet.sh runs this and
# montages the contact sheet (out/blender_species.png by default).
#
#   blender -b --factory-startup --python tools/blender/render_sheet.py -- \
#       OUT_DIR [--size 320] [--samples 24] [--transparent-bounces N] [--control] TREE.glb [TREE.glb ...]
#
# Writes OUT_DIR/NAME.png (RGBA, transparent film: the world lights the tree but is not drawn),
# OUT_DIR/NAME_leaves.png (the leaf mask from the material index pass) and OUT_DIR/leaves.json,
# and prints one line per tree. --control also renders the first tree with its leaves black from
# behind (the failure this is for), to show the measure finds black leaves when there are some.
# --transparent-bounces sets Cycles' transparent bounce limit (Blender's default, 8, unless given):
# a path that crosses more cut-away card parts than that ends black.
#
# How the measure works: every material whose name starts with "leaves" (Sylva's leaf materials)
# gets pass index 1. Cycles' material index pass (written only by surfaces whose alpha reaches the
# view layer's alpha threshold, 0.5, so the cut-away parts of a leaf card do not count) goes through
# an ID Mask node without antialiasing to a PNG: the leaf pixels. Cycles' diffuse direct and
# indirect light passes (the light a surface receives, its own colour divided out) are added and
# written as linear EXR: a leaf pixel is *unlit* ("black") where that light is under UNLIT, 0.03,
# under 5% of what a leaf facing the open sky gets from this world (0.66) and far under a sunlit
# one (about 1.6). Measuring light rather than the pixel's colour keeps a dark-green fir from
# counting as black. The display colour is reported too (share of leaf pixels with a Rec. 709
# luma under 0.05 and 0.10 of the sRGB, Filmic PNG).
import glob
import json
import math
import os
import sys
import time

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses the alias NumPy 1.24 removed

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402

THRESHOLDS = (0.05, 0.10)  # display luma
UNLIT = 0.03  # received diffuse light, linear
SKY = (0.55, 0.68, 0.85, 1.0)


def parse(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    opt = {"size": 320, "samples": 24, "transparent_bounces": None, "control": False, "trees": []}
    out = None
    i = 0
    while i < len(args):
        a = args[i]
        if a == "--size":
            opt["size"] = int(args[i + 1])
            i += 1
        elif a == "--samples":
            opt["samples"] = int(args[i + 1])
            i += 1
        elif a == "--transparent-bounces":
            opt["transparent_bounces"] = int(args[i + 1])
            i += 1
        elif a == "--control":
            opt["control"] = True
        elif out is None:
            out = a
        else:
            opt["trees"].append(os.path.abspath(a))
        i += 1
    if out is None or not opt["trees"]:
        print("usage: blender -b --factory-startup --python render_sheet.py -- OUT_DIR [--size N] [--samples N] [--transparent-bounces N] [--control] TREE.glb ...")
        sys.exit(2)
    opt["out"] = os.path.abspath(out)
    return opt


def world_points(max_points=200000):
    """World-space vertices of every mesh, subsampled to about max_points."""
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    total = sum(len(o.data.vertices) for o in meshes)
    stride = max(1, math.ceil(total / max_points))
    pts = []
    for o in meshes:
        n = len(o.data.vertices)
        co = numpy.empty(n * 3, dtype=numpy.float64)
        o.data.vertices.foreach_get("co", co)
        co = co.reshape(n, 3)[::stride]
        m = numpy.array(o.matrix_world, dtype=numpy.float64)
        pts.append(co @ m[:3, :3].T + m[:3, 3])
    return numpy.concatenate(pts) if pts else numpy.zeros((1, 3))


def fit_camera(scene, size):
    """The viewer's iso view (tools/viewer/page/viewer.js): 35 deg elevation, 45 deg azimuth, 30 deg
    field of view, the tree's vertices filling 90% of the frame. glTF's +Y up is Blender's +Z and
    glTF's +Z is Blender's -Y."""
    el, az = math.radians(35), math.radians(45)
    d = Vector((math.cos(el) * math.sin(az), -math.cos(el) * math.cos(az), math.sin(el)))
    up = Vector((0, 0, 1))
    right = up.cross(d).normalized()
    cam_up = d.cross(right).normalized()
    pts = world_points()
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = (lo + hi) / 2
    q = pts - c
    px, py, pz = q @ numpy.array(right), q @ numpy.array(cam_up), q @ numpy.array(d)
    t = math.tan(math.radians(15)) * 0.9
    ox = oy = 0.0
    dist = 1.0
    for _ in range(3):
        dist = float(max((numpy.abs(px - ox) / t + pz).max(), (numpy.abs(py - oy) / t + pz).max()))
        depth = dist - pz
        sx, sy = (px - ox) / depth, (py - oy) / depth
        ox += (sx.min() + sx.max()) / 2 * dist
        oy += (sy.min() + sy.max()) / 2 * dist
    target = Vector(c) + right * ox + cam_up * oy
    cam_data = bpy.data.cameras.new("camera")
    cam_data.angle = math.radians(30)
    radius = float(numpy.linalg.norm(hi - lo))
    cam_data.clip_start = max(0.01, dist - radius * 1.5)
    cam_data.clip_end = dist + radius * 1.5
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    cam.location = target + d * dist
    cam.rotation_euler = (-d).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    # Sun from the upper left, in front of the tree as seen from the camera (as the viewer's).
    sun_dir = (d - right + up * 1.5).normalized()  # from the tree toward the sun
    sun_data = bpy.data.lights.new("sun", "SUN")
    sun_data.energy = 3.0
    sun_data.angle = math.radians(3)
    sun = bpy.data.objects.new("sun", sun_data)
    sun.rotation_euler = (-sun_dir).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(sun)


def setup_render(scene, size, samples, transparent_bounces, out_dir, name):
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = SKY
    bg.inputs["Strength"].default_value = 1.0
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    if transparent_bounces is not None:
        scene.cycles.transparent_max_bounces = transparent_bounces
    scene.render.film_transparent = True
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = os.path.join(out_dir, f"{name}.png")
    layer = scene.view_layers[0]
    layer.use_pass_material_index = True
    layer.pass_alpha_threshold = 0.5
    layer.use_pass_diffuse_direct = True
    layer.use_pass_diffuse_indirect = True
    scene.use_nodes = True
    tree = scene.node_tree
    for n in list(tree.nodes):
        tree.nodes.remove(n)
    rl = tree.nodes.new("CompositorNodeRLayers")
    comp = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["Image"], comp.inputs["Image"])
    tree.links.new(rl.outputs["Alpha"], comp.inputs["Alpha"])
    mask = tree.nodes.new("CompositorNodeIDMask")
    mask.index = 1
    mask.use_antialiasing = False
    tree.links.new(rl.outputs["IndexMA"], mask.inputs["ID value"])
    fo = tree.nodes.new("CompositorNodeOutputFile")
    fo.base_path = out_dir
    fo.format.file_format = "PNG"
    fo.format.color_mode = "BW"
    fo.file_slots[0].path = f"{name}_leaves_"
    tree.links.new(mask.outputs["Alpha"], fo.inputs[0])
    light = tree.nodes.new("CompositorNodeMixRGB")
    light.blend_type = "ADD"
    light.use_clamp = False
    light.inputs[0].default_value = 1.0
    tree.links.new(rl.outputs["DiffDir"], light.inputs[1])
    tree.links.new(rl.outputs["DiffInd"], light.inputs[2])
    fl = tree.nodes.new("CompositorNodeOutputFile")
    fl.base_path = out_dir
    fl.format.file_format = "OPEN_EXR"
    fl.format.color_mode = "RGB"
    fl.format.color_depth = "16"
    fl.file_slots[0].path = f"{name}_light_"
    tree.links.new(light.outputs["Image"], fl.inputs[0])


def load_pixels(path):
    img = bpy.data.images.load(path)
    w, h = img.size
    px = numpy.empty(w * h * 4, dtype=numpy.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return px.reshape(h, w, 4)


def take(out_dir, prefix, ext):
    """The File Output node appends the frame number; rename to NAME_what.ext."""
    found = sorted(glob.glob(os.path.join(out_dir, f"{prefix}_*.{ext}")))
    dest = os.path.join(out_dir, f"{prefix}.{ext}")
    os.replace(found[-1], dest)
    return dest


def luma_of(px):
    return 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]


def measure(out_dir, name):
    beauty = load_pixels(os.path.join(out_dir, f"{name}.png"))
    leaf = load_pixels(take(out_dir, f"{name}_leaves", "png"))[..., 0] >= 0.5
    light = luma_of(load_pixels(take(out_dir, f"{name}_light", "exr")))
    luma = luma_of(beauty)
    tree = beauty[..., 3] >= 0.5
    leaf &= tree
    n = max(1, int(leaf.sum()))
    r = {"leaf_px": int(leaf.sum()), "tree_px": int(tree.sum()), "unlit_threshold": UNLIT,
         "leaf_unlit": float((leaf & (light < UNLIT)).sum() / n)}
    for t in THRESHOLDS:
        r[f"leaf_dark_{t:.2f}"] = float((leaf & (luma < t)).sum() / n)
    r["leaf_light_p05"] = float(numpy.percentile(light[leaf], 5)) if leaf.any() else None
    r["leaf_light_median"] = float(numpy.median(light[leaf])) if leaf.any() else None
    r["leaf_luma_median"] = float(numpy.median(luma[leaf])) if leaf.any() else None
    return r


def render_one(path, opt, name, control=False):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    t0 = time.time()
    bpy.ops.import_scene.gltf(filepath=path)
    scene = bpy.context.scene
    materials = {s.material for o in bpy.data.objects if o.type == "MESH" for s in o.material_slots if s.material}
    leaves = [m for m in materials if m.name.startswith("leaves")]
    for m in materials:
        m.pass_index = 1 if m in leaves else 0
    if control:
        # The failure the measure is for: leaves black from behind. On back faces each leaf
        # material's base colour is mixed to black (Geometry > Backfacing); its alpha stays.
        for m in leaves:
            nt = m.node_tree
            bsdf = next(n for n in nt.nodes if n.type == "BSDF_PRINCIPLED")
            base = bsdf.inputs["Base Color"]
            geo = nt.nodes.new("ShaderNodeNewGeometry")
            mix = nt.nodes.new("ShaderNodeMixRGB")
            nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
            if base.is_linked:
                nt.links.new(base.links[0].from_socket, mix.inputs["Color1"])
            else:
                mix.inputs["Color1"].default_value = base.default_value
            mix.inputs["Color2"].default_value = (0, 0, 0, 1)
            nt.links.new(mix.outputs["Color"], base)
    fit_camera(scene, opt["size"])
    setup_render(scene, opt["size"], opt["samples"], opt["transparent_bounces"], opt["out"], name)
    t1 = time.time()
    bpy.ops.render.render(write_still=True)
    t2 = time.time()
    r = measure(opt["out"], name)
    r.update({"name": name, "leaf_materials": sorted(m.name for m in leaves), "import_s": round(t1 - t0, 1), "render_s": round(t2 - t1, 1),
              "triangles": sum(sum(len(p.vertices) - 2 for p in o.data.polygons) for o in bpy.data.objects if o.type == "MESH")})
    if not leaves:
        r["problem"] = "no leaf material (none named leaves*)"
    return r


def main():
    opt = parse(sys.argv)
    os.makedirs(opt["out"], exist_ok=True)
    results = []
    jobs = [(p, os.path.splitext(os.path.basename(p))[0], False) for p in opt["trees"]]
    if opt["control"]:
        jobs.append((opt["trees"][0], os.path.splitext(os.path.basename(opt["trees"][0]))[0] + "_control_black_backs", True))
    for path, name, control in jobs:
        try:
            r = render_one(path, opt, name, control)
        except Exception as e:  # one broken file must not stop the sheet
            r = {"name": name, "problem": f"{type(e).__name__}: {e}"}
        r["control"] = control
        results.append(r)
        if "leaf_px" in r:
            print(f"SHEET {name}: unlit leaf px (light < {UNLIT}) {100 * r['leaf_unlit']:.2f}% of {r['leaf_px']}; "
                  f"leaf light p5 {r['leaf_light_p05']:.3f} median {r['leaf_light_median']:.3f}; "
                  f"dark display px (luma < 0.05) {100 * r['leaf_dark_0.05']:.2f}%, (< 0.10) {100 * r['leaf_dark_0.10']:.2f}%; "
                  f"import {r['import_s']} s, render {r['render_s']} s", flush=True)
        else:
            print(f"SHEET {name}: FAILED {r.get('problem')}", flush=True)
    with open(os.path.join(opt["out"], "leaves.json"), "w") as f:
        json.dump({"size": opt["size"], "samples": opt["samples"], "transparent_max_bounces": bpy.context.scene.cycles.transparent_max_bounces, "thresholds": THRESHOLDS, "blender": bpy.app.version_string,
                   "trees": results}, f, indent=2)


main()
