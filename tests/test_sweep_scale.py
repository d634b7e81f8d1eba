"""Sweeps at scale: lazy case generation, chunking and threads leave rows unchanged, every axis
reaches the engine, and the progress line reports impacts, rate and ETA."""

from __future__ import annotations

import itertools
import sys
from typing import Any

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution.runs.sweep import SweepSpec

CHEAP = rs.Scene(integrator="verlet", dt_factor=0.09)  # ~55 steps per contact: fast, still physical (below the 5-gon's bound)


def _axes() -> dict[str, Any]:
    return {"theta_deg": np.linspace(5.0, 90.0, 9), "mu": [0.0, 0.4], "n": [0, 6], "omega_in": [-0.5, 0.5]}


@pytest.mark.parametrize("chunk_size", [1, 7, 1_000_000])
@pytest.mark.parametrize("threads", [1, 2])
def test_rows_do_not_depend_on_chunks_or_threads(chunk_size: int, threads: int) -> None:
    reference = rs.sweep(CHEAP, **_axes(), threads=1, chunk_size=1_000_000)
    got = rs.sweep(CHEAP, **_axes(), threads=threads, chunk_size=chunk_size)
    assert_frame_equal(got, reference, check_exact=True)


def test_case_order_is_the_cartesian_product_first_axis_slowest() -> None:
    axes = _axes()
    df = rs.sweep(CHEAP, **axes, chunk_size=5)
    expected = list(itertools.product(*[list(map(type(np.asarray(v).tolist()[0]), v)) for v in axes.values()]))
    assert df.select(list(axes)).rows() == expected


def test_product_is_generated_lazily_by_index() -> None:
    # 10^12 cases: only the asked-for slice is ever built.
    theta = np.linspace(1.0, 90.0, 1_000_000)
    omega = np.linspace(-1.0, 1.0, 1_000_000)
    spec = SweepSpec(CHEAP, axes={"theta_deg": theta, "omega_in": omega})
    assert spec.n_cases == 10**12
    per_case, shown = spec.inputs(10**12 - 3, 10**12)
    np.testing.assert_array_equal(per_case["theta_deg"], [90.0] * 3)
    np.testing.assert_array_equal(per_case["omega_in"], omega[-3:])
    assert shown.rows() == [(90.0, o) for o in omega[-3:]]
    per_case, shown = spec.inputs(999_999, 1_000_001)  # across the first axis' carry
    np.testing.assert_array_equal(per_case["theta_deg"], theta[:2])
    np.testing.assert_array_equal(per_case["omega_in"], [omega[-1], omega[0]])
    assert shown.height == 2


def test_rows_are_single_impacts() -> None:
    df = rs.sweep(CHEAP, theta_deg=[20.0, 70.0], omega_in=[-1.0, 2.0], chunk_size=3)
    for row in df.iter_rows(named=True):
        rec = rs.simulate(CHEAP, theta_deg=row["theta_deg"], omega_in=row["omega_in"])
        # The frame shows the swept inputs (not the partner's spin, 0 without a partner).
        assert {k: v for k, v in rec.as_dict().items() if k in row} == {k: row[k] for k in rec.as_dict() if k in row}
        assert set(rec.as_dict()) - set(row) == {"partner_omega_in"}


def test_axes_reach_the_engine_frictionless_elastic_limit() -> None:
    # docs/model.md, section 11: mu = 0, gamma = 0 gives e_n = e_t = 1 on a disc (at the default dt); damping
    # and friction lower them.
    df = rs.sweep(rs.Scene(mu=0.0, gamma=0.0), theta_deg=[30.0, 60.0], gamma=[0.0, 0.33], mu=[0.0, 0.5])
    elastic = df.filter((pl.col("gamma") == 0.0) & (pl.col("mu") == 0.0))
    np.testing.assert_allclose(elastic["e_n"], 1.0, atol=1e-6)
    np.testing.assert_allclose(elastic["e_t"], 1.0, atol=1e-6)
    assert (df.filter(pl.col("gamma") > 0)["e_n"] < 0.95).all()
    assert (df.filter(pl.col("mu") > 0)["e_t"] < 1.0 - 1e-3).all()


def test_shape_axis_zero_is_the_exact_disc_and_polygons_match_their_scene() -> None:
    df = rs.sweep(CHEAP, theta_deg=[30.0, 80.0], n=[0, 5], phi0_deg=[0.0, 17.0])
    disc = rs.sweep(CHEAP.replace(shape=rs.Disc(r=CHEAP.r)), theta_deg=[30.0, 80.0])
    pent = rs.sweep(CHEAP.replace(shape=rs.RegularPolygon(r=CHEAP.r, n=5, phi0_deg=17.0)), theta_deg=[30.0, 80.0])
    cols = ["e_n", "e_t", "omega_out", "steps"]
    for phi0 in (0.0, 17.0):  # phi0 does not matter for a disc
        assert_frame_equal(df.filter((pl.col("n") == 0) & (pl.col("phi0_deg") == phi0)).select(cols), disc.select(cols))
    assert_frame_equal(df.filter((pl.col("n") == 5) & (pl.col("phi0_deg") == 17.0)).select(cols), pent.select(cols))


def test_per_call_axes_normal_law_and_inertia_keep_case_order() -> None:
    df = rs.sweep(CHEAP, theta_deg=[20.0, 50.0, 90.0], normal_law=["area", "linear"], inertia=["shape", "sphere"],
                  chunk_size=4)
    assert df.height == 12
    for law, inertia in itertools.product(["area", "linear"], ["shape", "sphere"]):
        alone = rs.sweep(CHEAP.replace(normal_law=law, inertia=inertia), theta_deg=[20.0, 50.0, 90.0])
        part = df.filter((pl.col("normal_law") == law) & (pl.col("inertia") == inertia))
        assert_frame_equal(part.drop("normal_law", "inertia"), alone)
    # the rolling limit e_T = 1/(1+kappa) tells the inertias apart: 2/3 (disc) vs 5/7 (sphere)
    slow = rs.sweep(rs.Scene(mu=1.0, integrator="verlet", dt_factor=0.05), theta_deg=[20.0], inertia=["shape", "sphere"])
    np.testing.assert_allclose(slow["e_t"], [2 / 3, 5 / 7], atol=0.03)


def test_cases_table_gives_the_same_rows_as_the_product() -> None:
    product = rs.sweep(CHEAP, **_axes())
    cases = product.select(list(_axes()))
    assert_frame_equal(rs.sweep(CHEAP, cases=cases, chunk_size=7, threads=2), product, check_exact=True)
    shuffled = cases.sample(fraction=1.0, shuffle=True, seed=3)
    got = rs.sweep(CHEAP, cases=shuffled, chunk_size=5)
    assert_frame_equal(got, product.join(shuffled.with_row_index(), on=list(_axes())).sort("index").drop("index"))


def test_combined_rules_checked_across_axes() -> None:
    gear5, verlet = rs.MAX_DT_FACTOR["gear5"], rs.MAX_DT_FACTOR["verlet"]
    assert gear5 < verlet
    with pytest.raises(ValueError, match=rf"`dt_factor` in \(0, {gear5}\] for the gear5 integrator .*found {verlet}\)"):
        rs.sweep(CHEAP, theta_deg=30.0, dt_factor=[gear5, verlet], integrator=["verlet", "gear5"])
    rs.sweep(CHEAP, theta_deg=30.0, dt_factor=[verlet], integrator=["verlet"])  # fine for verlet alone
    with pytest.raises(ValueError, match=r"case 1: require `inertia` \"shape\" for polygons"):
        rs.sweep(CHEAP, cases=pl.DataFrame({"theta_deg": [30.0, 30.0], "n": [0, 5], "inertia": ["sphere"] * 2}))
    with pytest.raises(ValueError, match=r"require `normal_law` one of \"area\", \"linear\""):
        rs.sweep(CHEAP, theta_deg=30.0, normal_law=["hooke"])
    with pytest.raises(ValueError, match=r"require `chunk_size` an integer >= 1"):
        rs.sweep(CHEAP, theta_deg=30.0, chunk_size=0)


def test_progress_line_without_tqdm(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import fails: the plain stderr line is used
    rs.sweep(CHEAP, theta_deg=np.linspace(5, 90, 30), progress=True, chunk_size=10)
    err = capsys.readouterr().err
    assert "30/30 impacts" in err and "/s, ETA" in err
