"""The seasynth panel: View3D → Sidebar (N) → seasynth."""

import json

import bpy

from . import engine
from .props import PHYSICAL


class VIEW3D_PT_seasynth(bpy.types.Panel):
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "seasynth"
    bl_label = "seasynth Sea"

    def draw(self, context):
        layout = self.layout
        if not engine.available():
            box = layout.box()
            box.alert = True
            box.label(text="seasynth module not found", icon="ERROR")
            box.label(text="See docs/blender.md, Install")
            return
        obj = context.active_object
        if obj is None or obj.type != "MESH" or not obj.seasynth.is_sea:
            layout.operator("mesh.seasynth_sea_add", icon="MOD_OCEAN", text="Add seasynth Sea")
            return
        s = obj.seasynth
        if s.error:
            box = layout.box()
            box.alert = True
            box.label(text=s.error, icon="ERROR")
            box.label(text="(the sea shows its last valid settings)")
        row = layout.row()
        row.label(text="Baked" if s.mode == "BAKED" else "Live", icon="FILE_IMAGE" if s.mode == "BAKED" else "PLAY")
        stats = {}
        if s.sidecar_json:
            try:
                stats = json.loads(s.sidecar_json).get("stats", {})
            except ValueError:
                stats = {}
        if "hs_m" in stats:
            row.label(text=f"Hs {stats['hs_m']:.2f} m")
        col = layout.column()
        col.enabled = s.mode == "LIVE"
        col.use_property_split = True
        col.use_property_decorate = False
        col.prop(s, "preset")
        col.prop(s, "method")
        col.prop(s, "size")
        col.prop(s, "extent")
        col.prop(s, "wind_speed")
        col.prop(s, "wind_dir")
        col.prop(s, "spectrum")
        sub = col.row()
        sub.active = s.spectrum in PHYSICAL
        sub.prop(s, "spreading")
        col.prop(s, "choppiness")
        col.prop(s, "seed")
        col.prop(s, "loop_period")
        sub = col.row()
        sub.active = s.method in ("fft", "hybrid") and s.spectrum in PHYSICAL and s.choppiness == 0.0
        sub.prop(s, "second_order")
        col.prop(s, "sample_at")
        col.prop(s, "seamless")
        col.prop(s, "time_offset")
        col.prop(s, "extra_json")
        col.separator()
        col.prop(s, "foam")
        sub = col.row()
        sub.active = s.foam
        sub.prop(s, "foam_amount")
        col.prop(s, "normals")
        layout.operator("object.seasynth_update", icon="FILE_REFRESH")


class VIEW3D_PT_seasynth_bake(bpy.types.Panel):
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "seasynth"
    bl_label = "Bake"
    bl_parent_id = "VIEW3D_PT_seasynth"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return engine.available() and obj is not None and obj.type == "MESH" and obj.seasynth.is_sea

    def draw(self, context):
        layout = self.layout
        s = context.active_object.seasynth
        scene = context.scene
        col = layout.column()
        col.use_property_split = True
        col.use_property_decorate = False
        col.prop(s, "bake_dir")
        col.prop(s, "bake_half")
        col.prop(s, "bake_compression")
        col.label(text=f"Frames {scene.frame_start}–{scene.frame_end} → files {scene.frame_start:05d}…")
        row = layout.row()
        row.operator("object.seasynth_bake", icon="RENDER_ANIMATION")
        row.operator("object.seasynth_live", icon="PLAY")
        if s.mode == "BAKED":
            layout.label(text=s.baked_dir, icon="FILE_FOLDER")


CLASSES = (VIEW3D_PT_seasynth, VIEW3D_PT_seasynth_bake)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
