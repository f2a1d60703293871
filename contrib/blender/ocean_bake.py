"""Bakes Blender's Ocean modifier to an EXR sequence, headless, for `seasynth bench
--sequence`: a PM sea of 15 m/s over `size` m, `resolution` (32: 1024² samples),
choppiness 1, foam on, frames 1..frames.

    blender -b --factory-startup --python contrib/blender/ocean_bake.py -- DIR [FRAMES [RESOLUTION [SIZE]]]

Prints `baked N frames in S s`; the files are DIR/disp_0001.exr … and foam_0001.exr ….
"""
import sys
import time

import bpy

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out = args[0]
frames = int(args[1]) if len(args) > 1 else 48
resolution = int(args[2]) if len(args) > 2 else 32
size = float(args[3]) if len(args) > 3 else 1024.0

bpy.ops.mesh.primitive_plane_add()
obj = bpy.context.active_object
mod = obj.modifiers.new("Ocean", "OCEAN")
mod.resolution = resolution
mod.spatial_size = int(size)
mod.spectrum = "PIERSON_MOSKOWITZ"
mod.wind_velocity = 15.0
mod.choppiness = 1.0
mod.use_foam = True
mod.frame_start = 1
mod.frame_end = frames
mod.filepath = out
started = time.time()
bpy.ops.object.ocean_bake(modifier="Ocean")
print(f"baked {frames} frames in {time.time() - started:.3f} s")
