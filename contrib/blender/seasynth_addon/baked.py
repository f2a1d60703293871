"""The baked sea: the object reads the EXR sequence its bake wrote, as
`contrib/blender/seasynth_import.py` imports one: the mesh becomes the flat grid of
sample positions and a Displace modifier adds each file's vector (Direction RGB to XYZ,
Space Local, Midlevel 0, Strength 1, the image Non-Color, Alpha None, not clamped); the
material reads the foam and normal sequences. Scene frame F shows file number F (the bake
numbers its files from the scene's start frame), the frame the live sea shows at F.
"""

import json
import os

import bpy
import numpy as np

from . import material, sea

MODIFIER = "seasynth bake"


def read_sequence(folder):
    with open(os.path.join(folder, "sequence.json"), encoding="utf-8") as f:
        doc = json.load(f)
    files = doc["files"]

    def pattern(suffix):
        return next((p for p in files if p.endswith(suffix)), None)

    return {
        "frames": int(doc["frames"]),
        "start": int(doc.get("start_frame", 1)),
        "disp": pattern(".disp.exr"),
        "foam": pattern(".foam.exr"),
        "normal": pattern(".normal.exr"),
        "params": doc.get("params", {}),
    }


def file_of(folder, pattern, number):
    return os.path.join(folder, pattern.replace("{k}", f"{number:05d}"))


def _sequence(path, name, alpha_mode):
    img = bpy.data.images.load(path, check_existing=False)
    img.name = name
    img.source = "SEQUENCE"
    img.colorspace_settings.name = "Non-Color"
    img.alpha_mode = alpha_mode
    return img


def _set_user(user, seq):
    """Scene frame F shows file number F: Blender shows file (F − frame_start + 1 +
    frame_offset) for F in frame_start … frame_start + frames − 1."""
    user.frame_start = seq["start"]
    user.frame_offset = seq["start"] - 1
    user.frame_duration = seq["frames"]
    user.use_auto_refresh = True
    user.use_cyclic = False


def link(obj, folder, scene):
    """Switches `obj` to the sequence in `folder`."""
    seq = read_sequence(folder)
    if seq["disp"] is None:
        raise ValueError(f"{folder}: the sequence has no disp.exr files")
    st = sea.state_of(obj, scene)
    me = obj.data
    seamless = obj.seasynth.seamless
    sea.ensure_topology(me, st, seamless)
    x, y = st.base(seamless)
    flat = np.stack([x, y, np.zeros_like(x)], axis=1).astype(np.float32)
    me.vertices.foreach_set("co", flat.ravel())
    sea._drop_attr(me, sea.FOAM_ATTR)
    sea._drop_attr(me, sea.NORMAL_ATTR)
    me.update()
    name = obj.name
    first = file_of(folder, seq["disp"], seq["start"])
    img = _sequence(first, name + ".disp", "NONE")
    tex = bpy.data.textures.new(name + ".disp", type="IMAGE")
    tex.image = img
    tex.use_clamp = False
    tex.use_alpha = False
    tex.use_mipmap = False
    tex.use_interpolation = True
    tex.filter_size = 1.0
    # Repeat: the closing vertices of a seamless tile read the first texels again.
    tex.extension = "REPEAT"
    _set_user(tex.image_user, seq)
    mod = obj.modifiers.get(MODIFIER) or obj.modifiers.new(MODIFIER, "DISPLACE")
    # First in the stack, so the artist's own modifiers see the displaced sea.
    if obj.modifiers[0] != mod:
        try:
            with bpy.context.temp_override(object=obj, active_object=obj):
                bpy.ops.object.modifier_move_to_index(modifier=mod.name, index=0)
        except RuntimeError:
            pass  # stays last: the artist can drag it up
    mod.texture = tex
    mod.texture_coords = "UV"
    mod.uv_layer = me.uv_layers[0].name
    mod.direction = "RGB_TO_XYZ"
    mod.space = "LOCAL"
    mod.mid_level = 0.0
    mod.strength = 1.0
    mat = material.material_of(obj)
    if mat is not None:
        nodes = mat.node_tree.nodes
        for node, key in (("Foam Sequence", "foam"), ("Normal Sequence", "normal")):
            n = nodes.get(node)
            if n is None:
                continue
            if seq[key]:
                n.image = _sequence(file_of(folder, seq[key], seq["start"]), f"{name}.{key}", "STRAIGHT")
                _set_user(n.image_user, seq)
            else:
                n.image = None
    s = obj.seasynth
    with sea.suspended():
        s.mode = "BAKED"
        s.baked_dir = folder
    material.update_for(obj)
    return seq


def unlink(obj):
    """Back to the live sea: the Displace modifier and the sequences go."""
    mod = obj.modifiers.get(MODIFIER)
    if mod is not None:
        tex = mod.texture
        obj.modifiers.remove(mod)
        if tex is not None and tex.users == 0:
            img = tex.image
            bpy.data.textures.remove(tex)
            if img is not None and img.users == 0:
                bpy.data.images.remove(img)
    mat = material.material_of(obj)
    if mat is not None:
        for node in ("Foam Sequence", "Normal Sequence"):
            n = mat.node_tree.nodes.get(node)
            if n is not None and n.image is not None:
                img, n.image = n.image, None
                if img.users == 0:
                    bpy.data.images.remove(img)
    s = obj.seasynth
    with sea.suspended():
        s.mode = "LIVE"
    material.update_for(obj)
