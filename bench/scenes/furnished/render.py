"""Renders the furnished room's photo and truths with Blender Cycles (issue 34).
    blender -b --factory-startup -P bench/scenes/furnished/render.py -- OUT_DIR [SAMPLES]
OUT_DIR holds gen.py's package; this writes photo.exr, photo.mask.png, photo.png and
truth/{identity,remove_bookshelf,remove_cabinet}.{exr,mask.png}. The scene is built from the
same scene.py vertex lists as room.obj. Conventions as in ../shared/data/room/README.md:
all-diffuse materials, one-sided Lambertian quad lamps (back side black, non-reflecting),
black world, pinhole camera = scene.json's K and world_to_camera, Box filter 1 px, no
clamping, no denoising; each image has its own seed (identity vs photo = the noise floor).
Masks: a separate render in which every lamp's front emits 1 and every surface is black but
occludes (no bounces, 64 samples); pixels > 1e-4 are 0, that region dilated by one pixel.
"""
import math
import os
import sys
import time

import bpy
import numpy as np
import OpenImageIO as oiio
from mathutils import Matrix

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene as S  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
OUT = argv[0]
MAX_SAMPLES = int(argv[1]) if len(argv) > 1 and argv[1].isdigit() else 1024


def node_material(name, spec):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Roughness"].default_value = 0.0
    nt.links.new(bsdf.outputs[0], out.inputs[0])
    if spec["type"] == "flat":
        bsdf.inputs["Color"].default_value = tuple(spec["rgb"]) + (1.0,)
        return m
    tc = nt.nodes.new("ShaderNodeTexCoord")  # Object coordinates = world (objects at origin)
    sep = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(tc.outputs["Object"], sep.inputs[0])
    if spec["type"] == "bricks":
        comb = nt.nodes.new("ShaderNodeCombineXYZ")
        nt.links.new(sep.outputs[spec["axes"][0]], comb.inputs[0])
        nt.links.new(sep.outputs[spec["axes"][1]], comb.inputs[1])
        br = nt.nodes.new("ShaderNodeTexBrick")
        nt.links.new(comb.outputs[0], br.inputs["Vector"])
        br.inputs["Color1"].default_value = tuple(spec["c1"]) + (1.0,)
        br.inputs["Color2"].default_value = tuple(spec["c2"]) + (1.0,)
        br.inputs["Mortar"].default_value = tuple(spec["mortar"]) + (1.0,)
        br.inputs["Scale"].default_value = 1.0
        br.inputs["Mortar Size"].default_value = spec["mortar_size"]
        br.inputs["Mortar Smooth"].default_value = 0.0
        br.inputs["Bias"].default_value = 0.0
        br.inputs["Brick Width"].default_value = spec["width"]
        br.inputs["Row Height"].default_value = spec["row"]
        nt.links.new(br.outputs["Color"], bsdf.inputs["Color"])
        return m
    # stripes: floor(coordinate / width) mod 2 selects the colour
    div = nt.nodes.new("ShaderNodeMath")
    div.operation = "DIVIDE"
    nt.links.new(sep.outputs[spec["axis"]], div.inputs[0])
    div.inputs[1].default_value = spec["width"]
    fl = nt.nodes.new("ShaderNodeMath")
    fl.operation = "FLOOR"
    nt.links.new(div.outputs[0], fl.inputs[0])
    md = nt.nodes.new("ShaderNodeMath")
    md.operation = "MODULO"
    nt.links.new(fl.outputs[0], md.inputs[0])
    md.inputs[1].default_value = 2.0
    mix = nt.nodes.new("ShaderNodeMixRGB")
    nt.links.new(md.outputs[0], mix.inputs["Fac"])
    mix.inputs["Color1"].default_value = tuple(spec["c1"]) + (1.0,)
    mix.inputs["Color2"].default_value = tuple(spec["c2"]) + (1.0,)
    nt.links.new(mix.outputs[0], bsdf.inputs["Color"])
    return m


def emitter_material(name, radiance):
    """One-sided Lambertian emitter: front (CCW) emits `radiance`, back is black."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    front = nt.nodes.new("ShaderNodeEmission")
    peak = max(max(radiance), 1e-9)
    front.inputs["Color"].default_value = tuple(c / peak for c in radiance) + (1.0,)
    front.inputs["Strength"].default_value = peak if max(radiance) > 0 else 0.0
    back = nt.nodes.new("ShaderNodeEmission")
    back.inputs["Strength"].default_value = 0.0
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(geo.outputs["Backfacing"], mix.inputs[0])
    nt.links.new(front.outputs[0], mix.inputs[1])
    nt.links.new(back.outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], out.inputs[0])
    return m


def add_mesh(name, verts, faces, material):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    me.update()
    me.materials.append(material)
    ob = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def build():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    w = bpy.data.worlds.new("black")
    w.use_nodes = True
    w.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    sc.world = w
    mats = {n: node_material(n, s) for n, s in S.MATERIALS.items()}
    objects = {}
    for name, plist in S.parts().items():
        objects[name] = [add_mesh("%s.%d" % (name, i), v, f, mats[m])
                         for i, (m, v, f) in enumerate(plist)]
    lamps = [add_mesh("lamp." + l["name"], l["vertices"], [(0, 1, 2, 3)],
                      emitter_material("emit." + l["name"], l["radiance"])) for l in S.LIGHTS]
    for ob in lamps:  # the front (CCW) normal must point down, into the room
        assert ob.data.polygons[0].normal.z < -0.999
    setup_camera(sc)
    return sc, objects, lamps


def setup_camera(sc):
    K, Rt = S.camera()
    cd = bpy.data.cameras.new("cam")
    cd.sensor_fit = "HORIZONTAL"
    cd.sensor_width = 36.0
    cd.lens = K[0][0] * cd.sensor_width / S.WIDTH
    assert abs(K[0][0] - K[1][1]) < 1e-9 and abs(K[0][2] - (S.WIDTH - 1) / 2) < 1e-9
    cam = bpy.data.objects.new("cam", cd)
    sc.collection.objects.link(cam)
    R = np.array([r[:3] for r in Rt])
    t = np.array([r[3] for r in Rt])
    c2w = np.eye(4)
    # OpenCV camera (x right, y down, z forward) -> Blender camera (x right, y up, z back)
    c2w[:3, :3] = R.T @ np.diag([1.0, -1.0, -1.0])
    c2w[:3, 3] = -R.T @ t
    cam.matrix_world = Matrix(c2w.tolist())
    sc.camera = cam
    r = sc.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = S.WIDTH, S.HEIGHT, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0


def cycles(sc, samples, bounces, adaptive, seed):
    sc.render.engine = "CYCLES"
    c = sc.cycles
    c.device = "CPU"
    sc.render.threads_mode = "FIXED"
    sc.render.threads = 2
    c.samples = samples
    c.use_adaptive_sampling = adaptive
    c.adaptive_threshold = 0.01
    c.adaptive_min_samples = samples // 2
    c.max_bounces = c.diffuse_bounces = bounces
    c.glossy_bounces = c.transmission_bounces = c.volume_bounces = 0
    c.use_denoising = False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = seed
    sc.view_settings.view_transform = "Standard"
    im = sc.render.image_settings
    im.file_format = "OPEN_EXR"
    im.color_mode = "RGB"
    im.color_depth = "32"
    im.exr_codec = "ZIP"


def render(sc, path):
    sc.render.filepath = path
    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    return time.time() - t0


def write_mask(exr, png):
    img = oiio.ImageBuf(exr).get_pixels(oiio.FLOAT)
    lit = (img[:, :, :3].max(axis=2) > 1e-4)
    pad = np.pad(lit, 1)
    h, w = lit.shape
    dil = np.zeros_like(lit)
    for dy in range(3):
        for dx in range(3):
            dil |= pad[dy:dy + h, dx:dx + w]
    out = oiio.ImageBuf(oiio.ImageSpec(w, h, 1, oiio.UINT8))
    out.set_pixels(oiio.ROI(0, w, 0, h), np.where(dil, 0, 255).astype(np.uint8)[:, :, None])
    assert out.write(png), out.geterror()
    return int(dil.sum())


def masks(sc, objects, lamps, shots):
    black = bpy.data.materials.new("black")
    black.use_nodes = True
    nt = black.node_tree
    nt.nodes.clear()
    e = nt.nodes.new("ShaderNodeEmission")
    e.inputs["Strength"].default_value = 0.0
    nt.links.new(e.outputs[0], nt.nodes.new("ShaderNodeOutputMaterial").inputs[0])
    for obs in objects.values():
        for ob in obs:
            ob.data.materials[0] = black
    for ob, l in zip(lamps, S.LIGHTS):
        ob.data.materials[0] = emitter_material("mask." + l["name"], [1.0, 1.0, 1.0])
    cycles(sc, 64, 0, False, 7)
    for removed, png in shots:
        for name, obs in objects.items():
            for ob in obs:
                ob.hide_render = name in removed
        tmp = os.path.join(OUT, "mask_tmp.exr")
        render(sc, tmp)
        n = write_mask(tmp, png)
        os.remove(tmp)
        print("mask %s: %d pixels 0" % (png, n))


def albedo(sc, objects, lamps, shots):
    """Per-pixel albedo (as the other packages' truth/albedo.exr): each material's diffuse colour
    turned into an emission of that colour, no bounces, lamps black. 64 samples, Box 1 px."""
    for mat in bpy.data.materials:
        nt = mat.node_tree
        bsdf = next((n for n in nt.nodes if n.bl_idname == "ShaderNodeBsdfDiffuse"), None)
        if bsdf is None:
            continue
        e = nt.nodes.new("ShaderNodeEmission")
        col = bsdf.inputs["Color"]
        if col.is_linked:
            nt.links.new(col.links[0].from_socket, e.inputs["Color"])
        else:
            e.inputs["Color"].default_value = col.default_value
        out = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
        nt.links.new(e.outputs[0], out.inputs[0])
    for ob in lamps:
        ob.hide_render = True
    cycles(sc, 64, 0, False, 5)
    for removed, path in shots:
        for name, obs in objects.items():
            for ob in obs:
                ob.hide_render = name in removed
        render(sc, path)
    for ob in lamps:
        ob.hide_render = False


def main():
    sc, objects, lamps = build()
    os.makedirs(os.path.join(OUT, "truth"), exist_ok=True)
    shots = [([], "photo", 1)] + [(e.get("remove_objects", []), "truth/" + n, 11 + i)
                                  for i, (n, e) in enumerate(S.EDITS.items())]
    times = []
    for removed, name, seed in ([] if "--albedo" in argv else shots):
        for n, obs in objects.items():
            for ob in obs:
                ob.hide_render = n in removed
        cycles(sc, MAX_SAMPLES, 32, True, seed)
        dt = render(sc, os.path.join(OUT, name + ".exr"))
        times.append("%s %.0f s" % (name, dt))
        print("rendered %s in %.0f s" % (name, dt))
    if "--albedo" in argv:  # the albedo of each shot (diagnostics), then stop
        os.makedirs(os.path.join(OUT, "albedo"), exist_ok=True)
        albedo(sc, objects, lamps, [(r, os.path.join(OUT, "albedo", n.split("/")[-1] + ".exr"))
                                    for r, n, _ in shots])
        return
    masks(sc, objects, lamps,
          [(r, os.path.join(OUT, n + ".mask.png")) for r, n, _ in shots])
    print("render times: " + ", ".join(times))


main()
