"""A Latin-hypercube design of sea states run through Dask into one Zarr store.

    python python/examples/dask_design.py STORE [N] [SIZE] [--workers W] [--scheduler ADDRESS]

Each sea state is one chunk of the array ``height`` (state, y, x), float32 meters,
computed by :func:`seasynth.run_job` on whichever worker Dask gives it; the design's
varied values and every state's seed, wind and Hs are coordinates along ``state``, and
the full parameters of every state are in the attribute ``params`` (a JSON list). The
same code runs on a laptop (a LocalCluster of W workers, the default) and on a real
cluster (``--scheduler tcp://host:8786``, or a ``dask.distributed.Client`` of your own
passed to :func:`run_design`).
"""

from __future__ import annotations

import json
import sys
from typing import Any, Dict, List, Optional

import numpy as np

import seasynth

#: The design of the example: wind speed and direction, peak enhancement and seed vary.
VARY = {
    "wind-speed": "uniform:5:25",
    "wind-dir": "uniform:0:360",
    "gamma": "uniform:1:7",
    "seed": "int:0:1000000000",
}


def make_design(n: int, size: int, design_seed: int = 1) -> List[Dict[str, Any]]:
    """n JONSWAP sea states on a size² FFT grid over 1024 m, Latin hypercube."""
    return seasynth.design(n, VARY, kind="lhs", design_seed=design_seed, method="fft",
                           spectrum="jonswap", fetch_km=200, size=size, extent=1024)


def heights_of(row: Dict[str, Any]) -> np.ndarray:
    """The heights of one row, float32 (y, x): a pure function of the row (its seed)."""
    return seasynth.run_job(row, threads=1).height.copy()


def write_one(row: Dict[str, Any], store: str, index: int) -> int:
    """Computes row `index` and writes it into its own chunk of `store`."""
    import zarr

    arr = zarr.open_array(store, path="height", mode="r+")
    arr[index] = heights_of(row)
    return index


def run_design(rows: List[Dict[str, Any]], store: str, client=None) -> str:
    """Writes every row's heights into the Zarr `store`, one chunk per sea state, on the
    Dask `client`'s workers (None: the current scheduler, or in this process), with the
    rows' values as coordinates. Returns `store`."""
    import dask.bag as db
    import zarr

    ny, nx = seasynth.Params.from_dict(rows[0]["params"]).shape
    root = zarr.open_group(store, mode="w")
    height = root.create_array("height", shape=(len(rows), ny, nx), chunks=(1, ny, nx), dtype="f4") \
        if hasattr(root, "create_array") else root.create_dataset("height", shape=(len(rows), ny, nx), chunks=(1, ny, nx), dtype="f4")
    height.attrs["_ARRAY_DIMENSIONS"] = ["state", "y", "x"]
    height.attrs["units"] = "m"
    height.attrs["params"] = json.dumps([r["params"] for r in rows])
    x, y = seasynth.Params.from_dict(rows[0]["params"]).coords()
    coords = {"x": x, "y": y, "state": np.arange(len(rows))}
    p = [r["params"] for r in rows]
    coords["seed"] = np.array([q["seed"] for q in p], dtype=np.uint64)
    coords["wind_speed_mps"] = np.array([q["wind"]["speed_mps"] for q in p])
    coords["wind_direction_deg"] = np.array([q["wind"]["direction_deg"] for q in p])
    coords["gamma"] = np.array([q["spectrum"]["gamma"] for q in p])
    for name, values in coords.items():
        dim = name if name in ("x", "y") else "state"
        a = root.create_array(name, shape=values.shape, dtype=values.dtype) if hasattr(root, "create_array") \
            else root.create_dataset(name, shape=values.shape, dtype=values.dtype)
        a[:] = values
        a.attrs["_ARRAY_DIMENSIONS"] = [dim]
        if name in ("x", "y"):
            a.attrs["units"] = "m"
    height.attrs["coordinates"] = " ".join(k for k in coords if k not in ("x", "y", "state"))
    bag = db.from_sequence(list(enumerate(rows)), npartitions=max(1, min(len(rows), 64)))
    done = bag.map(lambda ir: write_one(ir[1], store, ir[0]))
    if client is not None:
        written = client.compute(done).result()
    else:
        written = done.compute()
    assert sorted(written) == list(range(len(rows)))
    return store


def main(argv: Optional[List[str]] = None) -> None:
    args = list(sys.argv[1:] if argv is None else argv)
    workers, scheduler = 2, None
    if "--workers" in args:
        i = args.index("--workers")
        workers = int(args[i + 1])
        del args[i:i + 2]
    if "--scheduler" in args:
        i = args.index("--scheduler")
        scheduler = args[i + 1]
        del args[i:i + 2]
    store = args[0]
    n = int(args[1]) if len(args) > 1 else 10_000
    size = int(args[2]) if len(args) > 2 else 256
    from dask.distributed import Client, LocalCluster

    if scheduler:
        client = Client(scheduler)
    else:
        client = Client(LocalCluster(n_workers=workers, threads_per_worker=1))
    rows = make_design(n, size)
    run_design(rows, store, client)
    print(f"wrote {n} sea states of {size}² to {store}")
    client.close()


if __name__ == "__main__":
    main()
