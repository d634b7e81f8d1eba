"""Ensembles: the same draws made by hand through rs.simulate give the same records and the
same statistics; the samples depend on the seed only (not on threads or chunks); refused draws
are reported up front or kept with their reason; the intervals cover at their stated rate."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution._engine import RECORD_COLUMNS
from restitution.study import stats

HEXAGON = rs.Scene.paper(shape=rs.RegularPolygon(0.01, 6), integrator="adaptive", tol=1e-7)
VARY = {"phi0_deg": rs.Uniform(0.0, 60.0), "mu": rs.Normal(0.4, 0.15, lo=0.0), "omega_in": rs.Normal(0.0, 1.0)}


def test_the_ensemble_is_its_draws_made_by_hand() -> None:
    ens = rs.ensemble(HEXAGON, 12, vary=VARY, seed=3, theta_deg=[20.0, 70.0], threads=2)
    df = ens.samples
    assert df.height == 24 and df.columns[:5] == ["theta_deg", "draw", "phi0_deg", "mu", "omega_in"]
    assert df.filter(pl.col("theta_deg") == 20.0)["mu"].to_list() == df.filter(pl.col("theta_deg") == 70.0)["mu"].to_list()
    by_hand = []
    for row in df.iter_rows(named=True):
        scene = HEXAGON.replace(mu=row["mu"], shape=rs.RegularPolygon(0.01, 6, row["phi0_deg"]))
        by_hand.append(rs.simulate(scene, row["theta_deg"], row["omega_in"]).as_dict())
    # (Columns undefined on the plate, all None by hand, take the frame's float type.)
    hand = pl.DataFrame(by_hand).select(RECORD_COLUMNS).cast(df.select(RECORD_COLUMNS).schema)
    assert_frame_equal(df.select(RECORD_COLUMNS), hand, check_exact=True)

    summary = ens.summary(["e_n", "e_t", "omega_out"], n_boot=300)
    for (theta, q), part in hand.with_columns(theta_deg=df["theta_deg"]).unpivot(
            ["e_n", "e_t", "omega_out"], index="theta_deg", variable_name="q").group_by(["theta_deg", "q"]):
        x = part["value"].to_numpy()
        row = summary.filter((pl.col("theta_deg") == theta) & (pl.col("quantity") == q)).row(0, named=True)
        assert row["n"] == 12 and row["n_refused"] == row["n_timed_out"] == 0
        assert row["mean"] == pytest.approx(x.mean(), rel=1e-14, abs=1e-15)
        assert row["sd"] == pytest.approx(x.std(ddof=1), rel=1e-12)
        assert [row[k] for k in stats.QUANTILE_NAMES] == pytest.approx(np.quantile(x, stats.QUANTILES).tolist(),
                                                                        rel=1e-14, abs=1e-15)
        assert row["p_neg"] == (x < 0).mean()
        for k in stats.ESTIMATES:
            assert row[f"{k}_lo"] <= row[k] + 1e-15 and row[k] <= row[f"{k}_hi"] + 1e-15


def test_samples_depend_on_the_seed_only(tmp_path: Path) -> None:
    axes = {"theta_deg": [15.0, 45.0, 80.0], "gamma": [0.2, 0.33]}
    runs = [rs.ensemble(HEXAGON, 10, vary=VARY, seed=9, threads=t, chunk_size=c, **axes).samples
            for t, c in ((1, 1), (2, 7), (2, 1000))]
    for other in runs[1:]:
        assert_frame_equal(runs[0], other, check_exact=True)
    result = rs.ensemble_to_dataset(HEXAGON, tmp_path / "d", 10, vary=VARY, seed=9, chunk_size=8, **axes)
    (tmp_path / "d" / "part-000003.parquet").unlink()
    again = rs.ensemble_to_dataset(HEXAGON, tmp_path / "d", 10, vary=VARY, seed=9, resume=True, **axes)
    assert (result.chunks_written, again.chunks_written, again.chunks_skipped) == (8, 1, 7)
    assert_frame_equal(rs.read_ensemble(tmp_path / "d").samples, runs[0], check_exact=True)
    # read point by point from chunks of 8 (points of 10 straddle them): the in-memory summary
    in_memory = rs.ensemble(HEXAGON, 10, vary=VARY, seed=9, **axes).summary(n_boot=50)
    assert_frame_equal(rs.read_ensemble(tmp_path / "d").summary(n_boot=50), in_memory, check_exact=True)
    other_seed = rs.ensemble(HEXAGON, 10, vary=VARY, seed=10, **axes).samples
    assert other_seed["phi0_deg"].to_list() != runs[0]["phi0_deg"].to_list()
    with pytest.raises(ValueError, match=r"differs at ensemble.seed \(dataset: 9, now: 10\)"):
        rs.ensemble_to_dataset(HEXAGON, tmp_path / "d", 10, vary=VARY, seed=10, resume=True, **axes)


def test_refused_draws_are_reported_or_kept_with_their_reason() -> None:
    fast = {"v": rs.LogNormal(0.0, 1.5)}  # its tail reaches speeds whose depth exceeds r / 2
    with pytest.raises(rs.RestitutionError, match=r"of 400 cases are refused; truncate the distribution") as err:
        rs.ensemble(HEXAGON, 200, vary=fast, seed=1, theta_deg=[30.0, 60.0])
    assert err.value.parameter == "v" and err.value.case is not None
    ens = rs.ensemble(HEXAGON, 200, vary=fast, seed=1, theta_deg=[30.0, 60.0], on_refused="skip")
    df = ens.samples
    refused = df.filter(pl.col("refused").is_not_null())
    assert refused.height > 0 and refused["e_n"].null_count() == refused.height
    assert refused["refused"].str.contains("require `v` small enough").all()
    assert df.filter(pl.col("refused").is_null())["e_n"].null_count() == 0
    s = ens.summary(["e_n"], n_boot=0)
    assert (s["n"] + s["n_refused"]).to_list() == [200, 200]
    truncated = rs.ensemble(HEXAGON, 200, vary={"v": rs.LogNormal(0.0, 1.5, hi=5.0)}, seed=1, theta_deg=30.0)
    assert truncated.samples["refused"].null_count() == 200


@pytest.mark.parametrize("kwargs, match", [
    ({"vary": {"spin": rs.Uniform(0.0, 1.0)}}, "`spin` is not a sweep axis"),
    ({"vary": {"mu": rs.Uniform(0.0, 1.0)}, "mu": [0.1]}, "`mu` is both swept and drawn"),
    ({"vary": {"mu": rs.Uniform(0.0, 1.0)}, "theta_deg": None}, "`theta_deg` is required"),
    ({"vary": {"integrator": rs.Uniform(0.0, 1.0)}}, r"takes rs.Choice"),
    ({"vary": {"integrator": rs.Choice(["gear6"])}}, "integrator"),
    ({"vary": {"mu": 0.3}}, "must be a distribution"),
    ({"vary": {}}, "non-empty mapping"),
])
def test_bad_ensembles_are_refused(kwargs, match: str) -> None:
    args = {"theta_deg": 45.0, **kwargs}
    if args["theta_deg"] is None:
        del args["theta_deg"]
    with pytest.raises((ValueError, TypeError), match=match):
        rs.ensemble(HEXAGON, 4, seed=1, **args)


def test_bad_counts_and_seeds_are_refused_by_name() -> None:
    for n, seed, name in ((0, 1, "n"), (4, -1, "seed"), (4, 1.5, "seed")):
        with pytest.raises(rs.RestitutionError) as err:
            rs.ensemble(HEXAGON, n, vary=VARY, seed=seed, theta_deg=45.0)
        assert err.value.parameter == name


def test_a_drawn_angle_needs_no_axis() -> None:
    ens = rs.ensemble(rs.Scene(integrator="adaptive"), 50, vary={"theta_deg": rs.Uniform(5.0, 85.0)}, seed=4)
    assert ens.point_names == () and ens.samples.columns[:2] == ["draw", "theta_deg"]
    assert ens.summary(["e_t"], n_boot=0)["n"].to_list() == [50]


def test_intervals_cover_at_their_level() -> None:
    # 300 samples of 80 normal values: the 95 % intervals of the mean and the median contain the
    # true value in about 95 % of them (binomial sd 1.3 %); Wilson's interval of P(x < 0) likewise.
    rng = np.random.default_rng(0)
    hits = {"mean": 0, "q50": 0, "p_neg": 0}
    trials = 300
    for _ in range(trials):
        d = stats.describe(rng.normal(0.3, 1.0, 80), n_boot=400, rng=rng)
        hits["mean"] += d["mean_lo"] <= 0.3 <= d["mean_hi"]
        hits["q50"] += d["q50_lo"] <= 0.3 <= d["q50_hi"]
        hits["p_neg"] += d["p_neg_lo"] <= 0.3820885778 <= d["p_neg_hi"]  # Phi(-0.3)
    for k, h in hits.items():
        assert 0.95 - 4 * 0.0126 <= h / trials <= 0.95 + 4 * 0.0126, (k, h / trials)


def test_plots_are_written(tmp_path: Path) -> None:
    ens = rs.ensemble(HEXAGON, 16, vary=VARY, seed=2, theta_deg=[10.0, 40.0, 70.0], gamma=[0.2, 0.3])
    ens.plot_quantiles(path=tmp_path / "q.png")
    ens.plot_histograms("e_t", path=tmp_path / "h.png")
    assert (tmp_path / "q.png").stat().st_size > 0 and (tmp_path / "h.png").stat().st_size > 0
    with pytest.raises(ValueError, match="require `x` a swept axis"):
        ens.plot_quantiles(x="v")


def test_stratified_samples_fill_the_strata_on_any_chunking() -> None:
    runs = [rs.ensemble(HEXAGON, 16, vary=VARY, seed=5, sampling="stratified", theta_deg=[30.0, 60.0], chunk_size=c,
                        threads=t).samples for c, t in ((1, 1), (5, 2), (100, 2))]
    for other in runs[1:]:
        assert_frame_equal(runs[0], other, check_exact=True)
    phi = runs[0].filter(pl.col("theta_deg") == 30.0)["phi0_deg"].to_numpy()
    assert sorted(np.floor(phi / 60.0 * 16).astype(int).tolist()) == list(range(16))
    with pytest.raises(rs.RestitutionError, match="require `sampling` one of"):
        rs.ensemble(HEXAGON, 16, vary=VARY, seed=5, sampling="sobol", theta_deg=30.0)
