"""The Python package gives the command line's bits: heights equal the samples of the
float TIFF `seasynth generate` writes, maps those of its map files, frames those of
`seasynth animate`; arrays are handed over without a copy."""

import json
import pickle

import numpy as np
import pytest

import seasynth
from conftest import read_tiff_f32

# Every method, every spectrum family, choppy, texel centres: (name, keys as flags).
CASES = [
    ("hybrid-default", []),
    ("fft-phillips", ["--method", "fft", "--spectrum", "phillips"]),
    ("fft-pm-hasselmann", ["--method", "fft", "--spectrum", "pierson-moskowitz", "--spreading", "hasselmann", "--wind-speed", "15"]),
    ("fft-jonswap", ["--method", "fft", "--spectrum", "jonswap", "--fetch-km", "100", "--wind-dir", "30"]),
    ("fft-tma", ["--method", "fft", "--spectrum", "tma", "--depth", "20", "--wind-speed", "12"]),
    ("filtered-noise", ["--method", "filtered-noise", "--spectrum", "pierson-moskowitz", "--wind-speed", "10"]),
    ("perlin", ["--method", "perlin"]),
    ("trochoid", ["--method", "trochoid", "--spectrum", "pierson-moskowitz"]),
    ("fractal", ["--preset", "fractal-terrain"]),
    ("choppy", ["--method", "fft", "--spectrum", "jonswap", "--choppiness", "1", "--time", "2.5"]),
    ("centers", ["--method", "fft", "--spectrum", "pierson-moskowitz", "--sample-at", "centers"]),
    ("second-order", ["--method", "fft", "--spectrum", "pierson-moskowitz", "--wind-speed", "15", "--nonlinear", "second-order", "--extent", "1024"]),
    ("hybrid-second-order", ["--method", "hybrid", "--spectrum", "pierson-moskowitz", "--wind-speed", "15", "--nonlinear", "second-order", "--extent", "1024"]),
]


def keys_of(flags):
    """`--flag value` pairs as `generate` keywords (`_` for `-`)."""
    preset, keys = None, {}
    it = iter(flags)
    for flag in it:
        value = next(it)
        if flag == "--preset":
            preset = value
        else:
            keys[flag[2:].replace("-", "_")] = value
    return preset, keys


@pytest.mark.parametrize("name,flags", CASES, ids=[c[0] for c in CASES])
def test_heights_equal_the_cli_float_tiff_exactly(cli, tmp_path, name, flags):
    cli("generate", *flags, "--size", "96x64", "--seed", "5", "-o", tmp_path / "a.tif", "--quiet")
    want = read_tiff_f32(tmp_path / "a.tif")
    preset, keys = keys_of(flags)
    f = seasynth.generate(preset=preset, size="96x64", seed=5, **keys)
    assert f.height.shape == (64, 96) and f.height.dtype == np.float32
    assert np.array_equal(f.height, want), f"{name}: max |diff| {np.abs(f.height - want).max()}"
    # The sidecar's parameters and statistics are the command line's.
    side = json.loads((tmp_path / "a.json").read_text())
    assert f.sidecar()["params"] == side["params"]
    if name == "trochoid":
        # The command line streams a trochoid sea written to TIFF alone in strips, so
        # its statistics are summed in another order: equal to the last bits or so.
        assert f.stats == pytest.approx(side["stats"], rel=1e-12)
    else:
        assert f.stats == side["stats"]


def test_choppy_maps_equal_the_cli_map_files(cli, tmp_path):
    flags = ["--method", "fft", "--spectrum", "jonswap", "--choppiness", "1", "--size", "64", "--seed", "3"]
    cli("generate", *flags, "-o", tmp_path / "a.tif", "-o", tmp_path / "a.disp.tif", "--quiet")
    f = seasynth.generate(method="fft", spectrum="jonswap", choppiness=1, size=64, seed=3,
                          maps=("displacement", "normal", "jacobian", "foam"))
    disp = read_tiff_f32(tmp_path / "a.disp.tif")
    assert np.array_equal(f.displacement, disp)
    # Normals are unit vectors pointing up; foam lies in 0..1 and covers where J is low.
    assert np.allclose(np.linalg.norm(f.normal, axis=2), 1.0, atol=1e-5)
    assert (f.normal[:, :, 2] > 0).all()
    assert 0.0 <= f.foam.min() and f.foam.max() <= 1.0
    assert f.foam[f.jacobian > 1.0].max() == 0.0
    assert f.foam.max() > 0.0, "a choppy JONSWAP sea at λ = 1 has some foam"


def test_frames_equal_the_cli_animate_frames_bit_for_bit(cli, tmp_path):
    flags = ["--method", "fft", "--spectrum", "pierson-moskowitz", "--choppiness", "0.8", "--size", "48", "--seed", "9",
             "--loop-period", "8"]
    cli("animate", *flags, "--frames", "4", "--fps", "2", "--format", "tif,disp", "-o", tmp_path / "seq", "--quiet")
    frames = list(seasynth.animate(method="fft", spectrum="pierson-moskowitz", choppiness=0.8, size=48, seed=9,
                                   loop_period=8, frames=4, fps=2, maps=("displacement",)))
    assert len(frames) == 4
    for k, f in enumerate(frames):
        assert f.time == k / 2
        assert np.array_equal(f.height, read_tiff_f32(tmp_path / "seq" / f"frame_{k:05}.tif")), f"frame {k}"
        assert np.array_equal(f.displacement, read_tiff_f32(tmp_path / "seq" / f"frame_{k:05}.disp.tif")), f"frame {k}"
        # A frame is `generate --time t` bit for bit.
        g = seasynth.generate(f.params)
        assert np.array_equal(g.height, f.height)


@pytest.mark.parametrize("extra", [
    {"choppiness": 0.8},
    {"nonlinear": "second-order", "spreading": "hasselmann", "wind_speed": 12, "extent": 640},
])
def test_a_prepared_sea_gives_generate_at_any_time_in_any_order(extra):
    # Sea(...).frame(t) is generate(..., time=t) bit for bit, asked out of order, maps
    # included; a looping second-order sea's pairs are summed once for every frame.
    keys = dict(method="fft", spectrum="pierson-moskowitz", size=48, seed=4, loop_period=10, **extra)
    maps = ("normal",) if "choppiness" in extra else ()
    sea = seasynth.Sea(maps=maps, **keys)
    for t in [7.5, 0.0, 3.25, 17.5]:
        f = sea.frame(t)
        g = seasynth.generate(time=t, maps=maps, **keys)
        assert f.time == t
        assert np.array_equal(f.height, g.height), f"t = {t}"
        if maps:
            assert np.array_equal(f.normal, g.normal), f"t = {t}"
        assert f.sidecar() == g.sidecar(), f"t = {t}"
    assert not np.array_equal(sea.frame(0.0).height, sea.frame(1.0).height)


def test_write_sequence_writes_the_cli_files(cli, tmp_path):
    p = seasynth.Params(method="fft", spectrum="jonswap", choppiness=1, size=32, seed=2)
    done = seasynth.write_sequence(p, tmp_path / "py", frames=3, formats=["tif", "disp"], start_frame=1)
    assert done == (3, 0)
    cli("animate", "--method", "fft", "--spectrum", "jonswap", "--choppiness", "1", "--size", "32", "--seed", "2",
        "--frames", "3", "--format", "tif,disp", "--start-frame", "1", "-o", tmp_path / "cli", "--quiet")
    for n in (1, 2, 3):
        for kind in ("tif", "disp.tif"):
            a = (tmp_path / "py" / f"frame_{n:05}.{kind}").read_bytes()
            b = (tmp_path / "cli" / f"frame_{n:05}.{kind}").read_bytes()
            assert a == b, f"frame {n} {kind}"
    seq = json.loads((tmp_path / "py" / "sequence.json").read_text())
    assert seq["frames"] == 3 and seq["params"] == p.to_dict()


def test_field_write_writes_what_generate_writes(cli, tmp_path):
    f = seasynth.generate(preset="storm", size=64, seed=4)
    written = f.write(tmp_path / "py.tif", tmp_path / "py.png", tmp_path / "py.normal.png")
    assert [p.split("/")[-1] for p in written] == ["py.tif", "py.png", "py.normal.png"]
    cli("generate", "--preset", "storm", "--size", "64", "--seed", "4", "-o", tmp_path / "cli.tif",
        "-o", tmp_path / "cli.png", "-o", tmp_path / "cli.normal.png", "--quiet")
    for ext in ("tif", "png", "normal.png"):
        assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / f"cli.{ext}").read_bytes(), ext
    a = json.loads((tmp_path / "py.json").read_text())
    b = json.loads((tmp_path / "cli.json").read_text())
    assert a["params"] == b["params"] and a["stats"] == b["stats"] and a["mapping"] == b["mapping"]


def test_arrays_are_views_of_the_library_memory_not_copies():
    f = seasynth.generate(size=64, choppiness=1, method="fft", maps=("displacement", "normal"))
    h = f.height
    assert h.base is f._core, "the height array is a view of the field's own buffer"
    assert h.__array_interface__["data"][0] == f.height.__array_interface__["data"][0]
    assert h.flags["C_CONTIGUOUS"] and not h.flags["WRITEABLE"]
    assert f.normal.base is f._core and f.displacement.base is f._core
    with pytest.raises(ValueError):
        h[0, 0] = 1.0
    # The view outlives the Field object that made it.
    del f
    assert np.isfinite(h).all()


def test_the_same_bits_on_any_number_of_threads():
    p = seasynth.Params(preset="storm", size=128, choppiness=1)
    one = seasynth.generate(p, threads=1, maps=("foam",))
    two = seasynth.generate(p, threads=2, maps=("foam",))
    assert np.array_equal(one.height, two.height) and np.array_equal(one.foam, two.foam)


def test_params_round_trip_and_follow_the_command_lines_precedence():
    p = seasynth.Params(preset="storm", keys={"grid.size": [64, 32]}, wind_speed=12, size=48)
    d = p.to_dict()
    # Keys apply in order, the last one winning: size=48 after grid.size.
    assert d["grid"]["size"] == [48, 48] and d["wind"]["speed_mps"] == 12.0
    assert seasynth.Params.from_dict(d) == p
    assert pickle.loads(pickle.dumps(p)) == p
    assert seasynth.Params.from_dict(json.loads(json.dumps(d))).to_dict() == d
    assert p.replace(seed=7).to_dict()["seed"] == 7 and p.to_dict()["seed"] == d["seed"]
    assert p.shape == (48, 48)
    x, y = seasynth.Params(size=4, extent=8, sample_at="centers").coords()
    assert np.allclose(x, [1, 3, 5, 7]) and np.allclose(y, [1, 3, 5, 7])


def test_a_toml_preset_file_and_its_parameters_agree(tmp_path):
    p = seasynth.Params(preset="mastin-1987", size=32)
    path = tmp_path / "mine.toml"
    path.write_text(p.to_toml())
    assert seasynth.Params.from_toml(path) == p


def test_xarray_gets_dims_coords_in_meters_and_the_sidecar():
    xr = pytest.importorskip("xarray", reason="xarray is not installed")
    f = seasynth.generate(size="16x8", extent="32x16")
    a = f.to_xarray()
    assert a.dims == ("y", "x") and a.shape == (8, 16)
    assert np.allclose(a.x.values, np.arange(16) * 2.0) and a.x.attrs["units"] == "m"
    assert a.attrs["units"] == "m" and json.loads(a.attrs["params"]) == f.params.to_dict()
    assert isinstance(a, xr.DataArray) and np.array_equal(a.values, f.height)


def test_spectrum_and_analyze_give_the_json_reports(cli, tmp_path):
    s = seasynth.spectrum(preset="storm", freq=[0.05, 0.1])
    want = json.loads(cli("spectrum", "--preset", "storm", "--freq", "0.05,0.1", "--json").stdout)
    assert list(s["s_m2_per_hz"]) == [p["s_m2_per_hz"] for p in want["points"]]
    assert s["hs_m"] == want["hs_m"] and s["fp_hz"] == want["fp_hz"]
    default = seasynth.spectrum(preset="storm")
    assert len(default["f_hz"]) == 200 and default["f_hz"][default["s_m2_per_hz"].argmax()] == pytest.approx(s["fp_hz"], rel=0.02)

    cli("generate", "--preset", "storm", "--size", "128", "-o", tmp_path / "a.tif", "--quiet")
    from_cli = json.loads(cli("analyze", tmp_path / "a.tif", "--json").stdout)
    from_py = seasynth.analyze(tmp_path / "a.tif")
    assert from_py == from_cli
    f = seasynth.generate(preset="storm", size=128)
    a = seasynth.analyze(f)
    for key in ("std_m", "hs_m", "min_m", "max_m", "peak_wavelength_m"):
        assert a[key] == pytest.approx(from_cli[key], rel=1e-9), key
    for key in ("skewness", "kurtosis", "mean_square_slope"):
        assert a["waves"][key] == pytest.approx(from_cli["waves"][key], rel=1e-9), key
    # An array of float64 or with strides is converted, not misread.
    b = seasynth.analyze(f.height.astype(np.float64), extent=f.params.extent_m)
    assert b["std_m"] == a["std_m"]
    wide = np.zeros((128, 256), np.float32)
    wide[:, ::2] = f.height
    assert seasynth.analyze(wide[:, ::2], extent=f.params.extent_m)["std_m"] == a["std_m"]


def test_without_resampling_the_heights_are_the_displacement_maps(cli, tmp_path):
    keys = dict(method="fft", spectrum="jonswap", choppiness=1, size=64, seed=8)
    a = seasynth.generate(maps=("displacement",), resample=False, **keys)
    b = seasynth.generate(maps=("displacement",), **keys)
    assert np.array_equal(a.displacement, b.displacement)
    assert np.array_equal(a.height, b.displacement[:, :, 2])
    assert not np.array_equal(a.height, b.height), "the resampled heights differ from the undisplaced ones"
