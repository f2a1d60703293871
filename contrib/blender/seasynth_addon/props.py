"""The sea's settings, stored on its object (`object.seasynth`), so a saved .blend
reopens with the same sea. Every setting maps to one seasynth parameter (its CLI flag in
the tooltip); `params_json` keeps the resolved parameters of the sea on screen, the
`params` of its sidecar."""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
    StringProperty,
)

# The repository's presets that make a sea (presets/*.toml).
PRESETS = [
    ("moderate", "Moderate", "JONSWAP at 10 m/s over a 100 km fetch (Hs ≈ 2.1 m), choppy"),
    ("calm", "Calm", "A calm sea"),
    ("storm", "Storm", "A storm sea"),
    ("storm-loop", "Storm (loop)", "A choppy storm that loops every 20 s"),
    ("swell", "Swell", "Long swell"),
    ("li-tian", "Li Tian", "Li Tian fig. 2c: hybrid FFT + Perlin, Phillips, 7 m/s"),
    ("li-tian-fft", "Li Tian (FFT)", "Li Tian's sea, FFT only"),
    ("mastin-1987", "Mastin 1987", "Pierson–Moskowitz at 15 m/s, Hasselmann spreading"),
    ("tessendorf-usc", "Tessendorf", "Tessendorf's course notes: Phillips, 50 m/s, 1000 m"),
    ("thon-2000", "Thon 2000", "Thon's trochoid sea"),
]

METHODS = [
    ("fft", "FFT", "Tessendorf's FFT sea (--method fft): choppy waves, second order"),
    ("hybrid", "Hybrid", "Li Tian's FFT + Perlin blend (--method hybrid)"),
    ("filtered-noise", "Filtered noise", "Mastin's filtered white noise (--method filtered-noise)"),
    ("trochoid", "Trochoid", "Thon's Gerstner waves plus fitted turbulence (--method trochoid)"),
    ("perlin", "Perlin", "Perlin fBm alone (--method perlin)"),
]

SPECTRA = [
    ("pierson-moskowitz", "Pierson–Moskowitz", "Fully developed sea, heights in meters"),
    ("jonswap", "JONSWAP", "Fetch-limited sea, heights in meters"),
    ("tma", "TMA", "JONSWAP in finite depth (set Depth), heights in meters"),
    ("phillips", "Phillips", "Tessendorf's Phillips spectrum (amplitude A, not meters)"),
]
PHYSICAL = {"pierson-moskowitz", "jonswap", "tma"}

SPREADINGS = [
    ("hasselmann", "Hasselmann", "cos^2p(θ/2) after Hasselmann"),
    ("mitsuyasu", "Mitsuyasu", "Mitsuyasu's spreading"),
    ("donelan-banner", "Donelan–Banner", "Donelan and Banner's sech² spreading"),
    ("cos2", "cos²", "Phillips' |k̂·ŵ|²"),
]


def _changed(self, context):
    from . import sea

    sea.on_setting_changed(self.id_data, context)


def _preset_changed(self, context):
    from . import sea

    sea.on_preset_changed(self.id_data, context)


def _shading_changed(self, context):
    from . import material

    material.update_for(self.id_data)


class SeasynthSea(bpy.types.PropertyGroup):
    is_sea: BoolProperty(name="seasynth sea", default=False, options={"HIDDEN"})
    preset: EnumProperty(
        name="Preset",
        items=PRESETS,
        default="moderate",
        description="seasynth preset (--preset): loads its values into the fields below",
        update=_preset_changed,
    )
    method: EnumProperty(name="Method", items=METHODS, default="fft", update=_changed)
    size: IntProperty(
        name="Size",
        description="Samples (and vertices) along x and y (--size)",
        default=256,
        min=0,
        soft_min=2,
        soft_max=1024,
        update=_changed,
    )
    extent: FloatProperty(
        name="Extent (m)",
        description="Side of the tile in meters (--extent); FFT seas repeat with this period",
        default=256.0,
        soft_min=1.0,
        soft_max=4096.0,
        update=_changed,
    )
    wind_speed: FloatProperty(
        name="Wind Speed (m/s)",
        description="Wind speed, m/s (--wind-speed)",
        default=10.0,
        soft_min=0.5,
        soft_max=40.0,
        update=_changed,
    )
    wind_dir: FloatProperty(
        name="Wind Direction (°)",
        description="Direction the wind blows toward, degrees: 0 = +x, 90 = +y (--wind-dir)",
        default=0.0,
        soft_min=-180.0,
        soft_max=360.0,
        update=_changed,
    )
    spectrum: EnumProperty(name="Spectrum", items=SPECTRA, default="jonswap", update=_changed)
    spreading: EnumProperty(name="Spreading", items=SPREADINGS, default="hasselmann", update=_changed)
    choppiness: FloatProperty(
        name="Choppiness",
        description="Horizontal displacement factor λ (--choppiness; 0: heights only, 1: trochoid-like)",
        default=1.0,
        soft_min=0.0,
        soft_max=2.0,
        update=_changed,
    )
    seed: IntProperty(
        name="Seed",
        description="Random seed (--seed): the same seed gives the same sea at any size",
        default=1,
        min=0,
        update=_changed,
    )
    loop_period: FloatProperty(
        name="Loop Period (s)",
        description="Seamless loop period, s (--loop-period); 0: no loop",
        default=0.0,
        min=0.0,
        soft_max=120.0,
        update=_changed,
    )
    second_order: BoolProperty(
        name="Second Order",
        description="Add the bound waves of second-order theory (--nonlinear second-order; FFT or hybrid, physical spectra, no choppiness)",
        default=False,
        update=_changed,
    )
    sample_at: EnumProperty(
        name="Samples At",
        items=[
            ("corners", "Corners", "Vertex (i, j) at (i·dx, j·dy) (--sample-at corners)"),
            ("centers", "Centres", "Vertex (i, j) at ((i + ½)·dx, (j + ½)·dy) (--sample-at centers)"),
        ],
        default="corners",
        update=_changed,
    )
    time_offset: FloatProperty(
        name="Time Offset (s)",
        description="seasynth time at the scene's start frame (--time)",
        default=0.0,
        update=_changed,
    )
    extra_json: StringProperty(
        name="More Keys",
        description='Any other seasynth parameter as a JSON object of preset keys, e.g. {"spectrum.gamma": 2.0, "spectrum.fetch_km": 50}',
        default="",
        update=_changed,
    )
    seamless: BoolProperty(
        name="Seamless Edges",
        description="Add a closing column and row of vertices (the first ones, one tile further) so that copies of the sea side by side (an Array modifier with a constant offset of the extent) meet without a gap",
        default=False,
        update=_changed,
    )
    foam: BoolProperty(
        name="Foam",
        description="Compute seasynth's foam coverage each frame and mix it into the material",
        default=True,
        update=_changed,
    )
    normals: BoolProperty(
        name="seasynth Normals",
        description="Shade with seasynth's exact normals (a vertex attribute) instead of the mesh's",
        default=True,
        update=_changed,
    )
    foam_amount: FloatProperty(
        name="Foam Amount",
        description="Factor on the foam coverage in the material",
        default=1.0,
        min=0.0,
        soft_max=4.0,
        update=_shading_changed,
    )
    mode: EnumProperty(
        name="Mode",
        items=[
            ("LIVE", "Live", "Computed by seasynth on every frame change"),
            ("BAKED", "Baked", "Read from the baked EXR sequence"),
        ],
        default="LIVE",
        options={"HIDDEN"},
    )
    bake_dir: StringProperty(
        name="Folder",
        description="Folder of the baked sequence (frame_NNNNN.disp.exr …, sequence.json)",
        default="//seasynth_bake/",
        subtype="DIR_PATH",
    )
    bake_half: BoolProperty(
        name="Half Floats", description="Write 16-bit half EXRs (--exr-half)", default=False
    )
    bake_compression: EnumProperty(
        name="Compression",
        items=[("zip", "ZIP", "lossless"), ("piz", "PIZ", "lossless"), ("none", "None", "fastest")],
        default="zip",
    )
    baked_dir: StringProperty(name="Baked Folder", default="", options={"HIDDEN"})
    params_json: StringProperty(
        name="Resolved Parameters",
        description="The resolved seasynth parameters of the sea on screen (a sidecar's params)",
        default="",
        options={"HIDDEN"},
    )
    sidecar_json: StringProperty(
        name="Sidecar",
        description="The sidecar of the sea at its time offset (parameters, seed, version, stats)",
        default="",
        options={"HIDDEN"},
    )
    error: StringProperty(name="Error", default="", options={"HIDDEN"})


CLASSES = (SeasynthSea,)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.Object.seasynth = bpy.props.PointerProperty(type=SeasynthSea)


def unregister():
    del bpy.types.Object.seasynth
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
