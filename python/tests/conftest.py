"""Shared helpers: the command-line binary the Python results are compared with, and a
reader for the float TIFFs and raw files it writes."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli_path():
    """The `seasynth` binary: $SEASYNTH_BIN, else the repository's release build."""
    env = os.environ.get("SEASYNTH_BIN")
    if env:
        return pathlib.Path(env)
    return REPO / "target" / "release" / "seasynth"


@pytest.fixture(scope="session")
def cli():
    """Runs the command line; skips (with the reason shown by `pytest -rs`) when it has
    not been built."""
    path = cli_path()
    if not path.is_file():
        pytest.skip(f"no seasynth binary at {path}: run `cargo build --release` (or set SEASYNTH_BIN)")

    def run(*args, cwd=None, check=True):
        out = subprocess.run([str(path), *map(str, args)], cwd=cwd, capture_output=True, text=True)
        if check and out.returncode != 0:
            raise AssertionError(f"seasynth {' '.join(map(str, args))} failed ({out.returncode}):\n{out.stderr}")
        return out

    return run


def read_r32(path, shape):
    """A raw little-endian float32 height file (`.r32`), rows along y."""
    return np.fromfile(path, dtype="<f4").reshape(shape)


def read_tiff_f32(path):
    """The samples of a float TIFF written by seasynth: one (height) or three
    (displacement) float32 channels, uncompressed strips; (rows, columns[, channels])."""
    data = pathlib.Path(path).read_bytes()
    assert data[:4] in (b"II*\x00", b"MM\x00*"), f"{path} is not a TIFF"
    end = "<" if data[:2] == b"II" else ">"
    u16 = lambda o: int(np.frombuffer(data, end + "u2", 1, o)[0])  # noqa: E731
    u32 = lambda o: int(np.frombuffer(data, end + "u4", 1, o)[0])  # noqa: E731
    ifd = u32(4)
    tags = {}
    for k in range(u16(ifd)):
        e = ifd + 2 + 12 * k
        tag, kind, count = u16(e), u16(e + 2), u32(e + 4)
        size = {3: 2, 4: 4}.get(kind, 1) * count
        at = e + 8 if size <= 4 else u32(e + 8)
        if kind == 3:
            vals = [u16(at + 2 * i) for i in range(count)]
        elif kind == 4:
            vals = [u32(at + 4 * i) for i in range(count)]
        else:
            vals = None
        tags[tag] = vals
    width, height = tags[256][0], tags[257][0]
    channels = tags.get(277, [1])[0]
    assert tags.get(259, [1])[0] == 1, f"{path}: compressed TIFF"
    assert tags.get(339, [3])[0] == 3 and tags[258][0] == 32, f"{path}: not 32-bit float"
    offsets, counts = tags[273], tags[279]
    raw = b"".join(data[o:o + c] for o, c in zip(offsets, counts))
    a = np.frombuffer(raw, end + "f4").reshape(height, width, channels)
    return a[:, :, 0] if channels == 1 else a
