"""Cycles truths of the window room (gen.py's package), as data/courtyard/README.md renders its own:
pinhole camera = scene.json K and world_to_camera (OpenCV), Box filter 1 px, all diffuse, 32
bounces, no clamping, no denoising; the sun a Cycles Sun lamp of strength = irradiance and
diameter `angle`; the sky the exact SH9 world of /work/shared/tools/cycles/sh9.py (a rotated sky
from rotated coefficients). Checked conventions: /work/shared/tools/cycles/lights_check.py.
Run: blender -b --factory-startup -P render.py -- PKG SAMPLES SEED NAME OUT.exr
  NAME: an edit of PKG/edits (its lights applied), or "mask" (the world emits 1, surfaces black,
  no bounce: a pixel that sees the sky is not 0)."""
import json, math, os, sys
import bpy
from mathutils import Matrix, Vector

SH9_TOOLS = os.environ.get("RELIGHT_CYCLES_TOOLS", "/work/shared/tools/cycles")
sys.path.insert(0, SH9_TOOLS)
import sh9 as SH  # noqa: E402
import numpy as np  # noqa: E402

pkg, samples, seed, name, out = sys.argv[sys.argv.index("--") + 1:][:5]
samples, seed = int(samples), int(seed)
scene_json = json.load(open(os.path.join(pkg, "scene.json")))
geometry = json.load(open(os.path.join(pkg, "geometry.json")))

bpy.ops.wm.read_factory_settings(use_empty=True)
sc = bpy.context.scene
sc.render.engine = "CYCLES"
c = sc.cycles
c.device = "CPU"; c.samples = samples; c.use_adaptive_sampling = False; c.seed = seed
c.max_bounces = 32; c.diffuse_bounces = 32; c.glossy_bounces = 0; c.transmission_bounces = 0
c.transparent_max_bounces = 0; c.use_denoising = False
c.sample_clamp_direct = 0; c.sample_clamp_indirect = 0; c.light_sampling_threshold = 0.0
c.pixel_filter_type = "BOX"; c.filter_width = 1.0
cam = scene_json["camera"]
sc.render.resolution_x = cam["width"]; sc.render.resolution_y = cam["height"]
sc.render.resolution_percentage = 100
sc.view_settings.view_transform = "Standard"
im = sc.render.image_settings; im.file_format = "OPEN_EXR"; im.color_depth = "32"
sc.render.threads_mode = "FIXED"; sc.render.threads = 2

mask = name == "mask"
for oname, o in geometry.items():
    verts, faces = [], []
    for f in o["faces"]:
        faces.append(list(range(len(verts), len(verts) + len(f)))); verts += [tuple(p) for p in f]
    me = bpy.data.meshes.new(oname); me.from_pydata(verts, [], faces); me.update()
    ob = bpy.data.objects.new(oname, me); sc.collection.objects.link(ob)
    m = bpy.data.materials.new(oname); m.use_nodes = True
    nt = m.node_tree; nt.nodes.clear()
    mo = nt.nodes.new("ShaderNodeOutputMaterial"); b = nt.nodes.new("ShaderNodeBsdfDiffuse")
    rho = (0, 0, 0) if mask else o["reflectance"]
    b.inputs["Color"].default_value = (rho[0], rho[1], rho[2], 1)
    nt.links.new(b.outputs[0], mo.inputs[0]); me.materials.append(m)

# The camera: OpenCV (x right, y down, z forward) to Blender's (x right, y up, looking along -z).
W2C = np.array(cam["world_to_camera"] + [[0, 0, 0, 1]], float)
C2W = np.linalg.inv(W2C) @ np.diag([1, -1, -1, 1])
cd = bpy.data.cameras.new("cam"); cd.sensor_fit = "HORIZONTAL"; cd.sensor_width = 36.0
K = cam["K"]
cd.lens = K[0][0] * cd.sensor_width / cam["width"]
# A principal point off the centre (pixel centres at integers: the centre is (W-1)/2).
cd.shift_x = -(K[0][2] - (cam["width"] - 1) / 2) / cam["width"]
cd.shift_y = (K[1][2] - (cam["height"] - 1) / 2) / cam["width"]
co = bpy.data.objects.new("cam", cd); sc.collection.objects.link(co)
co.matrix_world = Matrix(C2W.tolist()); sc.camera = co

# The lights after the edit (the scene's, then the edit's fields).
lights = {l["name"]: dict(l) for l in scene_json["lights"]}
edit = {} if mask else json.load(open(os.path.join(pkg, "edits", name + ".json")))
for lname, e in edit.get("lights", {}).items():
    l = lights[lname]
    if "direction" in e: l["direction"] = e["direction"]
    if "irradiance" in e: l["irradiance"] = e["irradiance"]
    if "sh9" in e: l["sh9"] = e["sh9"]
    if "rotate" in e: l["sh9"] = SH.rotate(l["sh9"], e["rotate"]["axis"], e["rotate"]["degrees"]).tolist()
    if "scale" in e:
        k = e["scale"]
        if l["type"] == "environment": l["sh9"] = (np.asarray(l["sh9"]) * k).tolist()
        else: l["irradiance"] = [k * x for x in l["irradiance"]]
world = bpy.data.worlds.new("w"); sc.world = world
if mask:
    world.use_nodes = True; world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    c.max_bounces = 0
else:
    SH.world_nodes(world, lights["sky"]["sh9"])
    sun = lights["sun"]; E = sun["irradiance"]; Em = max(E)
    if Em > 0:
        L = bpy.data.lights.new("sun", "SUN"); L.energy = Em; L.color = [x / Em for x in E]
        L.angle = math.radians(sun["angle"])
        ob = bpy.data.objects.new("sun", L); sc.collection.objects.link(ob)
        d = Vector(sun["direction"]).normalized()
        ob.rotation_euler = (-d).to_track_quat("-Z", "Y").to_euler()  # light travels along -d
sc.render.filepath = out
bpy.ops.render.render(write_still=True)
print("wrote", out)
