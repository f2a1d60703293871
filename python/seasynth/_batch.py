"""Batch plans and random designs as plain Python rows (no pandas needed), and one row
computed exactly as ``seasynth batch`` computes it: the functions a Dask or Ray user
maps over a design."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _seasynth
from . import Field, Params, ParamError, PathLike, _items, generate


def _sweep_text(key: str, values: Any) -> str:
    """``KEY=A,B,C`` or ``KEY=START:STOP:STEP`` from a list or a string."""
    if isinstance(values, str):
        return f"{key}={values}"
    return f"{key}=" + ",".join(str(v) for v in values)


def plan(preset: Optional[PathLike] = None, *, keys: Optional[Mapping[str, Any]] = None,
         sweep: Optional[Mapping[str, Any]] = None, sample: Optional[int] = None,
         vary: Optional[Mapping[str, str]] = None, design: str = "random",
         design_seed: Optional[int] = None, name: Optional[str] = None,
         **kwargs: Any) -> List[Dict[str, Any]]:
    """The jobs of ``seasynth batch``, in order, as a list of dicts: ``job`` (index),
    ``name`` (the file stem), ``seed``, ``values`` (each swept or designed key as the
    plan prints it), ``params`` (the job's fully resolved parameters, the dict of
    :meth:`Params.to_dict`) or ``error``.

    ``sweep={"wind-dir": [0, 90, 180], "seed": "1:5:1"}`` is ``--sweep wind-dir=0,90,180
    --sweep seed=1:5:1``; ``sample=100, vary={"wind-speed": "uniform:5:20"},
    design="lhs"`` is ``--sample 100 --vary wind-speed=uniform:5:20 --design lhs``.
    Base keys as for :class:`Params`."""
    sweeps = [_sweep_text(k, v) for k, v in (sweep or {}).items()]
    varies = [f"{k}={v}" for k, v in (vary or {}).items()]
    text = _seasynth.plan_json(
        None if preset is None else os.fspath(preset),
        _items(keys, kwargs),
        sweeps,
        sample,
        varies,
        design,
        None if design_seed is None else str(design_seed),
        name,
    )
    doc = json.loads(text)
    rows = []
    for r in doc["rows"]:
        row = {"job": r["job"], "name": r["name"], "seed": r.get("seed"), "values": r["params"]}
        if "parameters" in r:
            row["params"] = r["parameters"]
        if r.get("error"):
            row["error"] = r["error"]
        rows.append(row)
    return rows


def design(n: int, vary: Mapping[str, str], *, kind: str = "lhs", design_seed: Optional[int] = None,
           preset: Optional[PathLike] = None, keys: Optional[Mapping[str, Any]] = None,
           name: Optional[str] = None, **kwargs: Any) -> List[Dict[str, Any]]:
    """A random design of ``n`` sea states (``kind`` = ``"random"`` or ``"lhs"``):
    :func:`plan` with ``sample=n``. ``vary={"wind-speed": "uniform:5:20",
    "wind-dir": "uniform:0:360"}``; the design seed defaults to the base parameters'
    seed."""
    return plan(preset, keys=keys, sample=n, vary=vary, design=kind, design_seed=design_seed,
                name=name, **kwargs)


def run_job(row: Mapping[str, Any], *, maps: Sequence[str] = (), threads: Optional[int] = None,
            dir: Optional[PathLike] = None, formats: Sequence[str] = ()) -> Field:
    """The field of one row of :func:`plan` or :func:`design`: the same bits as the
    file ``seasynth batch`` writes for that job. With ``dir`` and ``formats`` (e.g.
    ``("tif",)``), also writes ``DIR/NAME.tif`` and its sidecar."""
    if "params" not in row:
        raise ParamError(f"job {row.get('job')} {row.get('name')}: {row.get('error', 'no parameters')}")
    field = generate(Params.from_dict(row["params"]), maps=maps, threads=threads)
    if dir is not None and formats:
        os.makedirs(dir, exist_ok=True)
        field.write(*[os.path.join(os.fspath(dir), f"{row['name']}.{f}") for f in formats], threads=threads)
    return field
