"""seasynth sea: a live, physically scaled ocean in Blender, computed by the seasynth
Python module (heights in meters, choppy displacement, foam and normals), with a bake to
the EXR sequence `seasynth animate` writes. See docs/blender.md."""

bl_info = {
    "name": "seasynth sea",
    "author": "seasynth contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Add > Mesh > seasynth sea; View3D > Sidebar > seasynth",
    "description": "A live ocean surface in meters from the seasynth module: choppy waves, foam, normals, EXR bake",
    "category": "Add Mesh",
}

if "bpy" in locals():
    import importlib

    for _m in (engine, props, material, sea, baked, operators, ui):  # noqa: F821
        importlib.reload(_m)
else:
    from . import engine, props, material, sea, baked, operators, ui

import bpy  # noqa: E402


def register():
    props.register()
    operators.register()
    ui.register()
    handlers = bpy.app.handlers
    if sea.on_frame_change not in handlers.frame_change_pre:
        handlers.frame_change_pre.append(sea.on_frame_change)
    if sea.on_load not in handlers.load_post:
        handlers.load_post.append(sea.on_load)


def unregister():
    handlers = bpy.app.handlers
    if sea.on_frame_change in handlers.frame_change_pre:
        handlers.frame_change_pre.remove(sea.on_frame_change)
    if sea.on_load in handlers.load_post:
        handlers.load_post.remove(sea.on_load)
    sea.clear()
    ui.unregister()
    operators.unregister()
    props.unregister()
