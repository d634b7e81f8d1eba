"""The same sweep on a Dask cluster of 2 workers: chunks as tasks, the same dataset and rows."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.cli import main
from restitution.runs.dataset import read_dataset, read_manifest, sweep_to_dataset

distributed = pytest.importorskip("distributed")

CHEAP = rs.Scene(integrator="verlet", dt_factor=0.09)  # below the verlet bound of the 5- and 6-gon too
AXES: dict[str, Any] = {"theta_deg": np.linspace(5.0, 90.0, 18), "n": [0, 6], "omega_in": [-1.0, 0.0, 1.0]}


def test_dask_process_workers_write_the_local_dataset(tmp_path: Path) -> None:
    # Separate worker processes: the spec and the rows really travel (pickled) between them.
    local = sweep_to_dataset(CHEAP, tmp_path / "local", chunk_size=7, threads=2, **AXES)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = sweep_to_dataset(CHEAP, tmp_path / "dask", chunk_size=7, scheduler=client, **AXES)
    assert remote.chunks_written == local.chunks_written == 16
    assert_frame_equal(read_dataset(tmp_path / "dask"), read_dataset(tmp_path / "local"), check_exact=True)
    m_local, m_dask = read_manifest(tmp_path / "local"), read_manifest(tmp_path / "dask")
    assert m_local["spec_sha256"] == m_dask["spec_sha256"]
    names = sorted(p.name for p in (tmp_path / "dask").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "local").iterdir())


def test_cli_scheduler_address_and_resume_on_dask(tmp_path: Path) -> None:
    cfg = tmp_path / "c.toml"
    cfg.write_text('[scene]\nintegrator = "verlet"\ndt_factor = 0.09\n[axes]\ntheta_deg = { start = 5, stop = 90, step = 5 }\n'
                   "mu = [0.0, 0.5, 1.0]\n[sweep]\nchunk_size = 5\n")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        assert main(["sweep", str(cfg), "--out", str(tmp_path / "d"), "--scheduler", cluster.scheduler_address]) == 0
        full = read_dataset(tmp_path / "d")
        for k in (0, 4, 10):
            (tmp_path / "d" / f"part-{k:06d}.parquet").unlink()
        assert main(["sweep", str(cfg), "--out", str(tmp_path / "d"), "--resume",
                     "--scheduler", cluster.scheduler_address]) == 0
    assert_frame_equal(read_dataset(tmp_path / "d"), full, check_exact=True)
    local = rs.sweep(CHEAP, theta_deg=np.arange(5.0, 91.0, 5.0), mu=[0.0, 0.5, 1.0], threads=1)
    assert_frame_equal(full, local, check_exact=True)
