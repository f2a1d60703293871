"""Renders the add-on's sea headless with Eevee, for docs/blender-eevee.png.

    PYTHONPATH=DIR blender -b --factory-startup --python contrib/blender/addon_screenshot.py -- OUT.png [SIZE [FRAME [ENGINE]]]

DIR holds the seasynth module (docs/blender.md, Install). The sea: Add → seasynth sea with
the `moderate` preset (JONSWAP, 10 m/s, choppiness 0.8) at SIZE² vertices (default 512)
over 256 m, foam and normals on, the add-on's water material, Seamless Edges on and the tile
repeated 3 × 3 by Array modifiers, under a sun and a sky, seen from 10 m above the water; scene frame FRAME (default 1) at 24 fps. 960 × 540 pixels,
Eevee; ENGINE `cycles` renders with Cycles instead (64 samples on the CPU, no denoiser:
Debian's build has none).
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import seasynth_addon  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
out = os.path.abspath(args[0] if args else "blender-eevee.png")
size = int(args[1]) if len(args) > 1 else 512
frame = int(args[2]) if len(args) > 2 else 1
engine = args[3] if len(args) > 3 else "eevee"

seasynth_addon.register()
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
scene = bpy.context.scene
scene.render.fps, scene.render.fps_base = 24, 1.0
scene.frame_start, scene.frame_end = 1, 48
scene.frame_set(frame)
bpy.ops.mesh.seasynth_sea_add(preset="moderate", size=size, extent=256.0)
sea = bpy.context.active_object
sea.seasynth.foam_amount = 3.0
sea.seasynth.seamless = True
# Three tiles by three: the seamless tile repeats without a seam.
for axis, name in ((0, "x"), (1, "y")):
    arr = sea.modifiers.new("tiles " + name, "ARRAY")
    arr.count = 3
    arr.use_relative_offset = False
    arr.use_constant_offset = True
    arr.constant_offset_displace = (256.0, 0.0, 0.0) if axis == 0 else (0.0, 256.0, 0.0)

cam_data = bpy.data.cameras.new("camera")
cam_data.lens = 28
cam_data.clip_end = 2000
cam = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(cam)
cam.location = (200.0, 180.0, 10.0)
cam.rotation_euler = (math.radians(74), 0.0, math.radians(-40))
scene.camera = cam

sun_data = bpy.data.lights.new("sun", "SUN")
sun_data.energy = 4.0
sun_data.angle = math.radians(1.0)
sun = bpy.data.objects.new("sun", sun_data)
sun.rotation_euler = (math.radians(65), 0.0, math.radians(160))
scene.collection.objects.link(sun)

world = scene.world or bpy.data.worlds.new("world")
scene.world = world
world.use_nodes = True
nodes = world.node_tree.nodes
sky = nodes.new("ShaderNodeTexSky")
sky.sky_type = "NISHITA"
sky.sun_elevation = math.radians(25)
sky.sun_rotation = math.radians(250)
bg = nodes["Background"]
bg.inputs["Strength"].default_value = 0.35
world.node_tree.links.new(sky.outputs["Color"], bg.inputs["Color"])

if engine == "cycles":
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 64
    scene.cycles.use_denoising = False
else:
    scene.render.engine = "BLENDER_EEVEE"
    scene.eevee.taa_render_samples = 32
    scene.eevee.use_ssr = True
scene.view_settings.view_transform = "Filmic"
scene.view_settings.look = "Medium High Contrast"
scene.render.resolution_x, scene.render.resolution_y = 960, 540
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print(f"wrote {out}")
