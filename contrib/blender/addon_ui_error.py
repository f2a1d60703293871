"""Blender's window after a bad value in the seasynth panel, for docs/blender-error.png:
the error report of a setting's update reaches the interface. Needs a display: run it
under Xvfb, with xdotool (which closes the splash screen):

    PYTHONPATH=DIR xvfb-run -a -s "-screen 0 1600x900x24" blender --factory-startup \
        --python contrib/blender/addon_ui_error.py -- OUT.png

DIR holds the seasynth module (docs/blender.md, Install). Add → seasynth sea (preset
`moderate`, 256² vertices over 256 m, Material Preview), then the wind speed set to −3 m/s
as the panel sets it (an update in the window's context); the 1600 × 900 window is saved
at 960 × 540. Prints the panel's error text.
"""

import math
import os
import subprocess
import sys

import bpy
from mathutils import Euler, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import seasynth_addon  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
out = os.path.abspath(args[0] if args else "blender-error.png")
seasynth_addon.register()


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    return win, area


def setup():
    subprocess.run(["xdotool", "key", "Escape"], check=True)  # the splash screen
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    win, area = view3d()
    region = next(r for r in area.regions if r.type == "WINDOW")
    bpy.context.scene.render.fps = 24
    bpy.context.scene.frame_set(12)
    with bpy.context.temp_override(window=win, area=area, region=region):
        bpy.ops.mesh.seasynth_sea_add(preset="moderate", size=256, extent=256.0)
    space = area.spaces[0]
    space.shading.type = "MATERIAL"
    r3d = space.region_3d
    r3d.view_location = Vector((128.0, 128.0, 0.0))
    r3d.view_distance = 260.0
    r3d.view_rotation = Euler((math.radians(62), 0.0, math.radians(35))).to_quaternion()


def bad_value():
    win, area = view3d()
    region = next(r for r in area.regions if r.type == "UI")
    with bpy.context.temp_override(window=win, area=area, region=region):
        bpy.context.active_object.seasynth.wind_speed = -3.0
    print("panel error:", bpy.context.active_object.seasynth.error)


def shot():
    win, area = view3d()
    with bpy.context.temp_override(window=win, area=area):
        bpy.ops.screen.screenshot(filepath=out)
    img = bpy.data.images.load(out)
    img.scale(960, 540)
    img.save_render(out)
    print(f"wrote {out}")


bpy.app.timers.register(setup, first_interval=1.0)
bpy.app.timers.register(bad_value, first_interval=10.0)
bpy.app.timers.register(shot, first_interval=11.5)


def quit_blender():
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(quit_blender, first_interval=13.0)
