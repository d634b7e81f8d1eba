"""restitution.inverse: every planted solution in a synthetic table is found (and nothing else),
tolerance bands and near-misses, and the study's e_T = 0.9 example on the engine."""

from __future__ import annotations

import doctest

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.study import inverse, theory


def test_doctests():
    assert doctest.testmod(inverse).failed == 0


def _table(theta, curves):
    """A sweep-shaped frame: axes (a, b, theta_deg), then record columns; one curve per (a, b)."""
    rows = []
    for (a, b), f in curves.items():
        y = f(theta)
        rows.append(pl.DataFrame({"a": np.full(theta.size, a), "b": np.full(theta.size, b), "theta_deg": theta,
                                  "e_n": np.full(theta.size, 0.9), "e_t": y, "e_kin": np.abs(y)}))
    return pl.concat(rows)


def _polynomial(roots, scale):
    """0.9 + scale * prod((t - root) / 40): crosses 0.9 exactly at the roots (0.95 flat if none)."""
    def f(t):
        if len(roots) == 0:
            return np.full_like(t, 0.95)
        return 0.9 + scale * np.prod([(t - x) / 40.0 for x in roots], axis=0)
    return f


def test_finds_every_planted_crossing():
    rng = np.random.default_rng(4)
    theta = np.arange(4.0, 89.0, 0.7)  # a grid the roots do not sit on
    curves, planted = {}, {}
    for a in range(3):
        for b in (0.5, 1.5):
            k = 0 if (a, b) == (0, 0.5) else int(rng.integers(1, 5))  # one curve without a solution
            while True:  # roots apart, so that each grid interval holds at most one
                roots = np.sort(rng.uniform(6.0, 87.0, k))
                if k < 2 or np.diff(roots).min() > 3.0:
                    break
            curves[(a, b)] = _polynomial(roots, rng.uniform(0.5, 2.0) * rng.choice([-1.0, 1.0]))
            planted[(a, b)] = roots
    sol = inverse.find(_table(theta, curves), "e_t", 0.9)
    assert set(sol["kind"].to_list()) <= {"crossing"}
    total = 0
    for key, roots in planted.items():
        found = sol.filter((pl.col("a") == key[0]) & (pl.col("b") == key[1]))["theta_deg"].to_numpy()
        assert len(found) == len(roots), (key, found, roots)
        # Linear interpolation between grid points: off by at most ~ h^2 |y''| / |y'| -> well below h.
        assert np.allclose(np.sort(found), roots, atol=0.1)
        total += len(roots)
    assert total >= 8


def test_exact_crossings_for_piecewise_linear_data():
    theta = np.arange(0.5, 90.0, 1.0)
    # V shape with its corner off the grid: 0.9 at 20.25 and 60.25, both inside straight pieces.
    sol = inverse.find(_table(theta, {(0, 0): lambda t: 0.9 + 0.01 * np.abs(t - 40.25) - 0.2}), "e_t", 0.9)
    assert np.allclose(sol["theta_deg"].to_numpy(), [20.25, 60.25], atol=1e-12)


def test_zero_on_a_grid_point_counts_once():
    theta = np.arange(1.0, 11.0)
    sol = inverse.find(_table(theta, {(0, 0): lambda t: 0.9 + 0.1 * (t - 5.0)}), "e_t", 0.9)
    assert sol["theta_deg"].to_list() == [5.0]


def test_tolerance_band_and_near_miss():
    theta = np.arange(0.0, 60.0, 1.0) + 1.0
    curves = {
        (0, 0): lambda t: 0.9 + 0.01 * (t - 30.0),       # crossing at 30, within 0.05 on [25, 35]
        (1, 0): lambda t: 0.93 + 0.001 * (t - 20.0) ** 2,  # touches 0.93: within 0.05, never 0.9
        (2, 0): lambda t: 1.5 + 0 * t,                     # never close
    }
    sol = inverse.find(_table(theta, curves), "e_t", 0.9, tol=0.05)
    r0 = sol.filter(pl.col("a") == 0).row(0, named=True)
    assert r0["kind"] == "crossing" and r0["theta_deg"] == pytest.approx(30.0)
    assert (r0["theta_lo"], r0["theta_hi"]) == pytest.approx((25.0, 35.0))
    assert r0["slope"] == pytest.approx(0.01)
    r1 = sol.filter(pl.col("a") == 1)
    assert r1["kind"].to_list() == ["near"] and r1["theta_deg"][0] == pytest.approx(20.0)
    # 0.93 + 0.001 (t - 20)^2 <= 0.95 for |t - 20| <= sqrt(20), up to the piecewise-linear join.
    assert r1["theta_lo"][0] == pytest.approx(20 - np.sqrt(20), abs=0.05)
    assert sol.filter(pl.col("a") == 2).height == 0
    # Without tolerance only the crossing remains.
    assert inverse.find(_table(theta, curves), "e_t", 0.9)["kind"].to_list() == ["crossing"]


def test_bad_input():
    df = _table(np.arange(1.0, 5.0), {(0, 0): lambda t: t})
    with pytest.raises(ValueError, match="quantity"):
        inverse.find(df, "nope", 0.9)
    with pytest.raises(ValueError, match="tol"):
        inverse.find(df, "e_t", 0.9, tol=-1.0)


def test_study_example_e_t_09():
    """The study: e_T = 0.9 at theta ~ 30 for all omega_in (mu = 0.1), and also ~70, 83, 85, 87 deg
    for omega_in = -50, -20, -10, -5 deg/s. Rigid body: the sliding root of 1 - 0.1 (1 + e_N) tan theta
    = 0.9 and the rolling roots of 2/3 - r omega_in / (3 v cos theta) = 0.9, cos theta = -r omega_in / (0.7 v)."""
    spins = np.array([-50.0, -20.0, -10.0, -5.0, 0.0, 20.0])
    df = rs.sweep(rs.Scene(), theta_deg=np.arange(4.0, 89.01, 0.5), mu=[0.1], omega_in=np.radians(spins))
    sol = inverse.find(df, "e_t", 0.9, tol=0.01)
    for om in spins:
        s = sol.filter((pl.col("omega_in") - np.radians(om)).abs() < 1e-12)["theta_deg"].to_numpy()
        w = np.radians(om)
        expect = [27.6]
        if om < 0:
            expect.append(float(np.degrees(np.arccos(-theory.R_PAPER * w / (0.7 * theory.V_PAPER)))))
        assert len(s) == len(expect), (om, s)
        assert np.allclose(s, expect, atol=0.5), (om, s, expect)
    study = {-50.0: 70.0, -20.0: 83.0, -10.0: 85.0, -5.0: 87.0}
    for om, t in study.items():
        s = sol.filter((pl.col("omega_in") - np.radians(om)).abs() < 1e-12)["theta_deg"].max()
        assert abs(s - t) <= 1.5  # the study reads its angles off a figure ("~")


def test_plot(tmp_path):
    pytest.importorskip("matplotlib")
    df = _table(np.arange(1.0, 60.0), {(0, 0.0): lambda t: 0.9 + 0.01 * (t - 30.0)})
    df = df.rename({"b": "omega_in", "a": "mu"})
    sol = inverse.find(df, "e_t", 0.9, tol=0.02)
    fig = inverse.plot(sol, df, quantity="e_t", value=0.9, tol=0.02, path=tmp_path / "inv.png")
    assert (tmp_path / "inv.png").stat().st_size > 10_000
    import matplotlib.pyplot as plt

    plt.close(fig)
