"""`restitution fig2`: the study's Fig. 2 as Parquet + PNG, and its refusal of bad options."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.cli import main


def test_fig2_writes_parquet_and_png(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    assert main(["fig2", "--out", str(out), "--step", "20", "--shape", "disc", "--threads", "2"]) == 0
    parquet, png = out / "fig2.parquet", out / "fig2.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    df = pl.read_parquet(parquet)
    # theta 4, 24, ..., 84 against mu = 0, 0.1 ... 1 on the paper preset (exact disc)
    assert sorted(df["theta_deg"].unique().to_list()) == [4.0, 24.0, 44.0, 64.0, 84.0]
    assert df["mu"].unique().sort().to_list() == pytest.approx(np.linspace(0.0, 1.0, 11).tolist(), abs=1e-12)
    assert df.height == 5 * 11
    # The file holds exactly what the API computes for the same sweep.
    again = rs.sweep(rs.Scene.paper(shape=rs.Disc(r=0.01)), theta_deg=df["theta_deg"].unique(maintain_order=True),
                     mu=df["mu"].unique(maintain_order=True), threads=1)
    assert_frame_equal(df, again, check_exact=True)
    printed = capsys.readouterr().out
    assert "55 impacts" in printed and str(parquet) in printed


@pytest.mark.parametrize("step", ["0", "-5", "86", "nan", "inf"])
def test_fig2_bad_step_returns_2_naming_step(tmp_path: Path, capsys: pytest.CaptureFixture[str], step: str) -> None:
    out = tmp_path / "out"
    assert main(["fig2", "--out", str(out), "--step", step, "--shape", "disc"]) == 2
    err = capsys.readouterr().err
    assert "--step" in err and "(0, 85]" in err
    assert not (out / "fig2.parquet").exists()


def test_fig2_unparsable_step_is_an_argparse_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["fig2", "--out", str(tmp_path), "--step", "twenty"])
    assert info.value.code == 2
    assert "--step" in capsys.readouterr().err


def test_fig2_bad_threads_returns_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["fig2", "--out", str(tmp_path), "--step", "40", "--shape", "disc", "--threads", "0"]) == 2
    assert "threads" in capsys.readouterr().err
