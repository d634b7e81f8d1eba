"""`restitution ensemble CONFIG --out DIR`: the example config, resume, errors naming the key, and
the same dataset on a Dask cluster."""

from __future__ import annotations

from pathlib import Path

import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.cli import main
from restitution.runs.ensemble import load_config

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "ensemble_config.toml"

SMALL = """
[scene]
integrator = "adaptive"
mu = 0.3
[scene.shape]
kind = "regular_polygon"
r = 0.01
n = 4
[axes]
theta_deg = [20.0, 50.0, 80.0]
[ensemble]
n = 10
seed = 5
[vary]
phi0_deg = { dist = "uniform", lo = 0, hi = 90 }
mu = { dist = "normal", mean = 0.3, sd = 0.1, lo = 0 }
[sweep]
chunk_size = 4
"""


def test_the_example_config_reads_as_documented() -> None:
    spec, chunk = load_config(EXAMPLE)
    assert (spec.n_draws, spec.seed, chunk, spec.n_points) == (256, 2024, 1024, 18)
    assert spec.vary["mu"] == rs.Normal(0.3, 0.05, lo=0.0)
    assert spec.vary["phi0_deg"] == rs.Uniform(0.0, 90.0)
    assert spec.to_dict()["vary"]["omega_in"] == {"dist": "normal", "mean": 0.0, "sd": 0.5}


def test_cli_runs_resumes_and_summarises(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "e.toml"
    cfg.write_text(SMALL)
    out = tmp_path / "d"
    assert main(["ensemble", str(cfg), "--out", str(out), "--n-boot", "50"]) == 0
    assert "30 impacts (10 draws x 3 points) in 8 chunks" in capsys.readouterr().out
    full = rs.read_ensemble(out).samples
    (out / "part-000002.parquet").unlink()
    assert main(["ensemble", str(cfg), "--out", str(out), "--resume", "--n-boot", "50"]) == 0
    assert_frame_equal(rs.read_ensemble(out).samples, full, check_exact=True)
    summary = pl.read_parquet(out / "summary.parquet")
    assert summary.height == 3 * 4 and set(summary["quantity"]) == {"e_n", "e_t", "e_kin", "omega_out"}
    spec, _ = load_config(cfg)
    in_memory = rs.ensemble(spec.scene, 10, vary=spec.vary, seed=5, theta_deg=[20.0, 50.0, 80.0]).samples
    assert_frame_equal(full, in_memory, check_exact=True)


@pytest.mark.parametrize("edit, message", [
    (("seed = 5", "seed = -5"), "ensemble.seed: require `seed` an integer"),
    (("n = 10", "n = 0"), "ensemble.n: require `n` an integer >= 1"),
    (('dist = "uniform"', 'dist = "beta"'), "vary.phi0_deg: require a table with `dist` one of"),
    (("sd = 0.1", "sigma = 0.1"), "unknown key `sigma`"),
    (("[ensemble]", "[ensembel]"), "unknown key (did you mean `ensemble`?)"),
    (("seed = 5\n", ""), "ensemble.seed: required"),
    (("theta_deg = [20.0, 50.0, 80.0]", "mu = [0.1]"), "`mu` is both swept and drawn"),
])
def test_config_errors_name_the_key(tmp_path: Path, capsys: pytest.CaptureFixture[str], edit: tuple[str, str],
                                    message: str) -> None:
    cfg = tmp_path / "e.toml"
    cfg.write_text(SMALL.replace(*edit, 1))
    assert main(["ensemble", str(cfg), "--out", str(tmp_path / "d")]) == 2
    assert message in capsys.readouterr().err


def test_ensemble_on_dask_writes_the_local_dataset(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    cfg = tmp_path / "e.toml"
    cfg.write_text(SMALL)
    spec, _ = load_config(cfg)
    local = rs.ensemble_to_dataset(spec, tmp_path / "local", chunk_size=4)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as c:
        remote = rs.ensemble_to_dataset(spec, tmp_path / "dask", chunk_size=4, scheduler=c.scheduler_address)
    assert remote.chunks_written == local.chunks_written == 8
    assert_frame_equal(rs.read_ensemble(tmp_path / "dask").samples, rs.read_ensemble(tmp_path / "local").samples,
                       check_exact=True)
