"""Frame-change time of a live seasynth sea (the add-on) against Blender's Ocean modifier
at the same vertex count, in one Blender run.

    PYTHONPATH=DIR blender -b --factory-startup --python contrib/blender/frame_bench.py -- [FRAMES [SIZES]]

DIR holds the seasynth module (docs/blender.md, Install); FRAMES (default 24) frames are
timed after two warm-up frames; SIZES (default 128,256,512) are vertices per side. Both
seas: Pierson–Moskowitz at 15 m/s over 512 m, choppiness 1, foam and normals on, the
scene time following the frame at 24 fps (the Ocean modifier's Time driven by frame/24).
Each `scene.frame_set(f)` is timed whole (handlers, depsgraph, modifier), and the
evaluated mesh is read after it. The seasynth sea is timed playing (frames in order: the
add-on computes the next frame while Blender evaluates the current one) and scrubbing
(the same frames shuffled: every frame computed when asked for). The Ocean modifier runs in two geometry modes:
Displace on a grid of exactly N × N vertices with the simulation at resolution r, r² the
nearest square ≥ N, and Generate at that r, (r² + 1)² vertices. Prints a Markdown table
of medians and the ratios.
"""

import math
import os
import random
import statistics
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import seasynth_addon  # noqa: E402

EXTENT_M = 512
WIND_MPS = 15.0
FPS = 24


def clear():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        bpy.data.meshes.remove(m)


def time_frames(obj, frames, order="play"):
    """Median time of `scene.frame_set(f)` and the evaluated mesh, after two warm-up
    frames: frames 3 … frames + 2 in order ("play") or shuffled ("scrub")."""
    scene = bpy.context.scene
    todo = list(range(3, frames + 3))
    if order == "scrub":
        random.Random(1).shuffle(todo)
    times = []
    for k, f in enumerate([1, 2] + todo):
        t0 = time.perf_counter()
        scene.frame_set(f)
        dg = bpy.context.evaluated_depsgraph_get()
        n = len(obj.evaluated_get(dg).data.vertices)
        dt = time.perf_counter() - t0
        if k >= 2:
            times.append(dt)
    return statistics.median(times), n


def moves(obj):
    """The evaluated sea changes from frame to frame (guards against timing a still sea)."""
    scene = bpy.context.scene
    zs = []
    for f in (1, 2):
        scene.frame_set(f)
        dg = bpy.context.evaluated_depsgraph_get()
        me = obj.evaluated_get(dg).data
        zs.append([me.vertices[k].co.z for k in range(0, len(me.vertices), 997)])
    assert zs[0] != zs[1], f"{obj.name} does not move"


def seasynth_sea(n):
    bpy.ops.mesh.seasynth_sea_add(preset="mastin-1987", size=n, extent=EXTENT_M, wind_speed=WIND_MPS)
    obj = bpy.context.active_object
    s = obj.seasynth
    with seasynth_addon.sea.suspended():
        s.method = "fft"
        s.spectrum = "pierson-moskowitz"
        s.choppiness = 1.0
        s.foam = True
        s.normals = True
    bpy.ops.object.seasynth_update()
    return obj


def ocean(n, mode):
    r = math.ceil(math.sqrt(n))
    if mode == "DISPLACE":
        bpy.ops.mesh.primitive_grid_add(x_subdivisions=n - 1, y_subdivisions=n - 1, size=EXTENT_M)
    else:
        bpy.ops.mesh.primitive_plane_add()
    obj = bpy.context.active_object
    mod = obj.modifiers.new("Ocean", "OCEAN")
    mod.geometry_mode = mode
    mod.resolution = r
    mod.viewport_resolution = r
    mod.spatial_size = EXTENT_M
    mod.spectrum = "PIERSON_MOSKOWITZ"
    mod.wind_velocity = WIND_MPS
    mod.choppiness = 1.0
    mod.use_normals = True
    mod.use_foam = True
    fc = mod.driver_add("time")
    fc.driver.expression = f"frame/{FPS}"
    return obj, r


def main():
    args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    frames = int(args[0]) if args else 24
    sizes = [int(v) for v in args[1].split(",")] if len(args) > 1 else [128, 256, 512]
    seasynth_addon.register()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = 1, frames + 3
    rows = []
    for n in sizes:
        clear()
        obj = seasynth_sea(n)
        moves(obj)
        play_t, ss_n = time_frames(obj, frames, "play")
        scrub_t, _ = time_frames(obj, frames, "scrub")
        clear()
        obj, r = ocean(n, "DISPLACE")
        moves(obj)
        od_t, od_n = time_frames(obj, frames)
        clear()
        obj, _ = ocean(n, "GENERATE")
        og_t, og_n = time_frames(obj, frames)
        rows.append((n, ss_n, play_t, scrub_t, r, od_n, od_t, og_n, og_t))
        print(
            f"{n}: seasynth play {play_t * 1e3:.1f} ms, scrub {scrub_t * 1e3:.1f} ms, "
            f"Ocean displace {od_t * 1e3:.1f} ms, generate {og_t * 1e3:.1f} ms",
            flush=True,
        )
    print()
    load = ", ".join(f"{v:.1f}" for v in os.getloadavg())
    print(
        f"frame change, median of {frames} frames, Blender {bpy.app.version_string}, "
        f"{os.cpu_count()} cores, load average {load}"
    )
    print()
    print(
        "| N | seasynth sea, playing (N² vertices) | seasynth sea, scrubbing | Ocean, Displace on N² vertices (r, simulation r²) "
        "| Ocean, Generate at r | Ocean Displace ÷ seasynth (play, scrub) | Ocean Generate ÷ seasynth (play, scrub) |"
    )
    print("|---|---|---|---|---|---|---|")
    for n, ss_n, play_t, scrub_t, r, od_n, od_t, og_n, og_t in rows:
        print(
            f"| {n} | {play_t * 1e3:.1f} ms ({ss_n}) | {scrub_t * 1e3:.1f} ms | {od_t * 1e3:.1f} ms ({od_n}; r = {r}, {r * r}²) "
            f"| {og_t * 1e3:.1f} ms ({og_n} vertices) | {od_t / play_t:.1f}×, {od_t / scrub_t:.1f}× "
            f"| {og_t / play_t:.1f}×, {og_t / scrub_t:.1f}× |"
        )
    seasynth_addon.unregister()


main()
