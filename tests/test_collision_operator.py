"""Collision operators: the engine exactly at the nodes, the stated error true at points the table
was not built on, the stochastic operator's mean the deterministic one, the mirror, the saved
file readable from its documented schema alone, and refusals naming what to change."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.collision.build import in_rough_cell

DISC = rs.Scene(mu=0.3, integrator="adaptive", tol=1e-9)
TOL = 3e-3
HEXAGON = rs.Scene.paper(shape=rs.RegularPolygon(0.01, 6), mu=0.3, integrator="adaptive", tol=1e-7, E=1e8)


@pytest.fixture(scope="module")
def disc_op() -> rs.CollisionOperator:
    return rs.CollisionOperator.build(DISC, theta_deg=np.linspace(10, 90, 9), omega_in=[-1.0, 0.0, 1.0],
                                      v=[0.01, 0.05], tol=TOL, seed=1)


@pytest.fixture(scope="module")
def hexagon_op() -> rs.CollisionOperator:
    return rs.CollisionOperator.build(HEXAGON, theta_deg=np.linspace(10, 90, 9), omega_in=[-1.0, 1.0], v=[0.05, 0.2],
                                      vary={"phi0_deg": rs.Uniform(0.0, 60.0)}, n=24, tol=2e-2, seed=2, n_check=48)


def states(theta: np.ndarray, spin: np.ndarray, v: np.ndarray, r: float) -> tuple[np.ndarray, ...]:
    rad = np.radians(theta)
    return -v * np.sin(rad), v * np.where(theta == 90.0, 0.0, np.cos(rad)), spin * v / r


def engine(scene: rs.Scene, theta: np.ndarray, spin: np.ndarray, v: np.ndarray) -> pl.DataFrame:
    return rs.sweep(scene, cases=pl.DataFrame({"theta_deg": theta, "omega_in": spin * v / scene.r, "v": v}))


def test_at_a_node_the_operator_is_the_engine(disc_op: rs.CollisionOperator) -> None:
    t = disc_op.table
    theta, spin, v = np.meshgrid(t.theta_deg[[1, 5, -1]], t.spin[[0, len(t.spin) // 2]], t.v[[0, -1]], indexing="ij")
    theta, spin, v = theta.ravel(), spin.ravel(), v.ravel()
    got = disc_op(*states(theta, spin, v, DISC.r))
    df = engine(DISC, theta, spin, v)
    for mine, col in zip(got, ("vy_out", "vx_out", "omega_out")):
        np.testing.assert_allclose(mine, df[col].to_numpy(), rtol=1e-12, atol=1e-15 * v.max() / DISC.r)


def test_the_stated_error_holds_where_the_table_was_not_built(disc_op: rs.CollisionOperator) -> None:
    # Fresh uniform points (another seed than the build's check points): the share above the
    # stated 95th percentile is 5 % up to the binomial noise of both samples (3 sd each), and in
    # cells refinement called smooth multilinear interpolation errs at most the sum of its
    # axes' midpoint errors, each within tol once refinement converged there.
    rng = np.random.default_rng(99)
    n = 400
    lo, hi = disc_op.domain["spin"]
    theta, spin = rng.uniform(10.0, 90.0, n), rng.uniform(lo, hi, n)
    v = np.exp(rng.uniform(math.log(0.01), math.log(0.05), n))
    vn, vt, om = states(theta, spin, v, DISC.r)
    got = disc_op(vn, vt, om)
    df = engine(DISC, theta, spin, v)
    err = np.column_stack([np.abs(got[0] - df["vy_out"].to_numpy()) / v, np.abs(got[1] - df["vx_out"].to_numpy()) / v,
                           np.abs(got[2] - df["omega_out"].to_numpy()) * DISC.r / v])
    stated = disc_op.error
    share = (err > stated["p95_abs"].to_numpy()).mean(axis=0)
    allowed = 0.05 + 3 * math.sqrt(0.05 * 0.95 / n) + 3 * math.sqrt(0.05 * 0.95 / disc_op.info["n_check"])
    assert np.all(share <= allowed), (share, allowed)
    smooth = ~in_rough_cell(disc_op.table, disc_op.rough, np.column_stack([theta, spin, v]))
    assert smooth.mean() > 0.8
    assert err[smooth].max() <= 3 * TOL, err[smooth].max(axis=0)
    assert stated["max_abs_smooth"].max() <= 3 * TOL


def test_the_stochastic_operator_draws_around_the_deterministic_one(hexagon_op: rs.CollisionOperator) -> None:
    k = 40_000
    vn, vt, om = np.full(k, -0.1), np.full(k, 0.06), np.full(k, 2.0)
    det = [x[0] for x in hexagon_op(vn[:1], vt[:1], om[:1])]
    draws = hexagon_op(vn, vt, om, rng=np.random.default_rng(5))
    for d, x in zip(det, draws):
        assert abs(x.mean() - d) <= 4.0 * x.std() / math.sqrt(k), (x.mean(), d)
        assert x.std() > 0.0
    again = hexagon_op(vn, vt, om, rng=np.random.default_rng(5))
    assert all(np.array_equal(a, b) for a, b in zip(draws, again))


def test_at_a_node_the_stochastic_operator_draws_the_engines_draws(hexagon_op: rs.CollisionOperator) -> None:
    t = hexagon_op.table
    theta, spin, v = t.theta_deg[4], t.spin[1], t.v[0]
    engine_draws = rs.ensemble(HEXAGON, t.n_draws, vary={"phi0_deg": rs.Uniform(0.0, 60.0)}, seed=hexagon_op.seed,
                               sampling="stratified", theta_deg=theta, omega_in=spin * v / HEXAGON.r,
                               v=v).samples["vy_out"].to_numpy()
    k = 24_000
    vn, vt, om = states(np.full(k, theta), np.full(k, spin), np.full(k, v), HEXAGON.r)
    drawn = hexagon_op(vn, vt, om, rng=np.random.default_rng(2))[0]
    nearest = np.argmin(np.abs(drawn[:, None] - engine_draws[None, :]), axis=1)
    np.testing.assert_allclose(drawn, engine_draws[nearest], rtol=1e-12)  # each draw is one of the engine's
    counts = np.bincount(nearest, minlength=t.n_draws)
    # each of the n draws equally likely: chi^2 with n - 1 dof below its 0.999 quantile (49.7 for 23)
    expected = k / t.n_draws
    assert float(((counts - expected) ** 2 / expected).sum()) < 49.7


def test_the_stochastic_operator_against_fresh_engine_draws(hexagon_op: rs.CollisionOperator) -> None:
    # Between nodes, from orientations the table never saw: the operator's distribution is an
    # empirical one of n draws (per node), so a two-sample Kolmogorov-Smirnov test with sizes n
    # and 300 at level 0.001 must not tell them apart.
    theta, spin, v = 47.0, 0.01, 0.1
    fresh = rs.ensemble(HEXAGON, 300, vary={"phi0_deg": rs.Uniform(0.0, 60.0)}, seed=77, theta_deg=theta,
                        omega_in=spin * v / HEXAGON.r, v=v).samples
    vn, vt, om = states(np.full(5000, theta), np.full(5000, spin), np.full(5000, v), HEXAGON.r)
    ours = hexagon_op(vn, vt, om, rng=np.random.default_rng(1))
    n = hexagon_op.table.n_draws
    for mine, col in zip(ours, ("vy_out", "vx_out", "omega_out")):
        theirs = np.sort(fresh[col].to_numpy())
        grid = np.sort(np.concatenate([mine, theirs]))
        d = np.max(np.abs(np.searchsorted(np.sort(mine), grid, side="right") / mine.size
                          - np.searchsorted(theirs, grid, side="right") / theirs.size))
        assert d < 1.95 * math.sqrt(1.0 / n + 1.0 / theirs.size), (col, d)


def test_mirror_symmetry(disc_op: rs.CollisionOperator) -> None:
    vn, vt, om = np.array([-0.02, -0.03]), np.array([0.01, 0.025]), np.array([0.5, -2.0])
    a, b = disc_op(vn, vt, om), disc_op(vn, -vt, -om)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], -b[1]) and np.array_equal(a[2], -b[2])


def test_save_load_round_trip_and_the_documented_schema(disc_op: rs.CollisionOperator, tmp_path: Path) -> None:
    path = disc_op.save(tmp_path / "op.parquet")
    back = rs.CollisionOperator.load(path)
    rng = np.random.default_rng(3)
    vn, vt, om = -rng.uniform(0.01, 0.05, 50), rng.uniform(-0.05, 0.05, 50), rng.uniform(-1, 1, 50)
    assert all(np.array_equal(x, y) for x, y in zip(disc_op(vn, vt, om), back(vn, vt, om)))
    assert back.scene == DISC and back.tol == TOL and back.error.equals(disc_op.error)
    assert np.array_equal(back.rough, disc_op.rough)

    # What a C or Fortran reader does (docs/model.md, 16.3): no restitution code past this line.
    meta = json.loads(pl.read_parquet_metadata(path)["restitution.operator"])
    table = pl.read_parquet(path)
    n_t, n_s, n_v, n_d = meta["shape"]
    assert table.columns == ["i_theta", "i_spin", "i_v", "draw", "theta_deg", "spin", "v", "vn_ratio", "vt_ratio",
                             "spin_out"]
    row = ((2 * n_s + 1) * n_v + 1) * n_d  # node (2, 1, 1), draw 0: rows in C order
    assert table.row(row)[:4] == (2, 1, 1, 0) and table["theta_deg"][row] == meta["grid"]["theta_deg"][2]
    theta, w, v = 0.5 * sum(meta["grid"]["theta_deg"][2:4]), meta["grid"]["spin"][1], meta["grid"]["v"][1]
    vn_ratio = 0.5 * (table["vn_ratio"][row] + table["vn_ratio"][row + n_s * n_v * n_d])  # halfway to node (3, 1, 1)
    vn, vt = -v * math.sin(math.radians(theta)), v * math.cos(math.radians(theta))
    assert back(np.array([vn]), np.array([vt]), np.array([w * v / meta["r"]]))[0][0] == pytest.approx(vn_ratio * v,
                                                                                                        rel=1e-12)


def test_a_damaged_file_is_refused(disc_op: rs.CollisionOperator, tmp_path: Path) -> None:
    path = disc_op.save(tmp_path / "op.parquet")
    meta = pl.read_parquet_metadata(path)
    table = pl.read_parquet(path).with_columns(vn_ratio=pl.col("vn_ratio") * (1 + 1e-12))
    table.write_parquet(tmp_path / "edited.parquet", metadata=meta)
    with pytest.raises(ValueError, match="does not match its sha256 digest"):
        rs.CollisionOperator.load(tmp_path / "edited.parquet")
    pl.DataFrame({"x": [1]}).write_parquet(tmp_path / "other.parquet")
    with pytest.raises(ValueError, match="is not a collision operator"):
        rs.CollisionOperator.load(tmp_path / "other.parquet")


def test_calls_and_builds_are_checked(disc_op: rs.CollisionOperator) -> None:
    with pytest.raises(rs.RestitutionError, match=r"require `v_n` < 0: approaching the plate.*at index 1"):
        disc_op(np.array([-0.1, 0.1]), np.array([0.0, 0.0]), np.array([0.0, 0.0]))
    with pytest.raises(rs.RestitutionError, match="require `omega` finite"):
        disc_op(np.array([-0.1]), np.array([0.0]), np.array([np.nan]))
    square = rs.Scene(shape=rs.RegularPolygon(0.01, 4), integrator="adaptive")
    with pytest.raises(ValueError, match="phi0_deg` drawn uniformly over whole periods"):
        rs.CollisionOperator.build(square, theta_deg=[30.0, 60.0])
    with pytest.raises(ValueError, match="phi0_deg` drawn uniformly over whole periods"):
        rs.CollisionOperator.build(square, theta_deg=[30.0, 60.0], vary={"phi0_deg": rs.Uniform(0.0, 60.0)})
    with pytest.raises(ValueError, match="no mirror symmetry"):
        rs.CollisionOperator.build(rs.Scene(shape=rs.ConvexPolygon([(0, 0), (1, 0), (0, 1)])), theta_deg=[45.0])
    with pytest.raises(ValueError, match="`v` is an axis of the table"):
        rs.CollisionOperator.build(DISC, theta_deg=[45.0], vary={"v": rs.Uniform(0.01, 0.1)})
    with pytest.raises(rs.RestitutionError, match="require `n` an integer >= 1"):
        rs.CollisionOperator.build(DISC, theta_deg=[45.0], n=8)
    with pytest.raises(rs.RestitutionError, match="require `tol` finite and > 0"):
        rs.CollisionOperator.build(DISC, theta_deg=[45.0], tol=0.0)
    with pytest.raises(rs.RestitutionError, match="require `v` small enough"):
        rs.CollisionOperator.build(DISC, theta_deg=[45.0, 90.0], v=[0.1, 20.0])
