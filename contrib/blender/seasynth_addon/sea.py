"""The live sea: seasynth's frame at the scene time written into the object's mesh.

Scene frame F shows seasynth time t = time_offset + (F − frame_start)/fps, fps =
render.fps / render.fps_base: frame k = F − frame_start of `seasynth animate --time
time_offset --fps fps`, and file number F of a sequence baked with `--start-frame
frame_start` (the add-on's bake). The mesh has one vertex per sample, row by row
(vertex j·nx + i is sample (i, j)), at (x + λDx, y + λDy, h) in object space, meters,
x = (i [+ ½])·Lx/nx, y = (j [+ ½])·Ly/ny: the displaced vertex of the sample, exactly as
`animate --format disp.exr --up z` describes it; with Seamless Edges a closing column
and row follow (the first ones, one tile further). Everything moves through numpy and
`foreach_set`; no Python loop runs over vertices.
"""

import json
import threading
from contextlib import contextmanager

import bpy
import numpy as np

from . import engine, material
from .props import PHYSICAL

FOAM_ATTR = "seasynth_foam"
NORMAL_ATTR = "seasynth_normal"

_suspended = 0
# Per object (by its pointer): the parameters of the live frames and the flat grid.
_states = {}


@contextmanager
def suspended():
    """Setting changes inside do not regenerate the sea (several fields at once)."""
    global _suspended
    _suspended += 1
    try:
        yield
    finally:
        _suspended -= 1


def scene_fps(scene):
    return scene.render.fps / scene.render.fps_base


def frame_time(scene, time0, frame=None):
    """seasynth time of scene `frame` (default: the current one, subframe included)."""
    f = scene.frame_current_final if frame is None else frame
    return time0 + (f - scene.frame_start) / scene_fps(scene)


def typed(v):
    """The number an artist typed into a float field: Blender stores it as a float32
    (0.8 becomes 0.800000011920929), seasynth takes float64, so the shortest decimal that
    is this float32 goes through (0.8)."""
    return float(str(np.float32(v)))


def panel_args(s, scene):
    """The panel as seasynth's preset and keys, in the order they apply: the panel's
    flags, the scene's fps, then More Keys (so a key given there wins)."""
    keys = dict(
        method=s.method,
        size=s.size,
        extent=typed(s.extent),
        wind_speed=typed(s.wind_speed),
        wind_dir=typed(s.wind_dir),
        spectrum=s.spectrum,
        choppiness=typed(s.choppiness),
        seed=s.seed,
        time=typed(s.time_offset),
        sample_at=s.sample_at,
        nonlinear="second-order" if s.second_order else "linear",
    )
    if s.spectrum in PHYSICAL:
        keys["spreading"] = s.spreading
    if s.loop_period > 0.0:
        keys["loop_period"] = typed(s.loop_period)
    keys["motion.fps"] = scene_fps(scene)
    text = s.extra_json.strip()
    if text:
        try:
            extra = json.loads(text)
        except json.JSONDecodeError as e:
            raise engine.SeaError(f"More Keys: not JSON ({e})") from None
        if not isinstance(extra, dict):
            raise engine.SeaError('More Keys: a JSON object of preset keys, e.g. {"spectrum.gamma": 2.0}')
        keys.update(extra)
    return s.preset, keys


class State:
    """What the live frames need, derived once from the resolved parameters."""

    def __init__(self, params, resolved, params_json, sidecar, foam_threshold=None):
        self.params = params
        self.foam_threshold = foam_threshold
        self.resolved = resolved
        self.json = params_json
        self.sidecar = sidecar
        grid = resolved["grid"]
        self.nx, self.ny = (int(v) for v in grid["size"])
        self.lx, self.ly = (float(v) for v in grid["extent_m"])
        self.offset = 0.5 if grid.get("sample_at", "corners") == "centers" else 0.0
        self.time0 = float(resolved.get("time_s", 0.0))
        motion = resolved.get("motion", {})
        self.fps = float(motion.get("fps", 30.0))
        self.choppy = float(motion.get("choppiness", 0.0)) != 0.0
        self._base = {}

    def dims(self, seamless):
        """Vertices along x and y: one per sample, and with `seamless` a closing column
        and row (the first ones again, one tile further)."""
        return (self.nx + 1, self.ny + 1) if seamless else (self.nx, self.ny)

    def base(self, seamless):
        """x and y of every vertex of the flat grid, float64, row by row."""
        if seamless not in self._base:
            mx, my = self.dims(seamless)
            i = (np.arange(mx, dtype=np.float64) + self.offset) * (self.lx / self.nx)
            j = (np.arange(my, dtype=np.float64) + self.offset) * (self.ly / self.ny)
            self._base[seamless] = (np.tile(i, my), np.repeat(j, mx))
        return self._base[seamless]


def wrapped(a, seamless):
    """A (ny, nx, …) map with its first column and row repeated after the last, for the
    closing vertices of a seamless tile."""
    if not seamless:
        return a
    a = np.concatenate([a, a[:, :1]], axis=1)
    return np.concatenate([a, a[:1]], axis=0)


def _pin_foam(p, resolved, wanted):
    """`animate` resolves an "auto" foam threshold once, at its first frame (t = time),
    and uses it for every frame; the live frames do the same, so frame F's foam is
    `animate`'s frame F's. Returns the parameters of the live frames, the first frame's
    sidecar, and the threshold when the foam must be made here from the Jacobian (a
    resolved threshold seasynth does not take as a setting, ≤ 0 on a folding sea)."""
    f0 = engine.frame(p, float(resolved.get("time_s", 0.0)), ("foam",) if wanted else ())
    sidecar = f0.sidecar()
    motion = resolved.get("motion", {})
    auto = motion.get("foam_threshold", "auto") == "auto"
    choppy = float(motion.get("choppiness", 0.0)) != 0.0
    if wanted and auto and choppy:
        thr = (sidecar.get("foam") or {}).get("threshold_resolved")
        if thr is not None:
            try:
                return engine.replace(p, foam_threshold=float(thr)), sidecar, None
            except engine.SeaError:
                return p, sidecar, float(thr)
    return p, sidecar, None


def foam_from_jacobian(j, threshold):
    """seasynth's foam coverage round(65535·clamp((T − J)/T, 0, 1))/65535, float32."""
    f = (threshold - j.astype(np.float64)) / threshold * 65535.0
    v = np.clip(np.nan_to_num(f, nan=0.0), 0.0, 65535.0)
    t = np.floor(v)
    return ((t + (v - t >= 0.5)) / 65535.0).astype(np.float32)


def make_state(s, scene):
    """Validates the panel through seasynth; raises SeaError with seasynth's message."""
    preset, keys = panel_args(s, scene)
    p = engine.params(preset, keys)
    resolved = engine.resolved(p)
    live, sidecar, thr = _pin_foam(p, resolved, s.foam)
    return State(live, resolved, json.dumps(resolved, sort_keys=True), sidecar, thr)


def state_of(obj, scene):
    """The live state of `obj`, rebuilt from its stored parameters when needed (a file
    just opened, an undo)."""
    s = obj.seasynth
    fps = scene_fps(scene)
    st = _states.get(obj.as_pointer())
    if st is not None and st.json == s.params_json and st.fps == fps:
        return st
    if not s.params_json:
        st = make_state(s, scene)
    else:
        resolved = json.loads(s.params_json)
        p = engine.params_from_dict(resolved)
        if float(resolved.get("motion", {}).get("fps", fps)) != fps:
            # The scene's frame rate changed: the stored parameters follow it.
            p = engine.replace(p, keys={"motion.fps": fps})
            resolved = engine.resolved(p)
        live, sidecar, thr = _pin_foam(p, resolved, s.foam)
        st = State(live, resolved, json.dumps(resolved, sort_keys=True), sidecar, thr)
        if st.json != s.params_json:
            with suspended():
                s.params_json = st.json
                s.sidecar_json = json.dumps(sidecar, sort_keys=True)
    _remember(obj, st)
    return st


def _remember(obj, st):
    key = obj.as_pointer()
    if key not in _states:
        alive = {o.as_pointer() for o in bpy.data.objects}
        for k in [k for k in _states if k not in alive]:
            del _states[k]
    _states[key] = st


def build_topology(me, mx, my, nx, ny):
    """A grid of mx × my vertices (nx × ny samples), quads counter-clockwise seen from
    +z, smooth, UVs on the texel centres (u = (i + ½)/nx, v = 1 − (j + ½)/ny: image row 0
    is y = 0, the top of the image, where Blender's v is 1; the closing vertices of a
    seamless tile reach past 1 and the textures repeat), as the import script builds it."""
    me.clear_geometry()
    n, q = mx * my, (mx - 1) * (my - 1)
    me.vertices.add(n)
    me.loops.add(4 * q)
    me.polygons.add(q)
    j, i = np.mgrid[0 : my - 1, 0 : mx - 1]
    a = (j * mx + i).ravel()
    quads = np.stack([a, a + 1, a + 1 + mx, a + mx], axis=1).ravel().astype(np.int32)
    me.loops.foreach_set("vertex_index", quads)
    me.polygons.foreach_set("loop_start", np.arange(0, 4 * q, 4, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(q, 4, dtype=np.int32))
    me.polygons.foreach_set("use_smooth", np.ones(q, dtype=bool))
    me.update(calc_edges=True)
    uv = me.uv_layers.new(name="UVMap")
    u = ((quads % mx) + 0.5) / nx
    v = 1.0 - ((quads // mx) + 0.5) / ny
    uv.data.foreach_set("uv", np.stack([u, v], axis=1).astype(np.float32).ravel())
    me["seasynth_grid"] = [mx, my, nx, ny]


def ensure_topology(me, st, seamless):
    mx, my = st.dims(seamless)
    if len(me.vertices) != mx * my or list(me.get("seasynth_grid", [])) != [mx, my, st.nx, st.ny]:
        build_topology(me, mx, my, st.nx, st.ny)


def _point_attr(me, name, kind):
    a = me.attributes.get(name)
    if a is not None and (a.data_type != kind or a.domain != "POINT"):
        me.attributes.remove(a)
        a = None
    if a is None:
        a = me.attributes.new(name, kind, "POINT")
    return a


def _drop_attr(me, name):
    a = me.attributes.get(name)
    if a is not None:
        me.attributes.remove(a)


def positions(st, f, seamless=False):
    """Vertex positions (n, 3) float32 of frame `f`."""
    x, y = st.base(seamless)
    co = np.empty((x.size, 3), dtype=np.float32)
    d = getattr(f, "displacement", None) if st.choppy else None
    if d is not None:
        d = wrapped(d, seamless).reshape(-1, 3)
        co[:, 0] = x + d[:, 0]
        co[:, 1] = y + d[:, 1]
        co[:, 2] = d[:, 2]
    else:
        co[:, 0] = x
        co[:, 1] = y
        co[:, 2] = wrapped(f.height, seamless).reshape(-1)
    return co


def write_frame(obj, st, f):
    """Frame `f` into the mesh: positions, and the foam and normal attributes."""
    s, me = obj.seasynth, obj.data
    ensure_topology(me, st, s.seamless)
    me.vertices.foreach_set("co", positions(st, f, s.seamless).ravel())
    if s.foam and getattr(f, "foam", None) is not None:
        _point_attr(me, FOAM_ATTR, "FLOAT").data.foreach_set(
            "value", np.ascontiguousarray(wrapped(f.foam, s.seamless), dtype=np.float32).ravel()
        )
    else:
        _drop_attr(me, FOAM_ATTR)
    if s.normals and getattr(f, "normal", None) is not None:
        _point_attr(me, NORMAL_ATTR, "FLOAT_VECTOR").data.foreach_set(
            "vector", np.ascontiguousarray(wrapped(f.normal, s.seamless), dtype=np.float32).ravel()
        )
    else:
        _drop_attr(me, NORMAL_ATTR)
    me.update()


def maps_for(s, st):
    maps = []
    if st.choppy:
        maps.append("displacement")
    if s.normals:
        maps.append("normal")
    if s.foam:
        maps.append("foam" if st.foam_threshold is None else "jacobian")
    return maps


def frame_at(obj, st, t):
    """seasynth's frame at time `t` for the object's settings."""
    f = engine.frame(st.params, t, maps_for(obj.seasynth, st))
    if obj.seasynth.foam and st.foam_threshold is not None:
        return _WithFoam(f, foam_from_jacobian(f.jacobian, st.foam_threshold))
    return f


class _WithFoam:
    """A frame whose foam was made here from its Jacobian."""

    def __init__(self, f, foam):
        self._f, self.foam = f, foam

    def __getattr__(self, name):
        return getattr(self._f, name)


class _Ahead:
    """The next frame of a playing sea, computed on a worker thread while Blender
    evaluates and draws the current one (the module releases Python's lock while it
    computes). Only a frame asked for with the same state, time and maps is taken."""

    def __init__(self, obj, st, t):
        self.key = (id(st), t, tuple(maps_for(obj.seasynth, st)))
        self.frame = self.error = None
        self._thread = threading.Thread(target=self._run, args=(obj.seasynth.foam, st, t), daemon=True)
        self._thread.start()

    def _run(self, foam, st, t):
        try:
            f = engine.frame(st.params, t, self.key[2])
            if foam and st.foam_threshold is not None:
                f = _WithFoam(f, foam_from_jacobian(f.jacobian, st.foam_threshold))
            self.frame = f
        except engine.SeaError as e:
            self.error = e

    def busy(self):
        return self._thread.is_alive()

    def take(self, key):
        if key != self.key:
            return None
        self._thread.join()
        return self.frame


_ahead = {}  # object pointer -> _Ahead
_stale = []  # frames computed ahead that were not wanted, still running


def show_frame(obj, scene, frame=None, ahead=False):
    """The live sea at scene `frame` (default: the current frame). With `ahead` (frame
    changes), the following frame starts computing once this one is written."""
    st = state_of(obj, scene)
    t = frame_time(scene, st.time0, frame)
    key = obj.as_pointer()
    pending = _ahead.pop(key, None)
    f = None
    if pending is not None:
        f = pending.take((id(st), t, tuple(maps_for(obj.seasynth, st))))
        if f is None and pending.busy():
            _stale.append(pending)
    if f is None:
        f = frame_at(obj, st, t)
    write_frame(obj, st, f)
    _stale[:] = [a for a in _stale if a.busy()]
    if ahead and not _stale:
        step = scene.frame_step if scene.frame_step > 0 else 1
        nxt = (scene.frame_current if frame is None else frame) + step
        if nxt <= scene.frame_end:
            _ahead[key] = _Ahead(obj, st, frame_time(scene, st.time0, nxt))
    return f


def apply(obj, scene):
    """Regenerates the sea from its panel. On a bad value raises SeaError and leaves the
    sea on screen and its stored parameters as they were."""
    s = obj.seasynth
    st = make_state(s, scene)
    f = frame_at(obj, st, frame_time(scene, st.time0))
    _remember(obj, st)
    write_frame(obj, st, f)
    with suspended():
        s.params_json = st.json
        s.sidecar_json = json.dumps(st.sidecar, sort_keys=True)
        s.error = ""
    material.update_for(obj)
    return f


def report_error(message):
    """Blender's error report (status bar, Info editor) from a setting's update, where
    no operator is running; headless, the report is printed."""
    window = getattr(bpy.context, "window", None)
    mode = "INVOKE_DEFAULT" if window is not None and not bpy.app.background else "EXEC_DEFAULT"
    try:
        bpy.ops.object.seasynth_report(mode, message=message)
    except RuntimeError:
        pass  # the report itself: an operator that reports an error raises when called from Python


def on_setting_changed(obj, context):
    s = obj.seasynth
    if _suspended or not s.is_sea:
        return
    scene = context.scene if context and context.scene else bpy.context.scene
    try:
        if s.mode == "BAKED":
            from . import baked

            baked.unlink(obj)
        apply(obj, scene)
    except engine.SeaError as e:
        with suspended():
            s.error = str(e)
        report_error(str(e))


def preset_values(name):
    """The fields the panel shows, from a preset's resolved parameters."""
    d = engine.resolved(engine.params(name, {}))
    spectrum = d.get("spectrum", {})
    motion = d.get("motion", {})
    wind = d.get("wind", {})
    values = {
        "method": d.get("method", "fft"),
        "wind_speed": float(wind.get("speed_mps", 10.0)),
        "wind_dir": float(wind.get("direction_deg", 0.0)),
        "spectrum": spectrum.get("model", "jonswap"),
        "spreading": spectrum.get("spreading", "hasselmann"),
        "choppiness": float(motion.get("choppiness", 0.0)),
        "seed": int(d.get("seed", 1)),
        "loop_period": float(motion.get("loop_period_s") or 0.0),
        "second_order": spectrum.get("nonlinear", "linear") == "second-order",
        "time_offset": float(d.get("time_s", 0.0)),
    }
    return values


def load_preset(s, name):
    """Loads a preset's sea state into the panel, keeping Size, Extent and Samples At."""
    values = preset_values(name)
    with suspended():
        for key, value in values.items():
            try:
                setattr(s, key, value)
            except TypeError:
                pass  # a value the panel has no item for (a fractal spectrum): keep ours


def on_preset_changed(obj, context):
    s = obj.seasynth
    if _suspended or not s.is_sea:
        return
    try:
        load_preset(s, s.preset)
    except engine.SeaError as e:
        s.error = str(e)
        report_error(str(e))
        return
    on_setting_changed(obj, context)


def seas(scene):
    return [o for o in scene.objects if o.type == "MESH" and o.seasynth.is_sea]


@bpy.app.handlers.persistent
def on_frame_change(scene, depsgraph=None):
    """frame_change_pre: the live seas follow the scene's frame before it is evaluated."""
    for obj in seas(scene):
        s = obj.seasynth
        if s.mode != "LIVE" or not s.params_json:
            continue
        try:
            show_frame(obj, scene, ahead=True)
        except engine.SeaError as e:
            if s.error != str(e):
                with suspended():
                    s.error = str(e)


@bpy.app.handlers.persistent
def on_load(_filepath=None, *args):
    """A .blend just opened: its seas are rebuilt from their stored parameters."""
    _states.clear()
    for scene in bpy.data.scenes:
        on_frame_change(scene)


def clear():
    _states.clear()
    _ahead.clear()
