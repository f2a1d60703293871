"""Bad input raises ParamError with the command line's one-line message and writes
nothing; a job too large raises ResourceError before allocating; Ctrl-C stops a long
computation within about a second."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import seasynth

# (keywords for generate, the same as command-line flags).
BAD = [
    ({"wind_speed": -3}, ["--wind-speed", "-3"]),
    ({"size": 0}, ["--size", "0"]),
    ({"size": "0x64"}, ["--size", "0x64"]),
    ({"method": "fourier"}, ["--method", "fourier"]),
    ({"spectrum": "jonswop"}, ["--spectrum", "jonswop"]),
    ({"extent": float("inf")}, ["--extent", "inf"]),
    ({"wind_speed": float("nan")}, ["--wind-speed", "nan"]),
    ({"spectrum": "tma"}, ["--spectrum", "tma"]),
    ({"hs": 3}, ["--hs", "3"]),
    ({"fps": 0}, ["--fps", "0"]),
    ({"loop_period": -5}, ["--loop-period", "-5"]),
    ({"gamma": 0}, ["--gamma", "0"]),
    ({"sample_at": "middle"}, ["--sample-at", "middle"]),
    ({"wind_sped": 3}, ["--set", "wind_sped=3"]),
    ({"keys": {"perlin.octaves": 0}}, ["--set", "perlin.octaves=0"]),
]


@pytest.mark.parametrize("keys,flags", BAD, ids=[" ".join(b[1]) for b in BAD])
def test_bad_input_raises_the_cli_message(cli, tmp_path, keys, flags):
    out = cli("generate", *flags, "-o", tmp_path / "a.tif", check=False)
    assert out.returncode == 2, out.stderr
    want = out.stderr.strip().splitlines()[-1].removeprefix("Error: ")
    with pytest.raises(seasynth.ParamError) as e:
        seasynth.generate(**keys)
    assert isinstance(e.value, ValueError)
    assert str(e.value) == want
    assert "\n" not in str(e.value)
    assert not (tmp_path / "a.tif").exists()


def test_a_bad_output_path_writes_nothing(tmp_path):
    f = seasynth.generate(size=16)
    with pytest.raises(seasynth.ParamError, match="a.xyz"):
        f.write(tmp_path / "a.tif", tmp_path / "a.xyz")
    assert os.listdir(tmp_path) == []


def test_a_field_too_large_for_memory_raises_resource_error_before_allocating():
    with pytest.raises(seasynth.ResourceError) as e:
        seasynth.generate(method="fft", size=32768, choppiness=1, maps=("displacement", "normal", "jacobian", "foam"))
    assert isinstance(e.value, MemoryError)
    assert "needs about" in str(e.value) and "is available" in str(e.value)


def test_arrays_of_the_wrong_kind_are_refused():
    with pytest.raises(seasynth.ParamError, match="2-D"):
        seasynth.analyze(np.zeros(16), extent=10)
    with pytest.raises(seasynth.ParamError, match="dtype"):
        seasynth.analyze(np.zeros((8, 8), complex), extent=10)
    with pytest.raises(seasynth.ParamError, match="finite"):
        a = np.zeros((8, 8), np.float32)
        a[3, 5] = np.nan
        seasynth.analyze(a, extent=10)
    with pytest.raises(seasynth.ParamError, match="extent"):
        seasynth.analyze(np.zeros((8, 8)), extent=-1)
    with pytest.raises(seasynth.ParamError, match="extent"):
        seasynth.analyze(np.zeros((8, 8)))
    with pytest.raises(seasynth.ParamError, match="maps"):
        seasynth.generate(size=8, maps=("curl",))
    with pytest.raises(seasynth.ParamError, match="threads"):
        seasynth.generate(size=8, threads=0)


def seconds_to_interrupt(body):
    """Runs `body` (Python that prints "ready" and then works for minutes, printing
    "interrupted T" on KeyboardInterrupt) in a child, sends it SIGINT a second after
    "ready", and returns how long the KeyboardInterrupt took to come."""
    p = subprocess.Popen([sys.executable, "-c", textwrap.dedent(body)], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "ready"
    time.sleep(1.0)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    line = p.stdout.readline().split()
    p.wait(timeout=60)
    assert line and line[0] == "interrupted", line
    return float(line[1]) - sent


def test_ctrl_c_stops_a_long_generate_within_a_second():
    took = seconds_to_interrupt(
        """
        import time, seasynth
        print("ready", flush=True)
        try:
            # Minutes of work: a 4096² trochoid sea of many components.
            seasynth.generate(method="trochoid", size=4096, keys={"trochoid.components": 4096})
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
        """
    )
    assert took < 1.0, f"KeyboardInterrupt came {took:.2f} s after Ctrl-C"


def test_ctrl_c_stops_an_animation():
    took = seconds_to_interrupt(
        """
        import time, seasynth
        frames = seasynth.animate(method="trochoid", size=2048, keys={"trochoid.components": 2048}, frames=100)
        print("ready", flush=True)
        try:
            for f in frames:
                pass
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
        """
    )
    assert took < 1.0, f"KeyboardInterrupt came {took:.2f} s after Ctrl-C"
