"""seasynth: ocean-wave and terrain height maps in meters, as numpy arrays.

The same library as the ``seasynth`` command line, and the same bits: a field made here
equals the samples of the float TIFF ``seasynth generate`` writes for the same
parameters. Heights are float32 arrays of shape (ny, nx) in meters; row j lies at
y_j = (j + o)·Ly/ny and column i at x_i = (i + o)·Lx/nx, with o = 0 (``sample_at =
"corners"``, the default) or 0.5 (``"centers"``).

    >>> import seasynth
    >>> f = seasynth.generate(preset="storm", size=256)
    >>> f.height.shape, round(float(4 * f.height.std()), 1) > 0
    ((256, 256), True)

Parameters are given as the command line gives them: a preset (a built-in name or a
TOML/JSON file), then keys applied in order, the last one winning. A key is a flag's
name (``wind_speed=12`` is ``--wind-speed 12``; ``_`` stands for ``-``) or any preset
key through a dict (``keys={"grid.size": [512, 256]}``, as ``--set``). Values are
numbers, strings, booleans, lists or dicts; strings read as the command line reads them
(``size="512x256"``, ``height_range="-2:2"``).

Bad input raises :class:`ParamError` (a ``ValueError``) with the command line's
one-line message; a job too large for the memory raises :class:`ResourceError` (a
``MemoryError``) before anything is allocated. The computation runs with the
interpreter released; Ctrl-C raises KeyboardInterrupt at the next check (every 0.1 s; tested under 1 s).
"""

from __future__ import annotations

import json
import math
import os
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _seasynth
from ._seasynth import ParamError, ResourceError

__version__: str = _seasynth.__version__

__all__ = [
    "Params",
    "Field",
    "generate",
    "Sea",
    "animate",
    "write_sequence",
    "spectrum",
    "analyze",
    "plan",
    "design",
    "run_job",
    "presets",
    "keep_freed_memory",
    "ParamError",
    "ResourceError",
]

#: Flag names (as the command line writes them) and the preset key each stands for.
FLAG_KEYS: Dict[str, str] = dict(_seasynth.flag_keys())

#: The maps ``generate`` and ``animate`` can add to a field.
MAPS = ("displacement", "normal", "jacobian", "foam")

PathLike = Union[str, "os.PathLike[str]"]


def keep_freed_memory() -> None:
    """Keeps freed memory in the process for reuse instead of returning it to the system
    (glibc; every thread then allocates from the main arena), as ``seasynth animate``
    does: a loop of ``generate`` or ``animate`` of one size reuses its buffers instead
    of paying a page fault per 4 KiB (measured 30 % faster at 4096²). Process-wide, and
    the memory stays with the process until it ends; call it once, early, in a worker
    that generates many sea states."""
    _seasynth.keep_freed_memory()


def presets() -> List[str]:
    """The names of the built-in presets (``seasynth presets`` lists them too)."""
    return list(_seasynth.presets())


def _toml(value: Any) -> str:
    """A value as the TOML text the command line would read for it."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    raise ParamError(f"{value!r}: a parameter value must be a number, string, boolean, list or dict")


def _text(value: Any) -> str:
    """A value as typed after a flag: a string as it is, anything else as TOML."""
    return value if isinstance(value, str) else _toml(value)


def _items(keys: Optional[Mapping[str, Any]], kwargs: Mapping[str, Any]) -> List[Tuple[str, str, str]]:
    """(key, value text, origin) assignments, in order: ``keys`` then ``kwargs``."""
    out = []
    for key, value in list((keys or {}).items()) + list(kwargs.items()):
        flag = key.replace("_", "-")
        if flag in FLAG_KEYS:
            text = _text(value)
            out.append((flag, text, f"--{flag} {text}"))
        else:
            text = _text(value)
            out.append((key, text, f"--set {key}={text}"))
    return out


class Params:
    """Resolved, validated parameters: a preset, then keys, as on the command line.

    ``Params(preset="storm", wind_speed=20, keys={"grid.size": [512, 512]})`` is
    ``--preset storm --set grid.size=[512,512] --wind-speed 20``. ``to_dict()`` gives the
    parameters the sidecars record, and ``Params.from_dict`` takes them back.
    """

    __slots__ = ("_core",)

    def __init__(self, preset: Optional[PathLike] = None, keys: Optional[Mapping[str, Any]] = None, **kwargs: Any):
        preset = None if preset is None else os.fspath(preset)
        self._core = _seasynth.Params(preset, _items(keys, kwargs))

    @classmethod
    def _of(cls, core: Any) -> "Params":
        p = cls.__new__(cls)
        p._core = core
        return p

    @classmethod
    def from_toml(cls, path: PathLike) -> "Params":
        """The parameters of a preset file (TOML, or a JSON sidecar)."""
        return cls(preset=path)

    @classmethod
    def from_dict(cls, params: Mapping[str, Any]) -> "Params":
        """The parameters of ``to_dict()`` (or of a sidecar's ``params``), validated."""
        return cls._of(_seasynth.Params.from_json(json.dumps(params)))

    def to_dict(self) -> Dict[str, Any]:
        """The fully resolved parameters, as sidecars record them."""
        return json.loads(self._core.to_json())

    def to_toml(self) -> str:
        """The parameters as a preset file (``seasynth generate --preset FILE`` reads it)."""
        return self._core.to_toml()

    def replace(self, keys: Optional[Mapping[str, Any]] = None, **kwargs: Any) -> "Params":
        """These parameters with more keys applied (the same rules), validated."""
        return Params._of(self._core.apply(_items(keys, kwargs)))

    @property
    def shape(self) -> Tuple[int, int]:
        """(ny, nx): the shape of the height arrays."""
        nx, ny, _, _, _ = self._core.grid()
        return (ny, nx)

    @property
    def extent_m(self) -> Tuple[float, float]:
        """(Lx, Ly) in meters."""
        _, _, lx, ly, _ = self._core.grid()
        return (lx, ly)

    def coords(self) -> Tuple[np.ndarray, np.ndarray]:
        """(x, y): the samples' coordinates in meters (float64), honouring ``sample_at``."""
        nx, ny, lx, ly, o = self._core.grid()
        return ((np.arange(nx) + o) * (lx / nx), (np.arange(ny) + o) * (ly / ny))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Params) and self._core == other._core

    def __hash__(self) -> int:
        return hash(self._core.to_json())

    def __reduce__(self):
        return (Params.from_dict, (self.to_dict(),))

    def __repr__(self) -> str:
        d = self.to_dict()
        grid = d.get("grid", {})
        return (
            f"seasynth.Params(method={d.get('method')!r}, size={grid.get('size')}, "
            f"extent_m={grid.get('extent_m')}, seed={d.get('seed')})"
        )


def _params(params: Optional[Params], preset: Optional[PathLike], keys: Optional[Mapping[str, Any]], kwargs: Mapping[str, Any]) -> Params:
    if params is None:
        return Params(preset, keys, **kwargs)
    if not isinstance(params, Params):
        raise ParamError(f"params must be a seasynth.Params (got {type(params).__name__})")
    if preset is not None:
        raise ParamError("give either params or preset, not both")
    return params.replace(keys, **kwargs) if (keys or kwargs) else params


def _maps(maps: Iterable[str]) -> List[str]:
    if isinstance(maps, str):
        maps = (maps,)
    return [str(m) for m in maps]


def _export_flags(up=None, exr_half=False, exr_compression=None, **more: Any) -> List[Tuple[str, str]]:
    flags = []
    if up is not None:
        flags.append(("--up", str(up)))
    if exr_compression is not None:
        flags.append(("--exr-compression", str(exr_compression)))
    if exr_half:
        flags.append(("--exr-half", ""))
    for key, value in more.items():
        if value is None or value is False:
            continue
        flags.append(("--" + key.replace("_", "-"), "" if value is True else _text(value)))
    return flags


class Field:
    """A synthesized field: heights in meters and the maps asked for.

    Every array is a read-only view of memory the library computed (no copy): ``height``
    (ny, nx) float32; ``displacement`` (ny, nx, 3) = (λDx, λDy, h) in meters, the values
    of ``NAME.disp.exr`` with ``--up z``; ``normal`` (ny, nx, 3) unit normals (x, y, z);
    ``jacobian`` (ny, nx); ``foam`` (ny, nx) coverage 0..1. A map not asked for is None.
    """

    __slots__ = ("_core", "_sidecar")

    def __init__(self, core: Any):
        self._core = core
        self._sidecar: Optional[Dict[str, Any]] = None

    @property
    def height(self) -> np.ndarray:
        return self._core.height

    @property
    def displacement(self) -> Optional[np.ndarray]:
        return self._core.displacement

    @property
    def normal(self) -> Optional[np.ndarray]:
        return self._core.normal

    @property
    def jacobian(self) -> Optional[np.ndarray]:
        return self._core.jacobian

    @property
    def foam(self) -> Optional[np.ndarray]:
        return self._core.foam

    @property
    def params(self) -> Params:
        """The parameters of this field, its time included."""
        return Params._of(self._core.params)

    @property
    def time(self) -> float:
        """The time of this field, seconds."""
        return float(self.params.to_dict()["time_s"])

    @property
    def x(self) -> np.ndarray:
        """x of every column, meters."""
        return self.params.coords()[0]

    @property
    def y(self) -> np.ndarray:
        """y of every row, meters."""
        return self.params.coords()[1]

    def sidecar(self) -> Dict[str, Any]:
        """The JSON sidecar ``seasynth generate`` writes beside this field (without the
        list of files): tool, version, parameters, statistics, synthesis details."""
        if self._sidecar is None:
            self._sidecar = json.loads(self._core.sidecar_json())
        return json.loads(json.dumps(self._sidecar))

    @property
    def stats(self) -> Dict[str, float]:
        """min_m, max_m, mean_m, std_m and hs_m (= 4·std) of the heights."""
        return dict(self.sidecar()["stats"])

    def write(self, *paths: PathLike, up: Optional[str] = None, exr_half: bool = False,
              exr_compression: Optional[str] = None, threads: Optional[int] = None,
              **export: Any) -> List[str]:
        """Writes the field to every path, the format by extension (``.png``, ``.tif``,
        ``.exr``, ``.r16``, ``.obj``, ``.glb``, maps as ``NAME.normal.png``, …), each with
        its sidecar, exactly as ``seasynth generate -o PATH…`` does. Export flags as
        keywords: ``up="z"``, ``exr_half=True``, ``exr_compression="zip"``,
        ``engine="unity"``, ``tiles="2x2"``, ``mesh_step=2``, …. Files are staged and
        appear only when complete. Returns the paths written."""
        if not paths:
            raise ParamError("write needs at least one path")
        flags = _export_flags(up, exr_half, exr_compression, **export)
        written = self._core.write([os.fspath(p) for p in paths], flags, threads)
        return [os.fspath(p) for p in written]

    def to_xarray(self, name: str = "height"):
        """The heights as an ``xarray.DataArray`` with dims (y, x), coordinates in meters
        and the sidecar's parameters and statistics as attributes (needs xarray)."""
        try:
            import xarray as xr
        except ImportError as e:  # pragma: no cover - exercised without xarray
            raise ImportError("Field.to_xarray needs the package xarray: pip install xarray") from e
        side = self.sidecar()
        attrs = {"units": "m", "long_name": "sea surface height", "seasynth_version": side.get("version", "")}
        attrs["params"] = json.dumps(side["params"])
        for k, v in side["stats"].items():
            attrs[k] = v
        x, y = self.params.coords()
        return xr.DataArray(
            self.height,
            dims=("y", "x"),
            coords={"x": ("x", x, {"units": "m"}), "y": ("y", y, {"units": "m"})},
            name=name,
            attrs=attrs,
        )

    def __repr__(self) -> str:
        ny, nx = self.height.shape
        maps = [m for m in MAPS if getattr(self._core, m) is not None]
        return f"seasynth.Field({ny}x{nx}, t={self.time} s, maps={maps})"


def generate(params: Optional[Params] = None, *, preset: Optional[PathLike] = None,
             keys: Optional[Mapping[str, Any]] = None, maps: Sequence[str] = (),
             threads: Optional[int] = None, resample: bool = True, **kwargs: Any) -> Field:
    """The field of ``params`` (or of ``preset`` and keys), at its ``time``.

    ``maps``: any of ``"displacement"``, ``"normal"``, ``"jacobian"``, ``"foam"`` (the
    values of the map files of the same field). ``threads``: worker threads (default:
    every core); the result has the same bits on any number. Keys as for
    :class:`Params` (``size=1024``, ``wind_speed=12``, ``choppiness=1``, ``time=3.5``, …).
    ``resample=False``: a choppy field's ``height`` is the surface before the horizontal
    displacement (``displacement[..., 2]``) and the resampling onto the grid is skipped,
    for a host that moves vertices by ``displacement`` itself.
    """
    p = _params(params, preset, keys, kwargs)
    return Field(_seasynth.generate(p._core, _maps(maps), threads, resample))


class Sea:
    """One sea prepared once, for frames at any time: ``Sea(...).frame(t)`` is
    ``generate(..., time=t)`` bit for bit, without redoing the preparation each time
    (the random draws, and a looping second-order sea's pairs, summed once by their
    multiples of 2π/T). For a host that asks for frames out of order (a timeline).
    Arguments as for :func:`generate`."""

    __slots__ = ("_core", "params")

    def __init__(self, params: Optional[Params] = None, *, preset: Optional[PathLike] = None,
                 keys: Optional[Mapping[str, Any]] = None, maps: Sequence[str] = (),
                 threads: Optional[int] = None, resample: bool = True, **kwargs: Any):
        self.params = _params(params, preset, keys, kwargs)
        self._core = _seasynth.SeaCore(self.params._core, _maps(maps), threads, resample)

    def frame(self, time: float) -> Field:
        """The field at ``time`` seconds."""
        return Field(self._core.frame(float(time)))

    def __repr__(self) -> str:
        return f"seasynth.Sea({self.params!r})"


class _Frames:
    """The frames of :func:`animate`: an iterator of :class:`Field`."""

    def __init__(self, core: Any, frames: int):
        self._core = core
        self._frames = frames

    def __iter__(self) -> "_Frames":
        return self

    def __next__(self) -> Field:
        core = self._core.__next__()
        if core is None:
            raise StopIteration
        return Field(core)

    def __len__(self) -> int:
        return self._frames

    def close(self) -> None:
        """Stops the sequence (the frame computed ahead is dropped)."""
        self._core.close()

    def __enter__(self) -> "_Frames":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def animate(params: Optional[Params] = None, *, frames: int, fps: Optional[float] = None,
            preset: Optional[PathLike] = None, keys: Optional[Mapping[str, Any]] = None,
            maps: Sequence[str] = (), threads: Optional[int] = None, resample: bool = True,
            **kwargs: Any) -> Iterator[Field]:
    """The frames 0 … frames − 1 of a sequence, frame k at t = time + k/fps: an iterator
    of :class:`Field`, bit for bit the frames of ``seasynth animate`` (with foam, the
    sequence's one threshold and, with ``foam_fade``, its persistent foam). The next
    frame is computed while the caller uses the current one. ``resample`` as for
    :func:`generate`."""
    if fps is not None:
        kwargs["fps"] = fps
    p = _params(params, preset, keys, kwargs)
    return _Frames(_seasynth.animate(p._core, int(frames), _maps(maps), threads, resample), int(frames))


def write_sequence(params: Optional[Params], dir: PathLike, *, frames: int,
                   formats: Sequence[str] = ("png",), up: Optional[str] = None,
                   exr_half: bool = False, exr_compression: Optional[str] = None,
                   start_frame: Optional[int] = None, resume: bool = False,
                   threads: Optional[int] = None, **kwargs: Any) -> Tuple[int, int]:
    """Writes the frames of a sequence into ``dir`` as ``seasynth animate --frames N
    --format F,… -o DIR`` does: the same files (``frame_00001.disp.exr``, …) and
    ``DIR/sequence.json``. ``formats``: ``png``, ``tif``, ``exr``, ``normal``, ``foam``,
    ``jacobian``, ``disp``, ``disp.exr``, ``normal.exr``, ``foam.exr``,
    ``jacobian.exr``, ``preview``. Returns (frames written, frames kept by ``resume``)."""
    p = _params(params, None, None, kwargs)
    if isinstance(formats, str):
        formats = formats.split(",")
    flags = _export_flags(up, exr_half, exr_compression)
    return tuple(_seasynth.write_sequence(p._core, os.fspath(dir), int(frames), list(formats), flags,
                                          start_frame, resume, threads))


def spectrum(params: Optional[Params] = None, *, freq: Optional[Sequence[float]] = None,
             preset: Optional[PathLike] = None, keys: Optional[Mapping[str, Any]] = None,
             **kwargs: Any) -> Dict[str, Any]:
    """The model's one-sided frequency spectrum F(f) in m²/Hz: the report of ``seasynth
    spectrum --json`` with ``f_hz`` and ``s_m2_per_hz`` as arrays (at ``freq``, default
    200 frequencies from 0.2·fp to 10·fp), and ``hs_m``, ``fp_hz``, ``tp_s``, ``m0_m2``,
    ``kp_rad_per_m``, ``peak_wavelength_m``, ``params``."""
    p = _params(params, preset, keys, kwargs)
    if freq is None:
        fp = json.loads(_seasynth.spectrum_json(p._core, [1.0]))["fp_hz"]
        freq = np.geomspace(0.2 * fp, 10 * fp, 200)
    f = np.asarray(freq, dtype=np.float64).ravel()
    report = json.loads(_seasynth.spectrum_json(p._core, [float(v) for v in f]))
    points = report.pop("points")
    report["f_hz"] = np.array([pt["f_hz"] for pt in points])
    report["s_m2_per_hz"] = np.array([pt["s_m2_per_hz"] for pt in points])
    return report


def analyze(data: Union[PathLike, np.ndarray, Field], *, extent: Union[None, float, Tuple[float, float]] = None,
            height_range: Optional[str] = None) -> Dict[str, Any]:
    """The report of ``seasynth analyze --json``: statistics, skewness and kurtosis,
    slopes, the measured spectrum's peak, wave-by-wave and crest statistics.

    ``data``: a file (any height map seasynth reads; ``extent`` and ``height_range`` as
    the command line's ``--extent`` and ``--height-range``), a :class:`Field`, or a 2-D
    array of heights in meters (rows along y) with ``extent`` = L or (Lx, Ly) in meters.
    An array of another float or integer type is converted to float32; one that is not
    2-D or holds non-finite values is refused."""
    if isinstance(data, Field):
        if extent is None:
            extent = data.params.extent_m
        data = data.height
    if isinstance(data, (str, os.PathLike)):
        options = []
        if extent is not None:
            options.append(("--extent", extent if isinstance(extent, str) else _extent_text(extent)))
        if height_range is not None:
            options.append(("--height-range", str(height_range)))
        return json.loads(_seasynth.analyze_file(os.fspath(data), options))
    a = np.asarray(data)
    if a.ndim != 2:
        raise ParamError(f"the heights must be a 2-D array (got {a.ndim} dimensions, shape {a.shape})")
    if not (np.issubdtype(a.dtype, np.floating) or np.issubdtype(a.dtype, np.integer)):
        raise ParamError(f"the heights must be numbers in meters (got dtype {a.dtype})")
    if extent is None:
        raise ParamError("analyzing an array needs extent=L or (Lx, Ly) in meters")
    lx, ly = (extent, extent) if np.isscalar(extent) else tuple(extent)
    a = np.ascontiguousarray(a, dtype=np.float32)
    return json.loads(_seasynth.analyze_array(a, float(lx), float(ly)))


def _extent_text(extent: Union[float, Tuple[float, float]]) -> str:
    if np.isscalar(extent):
        return repr(float(extent))
    lx, ly = extent
    return f"{float(lx)!r}x{float(ly)!r}"


def _keys_doc() -> str:
    """The flag keys and their values in the default preset, for the docstrings."""
    defaults = Params().to_dict()
    lines = ["", "Keys (a flag's name with _ for -, the preset key it sets, its value in the default", "preset li-tian):", ""]
    for flag, key in FLAG_KEYS.items():
        value: Any = defaults
        for part in key.split("."):
            value = value.get(part) if isinstance(value, dict) else None
        lines.append(f"    {flag.replace('-', '_'):<16} {key:<26} {json.dumps(value)}")
    lines.append("")
    lines.append("Any other preset key goes through keys={...}; docs/parameters.md lists them all.")
    return "\n".join(lines)


_KEYS = _keys_doc()
for _f in (generate, animate, Params):
    _f.__doc__ = (_f.__doc__ or "") + _KEYS

from ._batch import design, plan, run_job  # noqa: E402  (uses the names above)
