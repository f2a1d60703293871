"""Import a seasynth displacement sequence into Blender (3.x and later).

Builds a grid with one vertex per sample of the sequence, placed where seasynth put the
samples (corners or texel centres, from `sequence.json`), and displaces it by the
`frame_NNNNN.disp.exr` sequence with a Displace modifier: Direction RGB to XYZ, Space
Local, Midlevel 0, Strength 1, the image Non-Color and not clamped, read as an image
sequence whose file numbers follow the scene frames (scene frame 1 shows the sequence's
first frame, file number `start_frame`). Foam (the EXR's A channel, written for choppy
seas, or a `foam.exr` sequence) drives a white mix in the material.

Write the sequence with

    seasynth animate ... --format disp.exr --up z -o DIR

(`--up y` works too: the object is then turned +90 degrees about X, as a Y-up host's
displacement is). `--sample-at centers` puts every vertex on a texel centre; with corners
the UVs still point at the texel centres, so both are exact.

Headless:

    blender -b --python seasynth_import.py -- DIR [--dump FRAME:FILE]...

`--dump` writes the evaluated vertices (world x y z, one line each, row by row) at scene
frame FRAME to FILE. From Blender's UI: open this file in the Text Editor and press Run
Script, then File > Import > seasynth displacement sequence (or F3, "seasynth"), and pick
the folder.
"""

import json
import math
import os
import sys

import bpy
from bpy.props import StringProperty
from bpy_extras.io_utils import ImportHelper


def read_sequence(folder):
    """The sequence sidecar, and what the import needs from it."""
    with open(os.path.join(folder, "sequence.json"), encoding="utf-8") as f:
        doc = json.load(f)
    grid = doc["params"]["grid"]
    pattern = next((p for p in doc["files"] if p.endswith(".disp.exr")), None)
    if pattern is None:
        raise ValueError(
            f"{folder}: the sequence has no disp.exr files (animate --format disp.exr)"
        )
    foam = next((p for p in doc["files"] if p.endswith(".foam.exr")), None)
    return {
        "nx": grid["size"][0],
        "ny": grid["size"][1],
        "lx": grid["extent_m"][0],
        "ly": grid["extent_m"][1],
        "offset": 0.5 if grid.get("sample_at", "corners") == "centers" else 0.0,
        "frames": doc["frames"],
        "fps": doc["fps"],
        "start": doc.get("start_frame", 0),
        "up": doc.get("up", "y") or "y",
        "disp": pattern,
        "foam": foam,
        # seasynth writes A (foam) into disp.exr only for a choppy sea.
        "alpha_foam": doc["params"].get("motion", {}).get("choppiness", 0.0) != 0.0,
    }


def file_of(folder, pattern, number):
    return os.path.join(folder, pattern.replace("{k}", f"{number:05d}"))


def sequence_image(path, name, frames, start, alpha_mode):
    """An image sequence, Non-Color, its first file `path` (number `start`)."""
    img = bpy.data.images.load(path, check_existing=False)
    img.name = name
    img.source = "SEQUENCE"
    img.colorspace_settings.name = "Non-Color"
    img.alpha_mode = alpha_mode
    return img


def set_user(user, frames, start):
    """Scene frame 1 shows file number `start`: Blender shows file number
    (scene frame - frame_start + 1 + frame_offset)."""
    user.frame_start = 1
    user.frame_duration = frames
    user.frame_offset = start - 1
    user.use_auto_refresh = True


def build_grid(name, s):
    """One vertex per sample at its position, quads counter-clockwise seen from above,
    UVs on the texel centres (u = (i + 1/2)/nx, v = 1 - (j + 1/2)/ny: image row 0 is y = 0,
    at the top of the image, where Blender's v is 1)."""
    nx, ny = s["nx"], s["ny"]
    dx, dy = s["lx"] / nx, s["ly"] / ny
    o = s["offset"]
    verts = []
    for j in range(ny):
        y = (j + o) * dy
        for i in range(nx):
            x = (i + o) * dx
            # Local frame of the EXR's axes: Z up (x, y, 0) or Y up (x, 0, -y).
            verts.append((x, y, 0.0) if s["up"] == "z" else (x, 0.0, -y))
    faces = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a = j * nx + i
            faces.append((a, a + 1, a + 1 + nx, a + nx))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    uv = mesh.uv_layers.new(name="UVMap")
    for poly in mesh.polygons:
        for li in poly.loop_indices:
            v = mesh.loops[li].vertex_index
            i, j = v % nx, v // nx
            uv.data[li].uv = ((i + 0.5) / nx, 1.0 - (j + 0.5) / ny)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    if s["up"] != "z":
        # Y-up data turned into Blender's Z-up world: (x, h, -y) -> (x, y, h).
        obj.rotation_euler = (math.pi / 2.0, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(obj)
    return obj, uv.name


def foam_material(name, folder, s, disp_img):
    """Water with white foam where the foam coverage is high (the EXR's A channel, or the
    foam.exr sequence)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    out = nodes["Material Output"]
    water = nodes["Principled BSDF"]
    water.inputs["Base Color"].default_value = (0.01, 0.05, 0.08, 1.0)
    water.inputs["Roughness"].default_value = 0.05
    if not (s["foam"] or s["alpha_foam"]):
        return mat  # no foam in the files: plain water
    foam = nodes.new("ShaderNodeBsdfDiffuse")
    foam.inputs["Color"].default_value = (0.9, 0.9, 0.9, 1.0)
    mix = nodes.new("ShaderNodeMixShader")
    tex = nodes.new("ShaderNodeTexImage")
    tex.interpolation = "Linear"
    if s["foam"]:
        img = sequence_image(
            file_of(folder, s["foam"], s["start"]), name + ".foam", s["frames"], s["start"], "STRAIGHT"
        )
        tex.image = img
        coverage = tex.outputs["Color"]
    else:
        # The displacement file again, its A channel read as data.
        img = sequence_image(
            disp_img.filepath, name + ".disp_alpha", s["frames"], s["start"], "CHANNEL_PACKED"
        )
        tex.image = img
        coverage = tex.outputs["Alpha"]
    set_user(tex.image_user, s["frames"], s["start"])
    links.new(coverage, mix.inputs["Fac"])
    links.new(water.outputs["BSDF"], mix.inputs[1])
    links.new(foam.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


def import_sequence(folder, name="seasynth"):
    """Builds the displaced grid of the sequence in `folder`; returns the object."""
    s = read_sequence(folder)
    obj, uv_name = build_grid(name, s)
    first = file_of(folder, s["disp"], s["start"])
    # The displacement: RGB only (alpha ignored, so that foam does not scale it).
    img = sequence_image(first, name + ".disp", s["frames"], s["start"], "NONE")
    tex = bpy.data.textures.new(name + ".disp", type="IMAGE")
    tex.image = img
    tex.use_clamp = False
    tex.use_alpha = False
    tex.use_mipmap = False
    tex.use_interpolation = True
    tex.filter_size = 1.0
    tex.extension = "EXTEND"
    set_user(tex.image_user, s["frames"], s["start"])
    mod = obj.modifiers.new("seasynth displacement", "DISPLACE")
    mod.texture = tex
    mod.texture_coords = "UV"
    mod.uv_layer = uv_name
    mod.direction = "RGB_TO_XYZ"
    mod.space = "LOCAL"
    mod.mid_level = 0.0
    mod.strength = 1.0
    obj.data.materials.append(foam_material(name, folder, s, img))
    scene = bpy.context.scene
    scene.frame_start = 1
    scene.frame_end = s["frames"]
    scene.render.fps = max(1, round(s["fps"]))
    scene.render.fps_base = scene.render.fps / s["fps"]
    scene.frame_set(1)
    return obj


def dump(obj, frame, path):
    """The evaluated vertices at scene `frame`, world coordinates, one line each."""
    scene = bpy.context.scene
    scene.frame_set(frame)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(depsgraph)
    mesh = ev.to_mesh()
    with open(path, "w", encoding="utf-8") as f:
        for v in mesh.vertices:
            w = ev.matrix_world @ v.co
            f.write(f"{w.x!r} {w.y!r} {w.z!r}\n")
    ev.to_mesh_clear()


class ImportSeasynth(bpy.types.Operator, ImportHelper):
    """Import a seasynth displacement sequence (a folder written by seasynth animate)"""

    bl_idname = "import_scene.seasynth_sequence"
    bl_label = "seasynth displacement sequence"
    filename_ext = ""
    use_filter_folder = True
    directory: StringProperty(subtype="DIR_PATH")

    def execute(self, context):
        try:
            import_sequence(self.directory)
        except (OSError, ValueError, KeyError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


def menu(self, context):
    self.layout.operator(ImportSeasynth.bl_idname, text=ImportSeasynth.bl_label)


def register():
    bpy.utils.register_class(ImportSeasynth)
    bpy.types.TOPBAR_MT_file_import.append(menu)


def main(argv):
    args = argv[argv.index("--") + 1 :]
    if not args:
        sys.exit("usage: blender -b --python seasynth_import.py -- DIR [--dump FRAME:FILE]...")
    folder, rest = args[0], args[1:]
    dumps = []
    while rest:
        if rest[0] != "--dump" or len(rest) < 2 or ":" not in rest[1]:
            sys.exit(f"unknown argument {rest[0]!r} (allowed: --dump FRAME:FILE)")
        frame, path = rest[1].split(":", 1)
        dumps.append((int(frame), path))
        rest = rest[2:]
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    obj = import_sequence(folder)
    for frame, path in dumps:
        dump(obj, frame, path)


if __name__ == "__main__":
    if "--" in sys.argv:
        main(sys.argv)
    else:
        register()
