"""Operators: add a sea, regenerate it, bake it, go back to live, report an error."""

import os
import time

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, StringProperty

from . import baked, engine, material, sea
from .props import PRESETS


def _active_sea(context):
    obj = context.active_object
    if obj is not None and obj.type == "MESH" and obj.seasynth.is_sea:
        return obj
    return None


class MESH_OT_seasynth_sea_add(bpy.types.Operator):
    """Add a sea computed by seasynth, live on every frame, in meters"""

    bl_idname = "mesh.seasynth_sea_add"
    bl_label = "seasynth sea"
    bl_options = {"REGISTER", "UNDO"}

    preset: EnumProperty(name="Preset", items=PRESETS, default="moderate")
    size: IntProperty(name="Size", description="Vertices along x and y", default=256, min=0, soft_min=2, soft_max=1024)
    extent: FloatProperty(name="Extent (m)", default=256.0, soft_min=1.0, soft_max=4096.0)
    wind_speed: FloatProperty(
        name="Wind Speed (m/s)", description="0: the preset's", default=0.0, soft_min=0.0, soft_max=40.0
    )

    def execute(self, context):
        if not engine.available():
            self.report({"ERROR"}, engine.missing_message())
            return {"CANCELLED"}
        me = bpy.data.meshes.new("seasynth sea")
        obj = bpy.data.objects.new("seasynth sea", me)
        s = obj.seasynth
        try:
            with sea.suspended():
                s.is_sea = True
                s.preset = self.preset
                sea.load_preset(s, self.preset)
                s.size = self.size
                s.extent = self.extent
                if self.wind_speed != 0.0:
                    s.wind_speed = self.wind_speed
            sea.apply(obj, context.scene)
        except engine.SeaError as e:
            bpy.data.objects.remove(obj)
            bpy.data.meshes.remove(me)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        context.collection.objects.link(obj)
        obj.location = context.scene.cursor.location
        material.assign(obj)
        for o in context.selected_objects:
            o.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        return {"FINISHED"}


class OBJECT_OT_seasynth_update(bpy.types.Operator):
    """Regenerate the active seasynth sea from its settings"""

    bl_idname = "object.seasynth_update"
    bl_label = "Update seasynth Sea"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return _active_sea(context) is not None

    def execute(self, context):
        obj = _active_sea(context)
        try:
            if obj.seasynth.mode == "BAKED":
                baked.unlink(obj)
            sea.apply(obj, context.scene)
        except engine.SeaError as e:
            obj.seasynth.error = str(e)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


class OBJECT_OT_seasynth_bake(bpy.types.Operator):
    """Write the scene's frames of the sea as an EXR sequence (seasynth animate's files)
    and read the sea from them"""

    bl_idname = "object.seasynth_bake"
    bl_label = "Bake seasynth Sequence"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = _active_sea(context)
        return obj is not None and bool(obj.seasynth.params_json)

    def execute(self, context):
        obj = _active_sea(context)
        s, scene = obj.seasynth, context.scene
        if s.bake_dir.startswith("//") and not bpy.data.filepath:
            self.report({"ERROR"}, "save the .blend first, or pick an absolute bake folder")
            return {"CANCELLED"}
        folder = os.path.normpath(bpy.path.abspath(s.bake_dir))
        frames = scene.frame_end - scene.frame_start + 1
        formats = ["disp.exr"]
        if s.foam:
            formats.append("foam.exr")
        if s.normals:
            formats.append("normal.exr")
        started = time.perf_counter()
        try:
            if s.mode == "BAKED":
                baked.unlink(obj)
            st = sea.state_of(obj, scene)
            # The stored parameters (foam threshold "auto": animate resolves it itself).
            p = engine.params_from_dict(st.resolved)
            engine.write_sequence(
                p,
                folder,
                frames=frames,
                formats=formats,
                start_frame=scene.frame_start,
                up="z",
                exr_half=s.bake_half,
                exr_compression=s.bake_compression,
            )
            baked.link(obj, folder, scene)
        except (engine.SeaError, OSError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report(
            {"INFO"},
            f"baked {frames} frames ({', '.join(formats)}) to {folder} in {time.perf_counter() - started:.1f} s",
        )
        return {"FINISHED"}


class OBJECT_OT_seasynth_live(bpy.types.Operator):
    """Compute the sea live again instead of reading its baked files"""

    bl_idname = "object.seasynth_live"
    bl_label = "Back to Live"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = _active_sea(context)
        return obj is not None and obj.seasynth.mode == "BAKED"

    def execute(self, context):
        obj = _active_sea(context)
        baked.unlink(obj)
        try:
            sea.show_frame(obj, context.scene)
        except engine.SeaError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


class OBJECT_OT_seasynth_report(bpy.types.Operator):
    """Show a seasynth message as Blender's error report. A setting's update runs no
    operator, and the reports of an operator called from Python only reach the caller;
    invoked, this one reports from its modal step, whose reports the window manager owns
    (the status bar, the Info editor). Executed (headless), it reports to the caller."""

    bl_idname = "object.seasynth_report"
    bl_label = "seasynth Error"
    bl_options = {"INTERNAL"}

    message: StringProperty()

    def invoke(self, context, event):
        wm = context.window_manager
        # A timer event runs the modal step at once, without waiting for input.
        self._timer = wm.event_timer_add(0.01, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        context.window_manager.event_timer_remove(self._timer)
        self.report({"ERROR"}, self.message)
        return {"CANCELLED"}

    def execute(self, context):
        self.report({"ERROR"}, self.message)
        return {"CANCELLED"}


def menu_add(self, context):
    self.layout.operator(MESH_OT_seasynth_sea_add.bl_idname, text="seasynth sea", icon="MOD_OCEAN")


CLASSES = (
    MESH_OT_seasynth_sea_add,
    OBJECT_OT_seasynth_update,
    OBJECT_OT_seasynth_bake,
    OBJECT_OT_seasynth_live,
    OBJECT_OT_seasynth_report,
)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.VIEW3D_MT_mesh_add.append(menu_add)


def unregister():
    bpy.types.VIEW3D_MT_mesh_add.remove(menu_add)
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
