"""The Blender add-on (contrib/blender/seasynth_addon) run headless by Blender.

Blender installs the add-on from its zip, adds a seasynth sea, steps scene frames, bakes
it and opens the saved .blend again; this test checks the evaluated meshes against the
seasynth module's arrays and against `seasynth animate`'s EXR files of the same frames,
the baked files against the command line's, and the error reports of bad panel values.

Needs `blender` on the PATH (`.ci/blender.sh` installs Debian's package), the seasynth
module importable here (its package folder is handed to Blender's Python through
PYTHONPATH; or set SEASYNTH_BLENDER_PYTHONPATH to a folder holding it, e.g. a
`pip install --no-deps --target DIR` of the wheel) and the command line: SEASYNTH_BIN,
or `cargo build --release`'s target/release/seasynth (CARGO_TARGET_DIR honoured). Each
missing piece skips the test with a note saying which.
"""

import json
import os
import shutil
import struct
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
ADDON = REPO / "contrib" / "blender" / "seasynth_addon"

# Vertex x, y are float32(x_grid + λDx): half an ulp at 64 m is 3.8e-6 m. The add-on and
# this test round the same float64 sum, so the measured difference is 0.
POSITION_TOLERANCE_M = 1e-5
# Heights, foam and normals are the module's float32 numbers copied into the mesh: equal.
# The baked sea is the flat grid plus each file's vector through Blender's Displace
# modifier (the texel centre sampled by UV, float32 matrix products): tests/blender.rs
# holds it to the same 1e-5 m.
BAKED_TOLERANCE_M = 1e-5

FPS = 24.0
START = 3  # the scene's first frame: scene frame F is animate's frame F − START, file F
END = 6
N = 32
L = 64.0

# The choppy sea: Add → seasynth sea (preset moderate, 32 vertices over 64 m, 12 m/s),
# then these panel values.
CHOPPY_PANEL = {"wind_dir": 30.0, "choppiness": 1.0, "seed": 7, "spectrum": "jonswap",
                "spreading": "hasselmann", "loop_period": 20.0, "time_offset": 2.5}
CHOPPY_CLI = ["--preset", "moderate", "--size", str(N), "--extent", str(L), "--wind-speed", "12",
              "--wind-dir", "30", "--choppiness", "1", "--seed", "7", "--spectrum", "jonswap",
              "--spreading", "hasselmann", "--loop-period", "20", "--time", "2.5"]
# Heights only, second order, samples at texel centres, a seamless tile (a closing column
# and row of vertices): preset mastin-1987 (15 m/s).
SECOND_PANEL = {"method": "fft", "choppiness": 0.0, "second_order": True, "sample_at": "centers",
                "seamless": True}
SECOND_CLI = ["--preset", "mastin-1987", "--size", str(N), "--extent", str(L), "--method", "fft",
              "--choppiness", "0", "--nonlinear", "second-order", "--sample-at", "centers"]

DRIVER = r'''
import json, os, sys, traceback
import bpy
import numpy as np

cfg = json.load(open(sys.argv[sys.argv.index("--") + 1]))
tmp = cfg["tmp"]
out = {}


def evaluated(obj):
    """The evaluated mesh's vertices (object space) and point attributes."""
    dg = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(dg)
    me = ev.to_mesh()
    res = {}
    co = np.empty(len(me.vertices) * 3, np.float32)
    me.vertices.foreach_get("co", co)
    res["co"] = co.reshape(-1, 3)
    for name, comp, width in (("seasynth_foam", "value", 1), ("seasynth_normal", "vector", 3)):
        a = me.attributes.get(name)
        if a is not None:
            arr = np.empty(len(a.data) * width, np.float32)
            a.data.foreach_get(comp, arr)
            res[name] = arr.reshape(-1, width) if width > 1 else arr
    ev.to_mesh_clear()
    return res


def dump(obj, tag, frame):
    bpy.context.scene.frame_set(frame)
    np.savez(os.path.join(tmp, f"{tag}_{frame}.npz"), **evaluated(obj))


def error_of(call):
    try:
        call()
    except RuntimeError as e:
        return str(e).strip()
    return None


def set_panel(obj, values):
    for k, v in values.items():
        setattr(obj.seasynth, k, v)


bpy.ops.preferences.addon_install(filepath=cfg["zip"])
bpy.ops.preferences.addon_enable(module="seasynth_addon")
out["registered"] = hasattr(bpy.types.Object, "seasynth") and "seasynth_sea_add" in dir(bpy.ops.mesh)
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
scene = bpy.context.scene
scene.render.fps, scene.render.fps_base = int(cfg["fps"]), 1.0
scene.frame_start, scene.frame_end = cfg["start"], cfg["end"]
scene.frame_set(cfg["start"])

# The choppy sea, live.
bpy.ops.mesh.seasynth_sea_add(preset="moderate", size=cfg["n"], extent=cfg["l"], wind_speed=12.0)
sea = bpy.context.active_object
set_panel(sea, cfg["choppy_panel"])
out["choppy_name"] = sea.name
out["choppy_params"] = json.loads(sea.seasynth.params_json)
out["choppy_sidecar"] = json.loads(sea.seasynth.sidecar_json)


def links(obj):
    """(from node, to node, to socket) of the sea's material."""
    nt = obj.active_material.node_tree
    return sorted([l.from_node.name, l.to_node.name, l.to_socket.name] for l in nt.links)


out["live_links"] = links(sea)
for f in cfg["frames"]:
    dump(sea, "live", f)

# Bad values: the report, the sea unchanged, still animated by its last good values.
json_before = sea.seasynth.params_json
scene.frame_set(cfg["end"])
before = evaluated(sea)["co"]
sea.seasynth.wind_speed = -3.0
out["wind_error"] = sea.seasynth.error
out["wind_unchanged"] = bool(np.array_equal(evaluated(sea)["co"], before))
out["wind_update_error"] = error_of(lambda: bpy.ops.object.seasynth_update())
dump(sea, "while_bad", cfg["frames"][1])
sea.seasynth.wind_speed = 12.0
sea.seasynth.size = 0
out["size_error"] = sea.seasynth.error
out["size_vertices"] = len(sea.data.vertices)
sea.seasynth.size = cfg["n"]
out["restored"] = sea.seasynth.params_json == json_before and sea.seasynth.error == ""
n_objects = len(bpy.data.objects)
out["add_error"] = error_of(lambda: bpy.ops.mesh.seasynth_sea_add(size=0))
out["add_objects_unchanged"] = len(bpy.data.objects) == n_objects

bpy.ops.wm.save_as_mainfile(filepath=os.path.join(tmp, "sea.blend"))

# Bake, read back through the Displace modifier, and back to live.
sea.seasynth.bake_dir = os.path.join(tmp, "bake")
sea.seasynth.bake_compression = "none"
bpy.ops.object.seasynth_bake()
out["baked_mode"] = sea.seasynth.mode
out["baked_modifiers"] = [m.type for m in sea.modifiers]
out["baked_links"] = links(sea)
out["baked_images"] = {n: sea.active_material.node_tree.nodes[n].image.filepath
                       for n in ("Foam Sequence", "Normal Sequence")}
for f in cfg["frames"]:
    dump(sea, "baked", f)
bpy.ops.object.seasynth_live()
out["live_mode"] = sea.seasynth.mode
out["live_modifiers"] = [m.type for m in sea.modifiers]
dump(sea, "live_again", cfg["frames"][1])

# Heights only, second order, samples at the texel centres.
bpy.ops.mesh.seasynth_sea_add(preset="mastin-1987", size=cfg["n"], extent=cfg["l"])
second = bpy.context.active_object
set_panel(second, cfg["second_panel"])
out["second_error"] = second.seasynth.error
out["second_params"] = json.loads(second.seasynth.params_json)
for f in cfg["frames"]:
    dump(second, "second", f)
second.seasynth.bake_dir = os.path.join(tmp, "bake2")
bpy.ops.object.seasynth_bake()
dump(second, "second_baked", cfg["frames"][1])

# The saved file: the same settings and sea.
bpy.ops.wm.open_mainfile(filepath=os.path.join(tmp, "sea.blend"))
sea = bpy.data.objects[out["choppy_name"]]
out["reopened_params"] = json.loads(sea.seasynth.params_json)
out["reopened_panel"] = {k: getattr(sea.seasynth, k) for k in cfg["choppy_panel"]}
dump(sea, "reopened", cfg["frames"][1])

# A new frame rate: the live sea and its stored parameters follow it.
bpy.context.scene.render.fps = 30
dump(sea, "fps30", cfg["frames"][1])
out["fps30_params"] = json.loads(sea.seasynth.params_json)

with open(os.path.join(tmp, "out.json"), "w") as fh:
    json.dump(out, fh)
'''


def skip(reason):
    print(f"note: {reason}", file=sys.stderr)
    pytest.skip(reason)


def blender_path():
    path = os.environ.get("BLENDER") or shutil.which("blender")
    if not path:
        skip("blender is not on the PATH: the Blender add-on test is skipped (.ci/blender.sh installs it)")
    return path


def seasynth_bin():
    env = os.environ.get("SEASYNTH_BIN")
    if env:
        if not Path(env).is_file():
            skip(f"SEASYNTH_BIN={env} is not a file")
        return env
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    for profile in ("release", "debug"):
        exe = target / profile / "seasynth"
        if exe.is_file():
            return str(exe)
    skip("no seasynth binary (set SEASYNTH_BIN, or run cargo build --release): the Blender add-on test is skipped")


def the_module():
    try:
        import seasynth
    except ImportError as e:
        skip(f"the seasynth module is not built ({e}): the Blender add-on test is skipped")
    return seasynth


def module_folder(tmp, seasynth):
    """A folder to put on Blender's PYTHONPATH that holds the seasynth package."""
    env = os.environ.get("SEASYNTH_BLENDER_PYTHONPATH")
    if env:
        return env
    folder = tmp / "pylib"
    shutil.copytree(Path(seasynth.__file__).parent, folder / "seasynth",
                    ignore=shutil.ignore_patterns("__pycache__"))
    return str(folder)


def run_blender(blender, env, *args):
    return subprocess.run([blender, "-b", "--factory-startup", *args], env=env,
                          capture_output=True, text=True, timeout=600)


def addon_zip(tmp):
    """The add-on as Edit → Preferences → Add-ons → Install takes it."""
    path = tmp / "seasynth_addon.zip"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for f in sorted(ADDON.glob("*.py")):
            z.write(f, f"seasynth_addon/{f.name}")
    return path


def read_exr(path):
    """The channels of an uncompressed scanline OpenEXR (float or half), rows from the
    top (row j of seasynth's files is y = j·Ly/ny): {name: (ny, nx) float32}."""
    data = Path(path).read_bytes()
    assert struct.unpack_from("<i", data, 0)[0] == 20000630, f"{path}: not an EXR"
    pos, attrs = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        name, kind = data[pos:name_end].decode(), data[name_end + 1:type_end].decode()
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        attrs[name] = (kind, data[type_end + 5:type_end + 5 + size])
        pos = type_end + 5 + size
    pos += 1
    assert attrs["compression"][1][0] == 0, f"{path}: compressed (write it with --exr-compression none)"
    chans, raw = [], attrs["channels"][1]
    p = 0
    while raw[p] != 0:
        end = raw.index(b"\0", p)
        chans.append((raw[p:end].decode(), struct.unpack_from("<i", raw, end + 1)[0]))
        p = end + 17
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    nx, ny = x1 - x0 + 1, y1 - y0 + 1
    offsets = struct.unpack_from(f"<{ny}Q", data, pos)
    out = {c: np.empty((ny, nx), np.float32) for c, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        p = off + 8
        for c, t in chans:
            dt, width = (np.float32, 4) if t == 2 else (np.float16, 2)
            out[c][y - y0] = np.frombuffer(data, dt, nx, p).astype(np.float32)
            p += width * nx
    return out


def cli(exe, cwd, *args):
    r = subprocess.run([exe, *args], cwd=cwd, capture_output=True, text=True)
    return r


def cli_message(exe, cwd, *args):
    """The command line's one-line error for `args` (exit code 2)."""
    r = cli(exe, cwd, *args)
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    assert line.startswith("Error: "), line
    return line[len("Error: "):]


def grid_xy(params):
    grid = params["grid"]
    nx, ny = grid["size"]
    lx, ly = grid["extent_m"]
    o = 0.5 if grid.get("sample_at", "corners") == "centers" else 0.0
    x = (np.arange(nx) + o) * (lx / nx)
    y = (np.arange(ny) + o) * (ly / ny)
    return np.tile(x, ny), np.repeat(y, nx)


def check_positions(co, want, what):
    d = np.abs(co.astype(np.float64) - want)
    k = int(np.argmax(d[:, :2]) // 2)
    assert d[:, :2].max() <= POSITION_TOLERANCE_M, f"{what}: vertex {k} at {co[k]}, want {want[k]}"
    k = int(np.argmax(d[:, 2]))
    assert d[:, 2].max() == 0.0, f"{what}: height of vertex {k} is {co[k, 2]}, want {want[k, 2]}"


def displaced(params, disp):
    """(x + λDx, y + λDy, h) of every sample, float32 as the mesh holds them."""
    x, y = grid_xy(params)
    d = disp.reshape(-1, 3)
    return np.stack([x + d[:, 0], y + d[:, 1], d[:, 2]], axis=1).astype(np.float32)


def test_blender_addon_makes_the_live_sea_seasynth_animate_makes(tmp_path):
    blender = blender_path()
    exe = seasynth_bin()
    seasynth = the_module()
    pylib = module_folder(tmp_path, seasynth)
    env = dict(os.environ)
    env["PYTHONPATH"] = pylib + os.pathsep + env.get("PYTHONPATH", "")
    env["BLENDER_USER_SCRIPTS"] = str(tmp_path / "scripts")  # the zip installs here, not in ~
    probe = run_blender(blender, env, "--python-expr",
                        "import seasynth; print('seasynth', seasynth.__version__, 'ok')")
    if " ok" not in probe.stdout:
        skip(f"Blender's Python does not import the seasynth module from {pylib}: {probe.stdout[-400:]}{probe.stderr[-400:]}")

    frames = [START, START + 1, END]
    cfg = {"tmp": str(tmp_path), "zip": str(addon_zip(tmp_path)), "fps": FPS, "start": START, "end": END,
           "n": N, "l": L, "frames": frames, "choppy_panel": CHOPPY_PANEL, "second_panel": SECOND_PANEL}
    (tmp_path / "cfg.json").write_text(json.dumps(cfg))
    (tmp_path / "driver.py").write_text(DRIVER)
    run = run_blender(blender, env, "--python-exit-code", "1", "--python", str(tmp_path / "driver.py"),
                      "--", str(tmp_path / "cfg.json"))
    log = run.stdout + run.stderr
    assert run.returncode == 0 and "Traceback" not in log, f"Blender failed:\n{log[-4000:]}"
    out = json.loads((tmp_path / "out.json").read_text())
    assert out["registered"], "the add-on did not register from its zip"

    def frame(tag, f):
        return np.load(tmp_path / f"{tag}_{f}.npz")

    # The command line's sequences of the same seas: files START … END.
    seq = ["--fps", str(FPS), "--frames", str(END - START + 1), "--start-frame", str(START),
           "--up", "z", "--exr-compression", "none", "-q"]
    r = cli(exe, tmp_path, "animate", *CHOPPY_CLI, *seq, "--format", "disp.exr,foam.exr,normal.exr", "-o", "cli")
    assert r.returncode == 0, r.stderr
    r = cli(exe, tmp_path, "animate", *SECOND_CLI, *seq, "--format", "disp.exr", "-o", "cli2")
    assert r.returncode == 0, r.stderr
    cli_seq = json.loads((tmp_path / "cli" / "sequence.json").read_text())
    cli2_seq = json.loads((tmp_path / "cli2" / "sequence.json").read_text())

    # The panel resolves to the command line's parameters, and the .blend keeps them.
    params = out["choppy_params"]
    assert params == cli_seq["params"], "the panel's parameters are not animate's"
    assert out["choppy_sidecar"]["params"] == params
    assert out["reopened_params"] == params
    for key, value in CHOPPY_PANEL.items():
        got = out["reopened_panel"][key]
        assert (got == pytest.approx(value)) if isinstance(value, float) else got == value, key
    assert out["second_error"] == "", out["second_error"]
    assert out["second_params"] == cli2_seq["params"], "the second-order panel is not animate's"

    # Live frames: the module's arrays and animate's files, frame k = F − START.
    p = seasynth.Params.from_dict(params)
    module_frames = list(seasynth.animate(p, frames=END - START + 1, maps=("displacement", "normal", "foam")))
    for f in frames:
        k = f - START
        live = frame("live", f)
        assert live["co"].shape == (N * N, 3)
        g = seasynth.generate(p, time=params["time_s"] + k / FPS, maps=("displacement",))
        check_positions(live["co"], displaced(params, g.displacement), f"scene frame {f} vs seasynth.generate")
        m = module_frames[k]
        check_positions(live["co"], displaced(params, m.displacement), f"scene frame {f} vs seasynth.animate")
        assert np.array_equal(live["seasynth_foam"], m.foam.ravel()), f"frame {f}: foam"
        assert np.array_equal(live["seasynth_normal"], m.normal.reshape(-1, 3)), f"frame {f}: normals"
        ex = read_exr(tmp_path / "cli" / f"frame_{f:05d}.disp.exr")
        disp = np.stack([ex["R"], ex["G"], ex["B"]], axis=-1)
        check_positions(live["co"], displaced(params, disp), f"scene frame {f} vs animate's file {f}")
        foam = read_exr(tmp_path / "cli" / f"frame_{f:05d}.foam.exr")["Y"]
        assert np.array_equal(live["seasynth_foam"], foam.ravel()), f"frame {f}: foam vs foam.exr"
        nrm = read_exr(tmp_path / "cli" / f"frame_{f:05d}.normal.exr")
        nrm = np.stack([nrm["R"], nrm["G"], nrm["B"]], axis=-1).reshape(-1, 3)
        assert np.array_equal(live["seasynth_normal"], nrm), f"frame {f}: normals vs normal.exr"
    first, last = frame("live", START)["co"], frame("live", END)["co"]
    assert np.abs(first[:, 2] - last[:, 2]).max() > 0.05, "the sea does not move between frames"
    gx, gy = grid_xy(params)
    assert np.abs(first[:, 0] - gx).max() > 0.01 and np.abs(first[:, 1] - gy).max() > 0.01, "no choppy displacement"

    second = out["second_params"]
    for f in frames:
        co = frame("second", f)["co"].reshape(N + 1, N + 1, 3)
        # The closing column and row: the first ones, one tile further.
        assert np.array_equal(co[:, N, 1:], co[:, 0, 1:]) and np.array_equal(co[N, :, [0, 2]], co[0, :, [0, 2]])
        assert np.abs(co[:, N, 0] - co[:, 0, 0] - L).max() <= POSITION_TOLERANCE_M
        assert np.abs(co[N, :, 1] - co[0, :, 1] - L).max() <= POSITION_TOLERANCE_M
        co = co[:N, :N].reshape(-1, 3)
        ex = read_exr(tmp_path / "cli2" / f"frame_{f:05d}.disp.exr")
        x, y = grid_xy(second)
        want = np.stack([x, y, ex["B"].ravel()], axis=1).astype(np.float32)
        check_positions(co, want, f"second order, scene frame {f} vs animate's file {f}")
        g = seasynth.generate(seasynth.Params.from_dict(second), time=second["time_s"] + (f - START) / FPS)
        assert np.array_equal(co[:, 2], g.height.ravel()), f"second order, frame {f}"
    # Baked, the closing vertices read the first texels again (the textures repeat).
    d = np.abs(frame("second_baked", START + 1)["co"].astype(np.float64) - frame("second", START + 1)["co"]).max()
    assert d <= BAKED_TOLERANCE_M, f"the baked seamless sea is {d} m off the live one"

    # Bad values: seasynth's own message, reported; the previous sea stays and animates.
    wind = cli_message(exe, tmp_path, "generate", *CHOPPY_CLI, "--wind-speed", "-3", "-o", "x.png")
    with pytest.raises(seasynth.ParamError) as e:
        seasynth.Params(preset="moderate", wind_speed=-3.0)
    assert str(e.value) == wind
    assert out["wind_error"] == wind
    assert out["wind_update_error"] == f"Error: {wind}"
    assert out["wind_unchanged"], "a bad wind speed changed the sea"
    assert np.array_equal(frame("while_bad", START + 1)["co"], frame("live", START + 1)["co"])
    size = cli_message(exe, tmp_path, "generate", *CHOPPY_CLI, "--size", "0", "-o", "x.png")
    assert out["size_error"] == size
    assert out["size_vertices"] == N * N
    assert out["add_error"] == f"Error: {size}"
    assert out["add_objects_unchanged"]
    assert out["restored"]

    # The bake: the command line's files, read back as the live sea.
    assert out["baked_mode"] == "BAKED" and out["baked_modifiers"] == ["DISPLACE"]
    bake_seq = json.loads((tmp_path / "bake" / "sequence.json").read_text())
    assert bake_seq["params"] == cli_seq["params"]
    assert bake_seq["start_frame"] == START and bake_seq["frames"] == END - START + 1
    for f in range(START, END + 1):
        for kind in ("disp", "foam", "normal"):
            name = f"frame_{f:05d}.{kind}.exr"
            assert (tmp_path / "bake" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    for f in frames:
        d = np.abs(frame("baked", f)["co"].astype(np.float64) - frame("live", f)["co"]).max()
        print(f"baked vs live, scene frame {f}: max {d:.2e} m")
        assert d <= BAKED_TOLERANCE_M, f"scene frame {f}: the baked sea is {d} m off the live one"
    # Foam and normals reach the material: attributes live, the sequences baked.
    foam_live = ["Foam Attribute", "Foam Amount", "Value"]
    normal_live = ["Normal Attribute", "Normal to World", "Vector"]
    to_bsdf = ["Normal to World", "Water", "Normal"]
    for link in (foam_live, normal_live, to_bsdf, ["Foam Amount", "Foam Mix", "Fac"]):
        assert link in out["live_links"], f"live material lacks {link}"
    for link in (["Foam Sequence", "Foam Amount", "Value"], ["Normal Sequence", "Normal to World", "Vector"], to_bsdf):
        assert link in out["baked_links"], f"baked material lacks {link}"
    assert foam_live not in out["baked_links"] and normal_live not in out["baked_links"]
    assert out["baked_images"]["Foam Sequence"].endswith(f"frame_{START:05d}.foam.exr")
    assert out["baked_images"]["Normal Sequence"].endswith(f"frame_{START:05d}.normal.exr")
    assert out["live_mode"] == "LIVE" and out["live_modifiers"] == []
    assert np.array_equal(frame("live_again", START + 1)["co"], frame("live", START + 1)["co"])
    assert np.array_equal(frame("reopened", START + 1)["co"], frame("live", START + 1)["co"])
    p30 = out["fps30_params"]
    assert p30["motion"]["fps"] == 30.0 and dict(p30, motion=None) == dict(params, motion=None)
    g = seasynth.generate(seasynth.Params.from_dict(p30), time=p30["time_s"] + 1 / 30.0, maps=("displacement",))
    check_positions(frame("fps30", START + 1)["co"], displaced(p30, g.displacement), "scene frame 4 at 30 fps")
