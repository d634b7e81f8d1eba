"""restitution.analysis: sub-grid extrema, the exponential fit and its error bars, theta_c and
e_kin,min from sweeps against rigid-body theory, micro-slip, and the study's Eq. 2."""

from __future__ import annotations

import doctest

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.study import analysis, theory


def test_doctests():
    assert doctest.testmod(analysis).failed == 0


@pytest.mark.parametrize("x0", [4.0, 4.13, 4.5, 4.87, 5.0])
def test_kink_located_between_grid_points(x0):
    """A corner between two gently curved branches (like sliding meeting rolling)."""
    x = np.arange(0.0, 10.0, 0.5)
    y = np.where(x < x0, -2.0 * (x - x0) + 0.01 * (x - x0) ** 2, 0.7 * (x - x0) + 0.02 * (x - x0) ** 2)
    e = analysis.locate_min(x, y)
    assert e.method.startswith("kink") or e.x == pytest.approx(x0, abs=1e-9)
    # Lines through two points of a branch with curvature 0.02 are off by ~ c h^2: tiny.
    assert e.x == pytest.approx(x0, abs=0.01)
    assert e.y == pytest.approx(0.0, abs=0.01)


def test_smooth_minimum_uses_the_parabola():
    x = np.linspace(0.0, 10.0, 41)
    for x0 in (3.0, 3.1, 6.77):
        e = analysis.locate_min(x, 1.5 + 0.3 * (x - x0) ** 2)
        assert e.method == "parabola"
        assert e.x == pytest.approx(x0, abs=1e-9) and e.y == pytest.approx(1.5, abs=1e-12)


def test_edge_minimum_is_reported_as_such():
    x = np.arange(5.0)
    assert analysis.locate_min(x, -x).method == "edge"
    assert analysis.locate_max(x, -((x - 2.2) ** 2)).x == pytest.approx(2.2)


def test_fit_exp_exact_data():
    x = np.linspace(0.1, 1.0, 10)
    for p in ((73.45, 5.44, 16.26), (0.22, 4.07, 0.68), (-3.0, -2.0, 1.0)):
        f = analysis.fit_exp(x, p[0] * np.exp(-p[1] * x) + p[2])
        assert np.allclose(f.params, p, rtol=1e-8, atol=1e-10)
        assert max(f.errors) < 1e-6


def test_fit_exp_error_bars_are_right_monte_carlo():
    """Parameters from noisy synthetic data: unbiased within their error bars, the error bars
    match the scatter of the estimates, and about 68 % of the 1-sigma intervals cover the truth."""
    rng = np.random.default_rng(2024)
    x = np.linspace(0.1, 1.0, 10)
    p = np.array([73.45, 5.44, 16.26])
    sigma = 1.0
    est, err, err_scaled = [], [], []
    for _ in range(200):
        y = p[0] * np.exp(-p[1] * x) + p[2] + rng.normal(0.0, sigma, x.size)
        f = analysis.fit_exp(x, y, sigma=sigma)  # known noise: absolute errors
        est.append(f.params)
        err.append(f.errors)
        err_scaled.append(analysis.fit_exp(x, y).errors)  # noise estimated from the residuals
    est, err, err_scaled = map(np.array, (est, err, err_scaled))
    spread = est.std(axis=0)
    # Each fit's error bar is close to the actual scatter (nonlinear: loosely).
    assert np.all(np.abs(err.mean(axis=0) / spread - 1.0) < 0.25)
    # With unknown noise the scaled error bars agree on average too (they fluctuate like chi2).
    assert np.all(np.abs(np.median(err_scaled, axis=0) / spread - 1.0) < 0.35)
    # The mean of 300 estimates is within 4 standard errors of the mean of the truth.
    assert np.all(np.abs(est.mean(axis=0) - p) < 4 * spread / np.sqrt(len(est)))
    cover = (np.abs(est - p) < err).mean(axis=0)
    assert np.all((cover > 0.55) & (cover < 0.80))


def test_fit_exp_rejects_bad_input():
    with pytest.raises(ValueError, match="at least 4"):
        analysis.fit_exp([0, 1, 2], [1, 2, 3])
    with pytest.raises(ValueError, match="sigma"):
        analysis.fit_exp(np.arange(5.0), np.arange(5.0), sigma=0.0)


def test_compare_flags_at_two_sigma():
    assert analysis.compare((1.0, 0.1), (1.25, 0.1)) == pytest.approx((0.25 / np.hypot(0.1, 0.1), False))
    assert analysis.compare((1.0, 0.1), (1.35, 0.1))[1] is True


def _theory_frame(theta, mus, e_n=0.9, omega_in=0.0):
    """A sweep-shaped frame whose records come from rigid-body theory (exact kinks)."""
    th, mu = np.meshgrid(theta, mus, indexing="ij")
    th, mu = th.ravel(), mu.ravel()
    return pl.DataFrame({
        "theta_deg": th, "mu": mu, "e_n": np.full(th.size, e_n),
        "e_t": theory.e_t(th, mu, e_n, omega_in), "e_kin": theory.e_kin(th, mu, e_n, omega_in),
        "omega_out": theory.omega_out(th, mu, e_n, omega_in),
    })


def test_critical_angles_recover_theory_on_a_coarse_grid():
    mus = [0.2, 0.5, 1.0]
    crit = analysis.critical_angles(_theory_frame(np.arange(4.0, 89.5, 1.0), mus)).sort("mu")
    expect = theory.theta_c(np.array(mus), 0.9)
    # 1-degree grid, sub-grid refinement: the kink is found to a few thousandths of a degree.
    assert np.allclose(crit["theta_c"].to_numpy(), expect, atol=0.01)
    assert np.allclose(crit["theta_c_theory"].to_numpy(), expect, atol=1e-9)
    e_min, t_min = theory.e_kin_min(mus, 0.9)
    assert np.allclose(crit["e_kin_min"].to_numpy(), e_min, atol=2e-4)
    assert np.allclose(crit["theta_e_kin_min"].to_numpy(), t_min, atol=0.05)


def test_critical_angles_of_the_engine_follow_theory():
    """The DEM's theta_c (peak of |omega_out|) follows rigid-body theory with the measured e_N,
    slightly above it (measured: +1.1 to +1.3 %; the soft contact rounds the corner and ends
    sliding a little later), at every mu: no plateau like the study's fit offset c = 16 deg."""
    df = rs.sweep(rs.Scene(), theta_deg=np.arange(4.0, 89.5, 0.5), mu=[0.2, 0.5, 1.0])
    crit = analysis.critical_angles(df).sort("mu")
    rel = ((crit["theta_c"] - crit["theta_c_theory"]) / crit["theta_c_theory"]).to_numpy()
    assert np.all((rel > 0.0) & (rel < 0.02)), rel
    # mu = 0 has no theta_c: |omega_out| = 0 everywhere.
    c0 = analysis.critical_angles(rs.sweep(rs.Scene(mu=0.0), theta_deg=np.arange(4.0, 90.0, 5.0), mu=[0.0]))
    assert c0["theta_c"][0] is None


def test_sondergaard_exact_in_the_sliding_regime():
    """Sliding throughout, every step has |F_t| = mu F_n, so e_T = 1 - s mu (1 + e_N) tan theta
    holds with the measured e_N to rounding, with spin too; in the rolling regime it fails."""
    th = np.arange(4.0, 89.0, 1.0)
    df = rs.sweep(rs.Scene(), theta_deg=th, mu=[0.1, 0.4], omega_in=[-0.5, 0.0, 0.5])
    res = analysis.sondergaard_residuals(df)
    tc = theory.theta_c(res["mu"].to_numpy(), res["e_n"].to_numpy(), res["omega_in"].to_numpy())
    far = res.filter(pl.col("sliding") & pl.Series(res["theta_deg"].to_numpy() < tc - 2.0))
    assert far.height > 50
    assert float(far["e_t_residual"].abs().max()) < 1e-9
    rolling = res.filter(~pl.col("sliding") & (pl.col("theta_deg") >= 75) & (pl.col("omega_in") == 0.0))
    assert rolling.height > 20 and float(rolling["e_t_residual"].abs().min()) > 0.2


def test_micro_slip_zero_for_rigid_body_and_falls_with_gamma_t():
    assert analysis.micro_slip(_theory_frame(np.arange(4.0, 89.5, 1.0), [0.5]))["amplitude"][0] == pytest.approx(
        0.0, abs=1e-12)
    df = rs.sweep(rs.Scene(mu=1.0), theta_deg=np.arange(20.0, 89.0, 0.5), mu=[1.0], gamma_t=[0.25, 0.5, 1.0])
    ms = analysis.micro_slip(df).sort("gamma_t")
    amp = ms["amplitude"].to_numpy()
    # docs/model.md, section 5: stronger tangential damping damps the oscillation about 2/3 (-7/+5 %, +-1.3 %, +-0.3 %).
    assert amp[0] > amp[1] > amp[2] > 0
    assert 0.002 < amp[1] < 0.03  # the study: about 2 %


def test_sphere_inertia_follows_the_sphere_theory():
    """inertia="sphere" (I = 2/5 m r^2): rolling e_T -> 5/7 and tan theta_c = 2 / (7 mu (1 + e_N))."""
    scene = rs.Scene(inertia="sphere")
    df = rs.sweep(scene, theta_deg=np.arange(4.0, 89.5, 0.5), mu=[0.3, 1.0])
    crit = analysis.critical_angles(df, kappa="sphere")
    rel = ((crit["theta_c"] - crit["theta_c_theory"]) / crit["theta_c_theory"]).to_numpy()
    assert np.all((rel > 0.0) & (rel < 0.02)), rel
    disc = theory.theta_c(crit["mu"].to_numpy(), crit["e_n_at_theta_c"].to_numpy(), kappa="disc")
    assert np.all(np.abs(crit["theta_c"].to_numpy() - disc) > 1.0)  # the disc's theory would not do
    ms = analysis.micro_slip(df, kappa="sphere")
    assert np.all(np.abs(ms["e_t_mean"].to_numpy() / (5 / 7) - 1) < 0.005)
