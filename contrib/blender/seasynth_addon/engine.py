"""Every call into the `seasynth` Python module, in one place.

The rest of the add-on asks this module for parameters, frames and bakes, so a change in
the module's names is a change here only. Errors in parameters come back as `SeaError`,
whose text is seasynth's own one-line message (`--wind-speed (wind.speed_mps) must be
> 0 and ≤ 100 m/s (got -3)`).
"""

import os
import sys
import threading

# A wheel installed into the add-on itself (pip install --no-deps --target
# seasynth_addon/_vendor seasynth-*.whl) is found first; otherwise Blender's sys.path
# (PYTHONPATH, the user scripts' modules folder, the bundled Python's site-packages).
_VENDOR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_vendor")
if os.path.isdir(_VENDOR) and _VENDOR not in sys.path:
    sys.path.insert(0, _VENDOR)

try:
    import seasynth as _ss
except ImportError as e:  # the add-on still registers and says what is missing
    _ss = None
    IMPORT_ERROR = str(e)
else:
    IMPORT_ERROR = ""


class SeaError(ValueError):
    """A parameter seasynth refuses, or the module missing; str() is one line."""


def available():
    return _ss is not None


def missing_message():
    return (
        "the seasynth Python module is not found by Blender's Python "
        f"({IMPORT_ERROR}); see docs/blender.md, Install"
    )


def _module():
    if _ss is None:
        raise SeaError(missing_message())
    return _ss


def _wrap(call, *args, **kwargs):
    ss = _module()
    try:
        return call(*args, **kwargs)
    except ss.ParamError as e:
        raise SeaError(str(e)) from None
    except MemoryError as e:  # seasynth.ResourceError: a sea too large for the memory
        raise SeaError(str(e) or "not enough memory for this sea") from None
    except (ValueError, TypeError, OverflowError) as e:
        # A value Python could not hand to seasynth at all (a negative size, say).
        raise SeaError(str(e)) from None


def version():
    return getattr(_ss, "__version__", "?") if _ss is not None else ""


def params(preset, keys):
    """Parameters as the command line makes them: `preset`, then `keys` in order, each a
    flag's name (`wind_speed`: `--wind-speed`) or a preset key (`motion.fps`: `--set`),
    the last one winning. A `seasynth.Params`."""
    return _wrap(_module().Params, preset=preset, keys=keys)


def params_from_dict(d):
    return _wrap(_module().Params.from_dict, d)


def replace(p, keys=None, **flags):
    """`p` with more keys applied (the same rules as `params`)."""
    return _wrap(p.replace, keys, **flags)


def resolved(p):
    """The fully resolved parameters (what a sidecar's `params` holds)."""
    return p.to_dict()


# The seas prepared most recently (parameters, maps, `seasynth.Sea`): scrubbing the
# timeline asks for frames out of order, and each comes from the prepared sea.
_SEAS = []
_SEAS_KEPT = 2
_SEAS_LOCK = threading.Lock()


def _sea(p, maps):
    with _SEAS_LOCK:
        for q, m, sea in _SEAS:
            if m == maps and q == p:
                return sea
    sea = _wrap(_module().Sea, p, maps=maps, resample="displacement" not in maps)
    with _SEAS_LOCK:
        _SEAS.append((p, maps, sea))
        del _SEAS[:-_SEAS_KEPT]
    return sea


def frame(p, time_s, maps):
    """The sea at `time_s` seconds, with the extra `maps` ("displacement", "normal",
    "foam"): a frame with `height`, `displacement`, `normal`, `foam` (numpy float32,
    rows along y), `stats` and `sidecar()`. With the displacement the vertices move by
    it, so the choppy heights are not resampled onto the grid (`resample=False`). The
    frame of a prepared `seasynth.Sea` (the draws, and a looping second-order sea's
    pairs, made once for the parameters): `generate` at that time, bit for bit."""
    return _wrap(_sea(p, tuple(maps)).frame, time_s)


def write_sequence(p, folder, frames, formats, start_frame, up="z", exr_half=False, exr_compression="zip"):
    """The files of `seasynth animate --format FORMATS --up UP --start-frame START -o FOLDER`."""
    return _wrap(
        _module().write_sequence,
        p,
        folder,
        frames=frames,
        formats=list(formats),
        up=up,
        start_frame=start_frame,
        exr_half=exr_half,
        exr_compression=exr_compression,
    )
