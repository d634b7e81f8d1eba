"""Sweeps streamed to a Parquet dataset: read back in case order, resumed after a kill or a
Ctrl-C with exactly the rows of an uninterrupted run, and refused when the spec changed."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.cli import main
from restitution.runs.config import load_config
from restitution.runs.dataset import (MANIFEST, missing_chunks, read_dataset, read_manifest, sweep_to_dataset)

CHEAP = rs.Scene(integrator="verlet", dt_factor=0.09)  # below the verlet bound of the 5- and 6-gon too
AXES: dict[str, Any] = {"theta_deg": np.linspace(5.0, 90.0, 18), "mu": [0.0, 0.5, 1.0]}

# A sweep slow enough (about half a second on one free core) to be caught mid-way by a kill.
SLOW_CONFIG = """
[scene]
mu = 0.3
dt_factor = 0.002
[axes]
omega_in = { start = -0.5, stop = 0.5, num = 6 }
theta_deg = { start = 4, stop = 89, step = 1 }
[sweep]
chunk_size = 8
"""


def test_dataset_reads_back_the_in_memory_sweep(tmp_path: Path) -> None:
    result = sweep_to_dataset(CHEAP, tmp_path / "d", chunk_size=1, **AXES)
    assert (result.n_cases, result.n_chunks, result.chunks_written) == (54, 54, 54)
    assert_frame_equal(read_dataset(tmp_path / "d"), rs.sweep(CHEAP, **AXES), check_exact=True)
    m = read_manifest(tmp_path / "d")
    assert m["restitution_version"] == rs.__version__ and m["integrator"] == "verlet"
    assert m["spec"]["scene"]["mu"] == CHEAP.mu and m["spec"]["axes"]["mu"] == [0.0, 0.5, 1.0]
    meta = pl.read_parquet_metadata(tmp_path / "d" / "part-000007.parquet")
    assert json.loads(meta["restitution.chunk"])["start"] == 7
    assert json.loads(meta["restitution.spec"])["scene"]["dt_factor"] == 0.09
    assert meta["restitution.version"] == rs.__version__


def test_resume_recomputes_only_missing_or_damaged_chunks(tmp_path: Path) -> None:
    d = tmp_path / "d"
    sweep_to_dataset(CHEAP, d, chunk_size=5, **AXES)
    full = read_dataset(d)
    (d / "part-000002.parquet").unlink()
    (d / "part-000004.parquet").write_bytes(b"PAR1 not a parquet file")  # e.g. a disk fault
    before = (d / "part-000003.parquet").stat().st_mtime_ns
    stale = d / ".part-000006.parquet.999999999.1.tmp"  # a dead writer's leftover
    stale.write_bytes(b"partial")
    assert missing_chunks(d) == [2]
    with pytest.raises(ValueError, match="incomplete: 1 of 11 chunks missing"):
        read_dataset(d)
    result = sweep_to_dataset(CHEAP, d, resume=True, **AXES)
    assert (result.chunks_written, result.chunks_skipped) == (2, 9)
    assert (d / "part-000003.parquet").stat().st_mtime_ns == before
    assert not stale.exists()
    assert_frame_equal(read_dataset(d), full, check_exact=True)


def test_resume_refuses_a_changed_spec_naming_the_difference(tmp_path: Path) -> None:
    d = tmp_path / "d"
    sweep_to_dataset(CHEAP, d, chunk_size=10, **AXES)
    with pytest.raises(ValueError, match="already holds a sweep"):
        sweep_to_dataset(CHEAP, d, **AXES)
    with pytest.raises(ValueError, match=r"differs at axes.mu \(dataset: \[0.0, 0.5, 1.0\], now: \[0.0, 0.5\]\)"):
        sweep_to_dataset(CHEAP, d, resume=True, theta_deg=AXES["theta_deg"], mu=[0.0, 0.5])
    with pytest.raises(ValueError, match=r"differs at scene.gamma \(dataset: 0.33, now: 0.2\)"):
        sweep_to_dataset(CHEAP.replace(gamma=0.2), d, resume=True, **AXES)
    with pytest.raises(ValueError, match=r"differs at axis order"):
        sweep_to_dataset(CHEAP, d, resume=True, mu=AXES["mu"], theta_deg=AXES["theta_deg"])
    with pytest.raises(ValueError, match=r"differs at sweep.chunk_size \(dataset: 10, now: 3\)"):
        sweep_to_dataset(CHEAP, d, resume=True, chunk_size=3, **AXES)
    theta = AXES["theta_deg"].copy()
    theta[7] += 1e-9
    with pytest.raises(ValueError, match=r"differs at axes.theta_deg\[7\]"):
        sweep_to_dataset(CHEAP, d, resume=True, theta_deg=theta, mu=AXES["mu"])


def test_cases_table_dataset_and_its_resume_check(tmp_path: Path) -> None:
    cases = pl.DataFrame({"theta_deg": [10.0, 45.0, 80.0, 30.0], "omega_in": [0.0, 1.0, -1.0, 0.5], "n": [0, 0, 7, 7]})
    d = tmp_path / "d"
    sweep_to_dataset(CHEAP, d, cases=cases, chunk_size=3)
    assert_frame_equal(read_dataset(d), rs.sweep(CHEAP, cases=cases), check_exact=True)
    assert_frame_equal(pl.read_parquet(d / "cases.parquet"), cases)
    with pytest.raises(ValueError, match="differs at the cases table"):
        sweep_to_dataset(CHEAP, d, cases=cases.with_columns(pl.col("omega_in") * 2), resume=True)


def _write_config(tmp_path: Path) -> Path:
    cfg = tmp_path / "slow.toml"
    cfg.write_text(SLOW_CONFIG)
    return cfg


def _start(cfg: Path, out: Path) -> subprocess.Popen[bytes]:
    return subprocess.Popen([sys.executable, "-m", "restitution", "sweep", str(cfg), "--out", str(out),
                             "--threads", "1", "--no-progress"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def _wait_for_parts(out: Path, proc: subprocess.Popen[bytes], k: int) -> None:
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and proc.poll() is None:
        if out.is_dir() and sum(p.name.startswith("part-") for p in out.iterdir()) >= k:
            return
        time.sleep(0.005)
    raise AssertionError(f"the sweep ended or stalled before {k} chunk files existed: {proc.communicate()}")


@pytest.mark.parametrize("how", ["kill", "interrupt"])
def test_resume_after_the_sweep_process_is_stopped_gives_the_uninterrupted_rows(tmp_path: Path, how: str) -> None:
    cfg = _write_config(tmp_path)
    out = tmp_path / "run"
    proc = _start(cfg, out)
    _wait_for_parts(out, proc, 3)
    proc.send_signal(signal.SIGKILL if how == "kill" else signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    n_chunks = read_manifest(out)["n_chunks"]
    left = missing_chunks(out)
    assert 0 < len(left) < n_chunks - 2, "the process must have stopped mid-sweep"
    if how == "interrupt":
        # Ctrl-C: a clean stop between chunks, every finished chunk kept, no temporary files.
        assert proc.returncode == 130, err
        assert b"--resume" in err
        assert left == list(range(n_chunks - len(left), n_chunks)), "finished chunks are a prefix"
        assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]
    else:
        assert proc.returncode == -signal.SIGKILL
    # every file there is whole and belongs to the sweep
    for p in sorted(out.glob("part-*.parquet")):
        assert pl.read_parquet(p).height == 8
    assert main(["sweep", str(cfg), "--out", str(out), "--resume", "--threads", "2", "--no-progress"]) == 0
    assert missing_chunks(out) == []
    spec, _ = load_config(cfg)
    axes: dict[str, Any] = {k: spec.axes[k] for k in spec.axis_names}
    uninterrupted = rs.sweep(spec.scene, **axes, threads=2)
    assert_frame_equal(read_dataset(out), uninterrupted, check_exact=True)


def test_cli_refuses_to_resume_a_changed_config(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "c.toml"
    cfg.write_text('[scene]\nintegrator = "verlet"\ndt_factor = 0.1\n[axes]\ntheta_deg = [30, 60]\nmu = [0, 1]\n')
    out = tmp_path / "o"
    assert main(["sweep", str(cfg), "--out", str(out), "--chunk-size", "3"]) == 0
    assert "4 impacts in 2 chunks" in capsys.readouterr().out
    cfg.write_text('[scene]\nintegrator = "verlet"\ndt_factor = 0.1\n[axes]\ntheta_deg = [30, 60]\nmu = [0, 0.5]\n')
    assert main(["sweep", str(cfg), "--out", str(out), "--resume"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "differs at axes.mu (dataset: [0.0, 1.0], now: [0.0, 0.5])" in err
    assert main(["sweep", str(cfg), "--out", str(tmp_path / "o2"), "--chunk-size", "0"]) == 2
    assert "--chunk-size" in capsys.readouterr().err


def test_out_must_be_new_or_empty(tmp_path: Path) -> None:
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="not empty and holds no sweep"):
        sweep_to_dataset(CHEAP, tmp_path / "x", theta_deg=30.0)
    with pytest.raises(ValueError, match="not a sweep dataset"):
        read_dataset(tmp_path / "x")
    assert os.listdir(tmp_path / "x") == ["notes.txt"]
    assert not (tmp_path / "x" / MANIFEST).exists()
