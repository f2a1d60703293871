"""The Dask recipe (python/examples/dask_design.py): a small LHS design on a
LocalCluster of 2 workers writes Zarr whose every sea state equals the serial
`generate` of its row, byte for byte."""

import json
import pathlib
import sys

import numpy as np
import pytest

import seasynth

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))


def test_a_design_through_a_local_cluster_equals_the_serial_fields(tmp_path):
    pytest.importorskip("dask.bag", reason="dask is not installed")
    distributed = pytest.importorskip("dask.distributed", reason="dask.distributed is not installed")
    zarr = pytest.importorskip("zarr", reason="zarr is not installed")
    import dask_design

    rows = dask_design.make_design(12, 64)
    assert len(rows) == 12 and all("params" in r for r in rows)
    # LHS: each varied value falls in a different twelfth of its range.
    speeds = sorted(r["params"]["wind"]["speed_mps"] for r in rows)
    assert [int((s - 5) / 20 * 12) for s in speeds] == list(range(12))
    store = str(tmp_path / "design.zarr")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            dask_design.run_design(rows, store, client)
    root = zarr.open_group(store, mode="r")
    height = root["height"]
    assert height.shape == (12, 64, 64) and height.chunks == (1, 64, 64)
    params = json.loads(height.attrs["params"])
    for k, row in enumerate(rows):
        serial = seasynth.generate(seasynth.Params.from_dict(row["params"])).height
        assert np.asarray(height[k]).tobytes() == serial.tobytes(), f"state {k}"
        assert params[k] == row["params"]
    assert list(np.asarray(root["seed"][:])) == [r["params"]["seed"] for r in rows]
