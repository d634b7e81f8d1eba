"""Rigid-body theory (restitution.theory): hand-computed values, the limits of docs/model.md (section 10) and the
conservation laws an impulsive contact at the contact point must obey."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

from restitution.study import theory

R, V = 0.01, 0.0357


def test_doctests():
    assert doctest.testmod(theory).failed == 0


def test_sliding_and_rolling_by_hand():
    # 1 - 0.2 * 1.8 * tan 30
    assert float(theory.e_t_sliding(30.0, 0.2, 0.8)) == pytest.approx(1 - 0.36 / math.sqrt(3), abs=1e-14)
    # Rolling without spin: 1 / (1 + kappa): 2/3 for a disc, 5/7 for a sphere.
    assert float(theory.e_t_rolling(50.0)) == pytest.approx(2 / 3, abs=1e-15)
    assert float(theory.e_t_rolling(50.0, kappa="sphere")) == pytest.approx(5 / 7, abs=1e-15)
    # With spin: 2/3 - r omega / (3 v_T); r = 0.01, v_T = 0.02 cos 60 = 0.01, omega = -1 -> 2/3 + 1/3.
    assert float(theory.e_t_rolling(60.0, -1.0, r=0.01, v=0.02)) == pytest.approx(1.0, abs=1e-12)
    # Backward sliding (contact point moving backwards, s = -1) raises e_T: 1 + mu (1 + e_N) tan theta.
    w = -3.0 * V / R  # r omega = -3 v: u = v (cos theta - 3) < 0 at every angle
    assert float(theory.e_t_sliding(45.0, 0.1, 1.0, w)) == pytest.approx(1.2, abs=1e-12)


def test_theta_c_formula_and_model_value():
    mu = np.array([0.1, 0.5, 1.0, 2.0])
    for kappa, k in (("disc", 0.5), ("sphere", 0.4)):
        expected = np.degrees(np.arctan(k / ((1 + k) * mu * 1.9)))
        assert np.allclose(theory.theta_c(mu, 0.9, kappa=kappa), expected, atol=1e-10)
    # docs/model.md, section 10: 9.95 deg at mu = 1 for the preset's e_N = 0.90.
    assert round(float(theory.theta_c(1.0, 0.90)), 2) == 9.95
    # The regime test switches exactly there.
    tc = float(theory.theta_c(0.3, 0.85))
    assert theory.slides(tc - 1e-6, 0.3, 0.85) and not theory.slides(tc + 1e-6, 0.3, 0.85)


def test_frictionless_limit():
    th = np.linspace(1.0, 89.0, 50)
    for w in (-2.0, 0.0, 3.0):
        assert np.allclose(theory.e_t(th, 0.0, 0.9, w), 1.0, atol=1e-14)
        assert np.allclose(theory.omega_out(th, 0.0, 0.9, w), w, atol=1e-12)
    assert np.all(np.isnan(theory.theta_c(0.0, [0.5, 0.9])))


def _random_cases(n=4000, seed=7):
    rng = np.random.default_rng(seed)
    th = rng.uniform(0.5, 90.0, n)
    mu = rng.uniform(0.0, 1.5, n)
    en = rng.uniform(0.0, 1.0, n)
    w = rng.uniform(-2.0, 2.0, n) * V / R  # spins up to 2 v / r either way
    return th, mu, en, w


@pytest.mark.parametrize("kappa", [0.5, 0.4])
def test_angular_momentum_about_contact_point_conserved(kappa):
    """Impulses act at the contact point, so I omega - m r v_x is unchanged (both regimes)."""
    th, mu, en, w = _random_cases()
    vx_in = V * np.cos(np.radians(th))
    vx = theory.vx_out(th, mu, en, w, kappa=kappa)
    wo = theory.omega_out(th, mu, en, w, kappa=kappa)
    assert np.allclose(kappa * R * wo - vx, kappa * R * w - vx_in, atol=1e-15, rtol=0)


@pytest.mark.parametrize("kappa", [0.5, 0.4])
def test_never_an_energy_gain(kappa):
    th, mu, en, w = _random_cases(seed=3)
    vx = theory.vx_out(th, mu, en, w, kappa=kappa)
    vy = en * V * np.sin(np.radians(th))
    wo = theory.omega_out(th, mu, en, w, kappa=kappa)
    before = V**2 + kappa * R**2 * w**2
    after = vx**2 + vy**2 + kappa * R**2 * wo**2
    assert np.all(after <= before * (1 + 1e-12))


def test_rolling_ends_with_zero_slip_and_sliding_never_reverses():
    th, mu, en, w = _random_cases(seed=11)
    sl = theory.slides(th, mu, en, w)
    u_in = V * np.cos(np.radians(th)) + R * w
    u_out = theory.vx_out(th, mu, en, w) + R * theory.omega_out(th, mu, en, w)
    assert np.allclose(u_out[~sl], 0.0, atol=1e-15)
    # Sliding throughout: the slip keeps its sign (Coulomb friction cannot reverse it).
    assert np.all(u_out[sl] * u_in[sl] >= 0.0)
    assert sl.any() and (~sl).any()


def test_branches_meet_at_the_boundary():
    """e_T is continuous in theta: at every regime boundary, with or without spin, both sides agree."""
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(200):
        mu, en, w = rng.uniform(0.02, 1.0), rng.uniform(0.3, 1.0), rng.uniform(-1.5, 1.5) * V / R
        for t, _side in theory.regime_boundaries(mu, en, w):
            if not 0.01 < t < 89.99:
                continue
            lo, hi = theory.e_t([t - 1e-7, t + 1e-7], mu, en, w)
            assert lo == pytest.approx(hi, abs=1e-5 * max(1.0, abs(lo)))
            checked += 1
    assert checked > 100


def test_theta_c_is_the_first_boundary():
    rng = np.random.default_rng(9)
    for _ in range(300):
        mu, en, w = rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(-1.5, 1.5) * V / R
        rolling_starts = [t for t, side in theory.regime_boundaries(mu, en, w) if side == "rolling"]
        tc = float(theory.theta_c(mu, en, w))
        if rolling_starts:
            assert tc == pytest.approx(rolling_starts[0], abs=1e-6)
        else:
            assert math.isnan(tc)


def test_e_kin_and_beta_by_hand():
    # Head-on: e_kin = e_N.
    assert float(theory.e_kin(90.0, 0.7, 0.8)) == pytest.approx(0.8, abs=1e-14)
    # Sliding beta = -1 + (1 + kappa)/kappa mu (1 + e_N) tan theta (no spin); rolling: 0.
    assert float(theory.beta(10.0, 0.1, 0.9)) == pytest.approx(-1 + 3 * 0.19 * math.tan(math.radians(10)), abs=1e-12)
    assert float(theory.beta(60.0, 1.0, 0.9)) == 0.0


def test_e_kin_min_against_brute_force():
    th = np.linspace(4.0, 89.0, 200001)
    for mu in (0.1, 0.3, 1.0):
        e, t = theory.e_kin_min([mu], 0.9)
        brute = theory.e_kin(th, mu, 0.9)
        # Never above the dense grid's minimum, and below it by at most what the grid misses at a kink.
        assert brute.min() - 1e-5 <= e[0] <= brute.min() + 1e-12
        assert t[0] == pytest.approx(th[np.argmin(brute)], abs=1e-3)
    # At large mu the minimum is the kink at theta_c.
    assert float(theory.e_kin_min([1.0], 0.9)[1][0]) == pytest.approx(float(theory.theta_c(1.0, 0.9)), abs=1e-6)


def test_e_n_for_theta_c_inverts_theta_c():
    assert float(theory.theta_c(0.7, theory.e_n_for_theta_c(20.0, 0.7))) == pytest.approx(20.0, abs=1e-10)


@pytest.mark.parametrize("kwargs, name", [
    (dict(theta_deg=0.0, mu=0.1, e_n=0.9), "theta_deg"),
    (dict(theta_deg=91.0, mu=0.1, e_n=0.9), "theta_deg"),
    (dict(theta_deg=30.0, mu=-0.1, e_n=0.9), "mu"),
    (dict(theta_deg=30.0, mu=0.1, e_n=1.1), "e_n"),
])
def test_bad_input_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        theory.e_t(**kwargs)
    with pytest.raises(ValueError, match="kappa"):
        theory.e_t(30.0, 0.1, 0.9, kappa="cube")
