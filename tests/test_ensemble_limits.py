"""Limits ensembles must reach (docs/model.md, sections 16.5 and 16.6).

1. Stiff, frictionless, elastic regular n-gons at uniform random orientation approach rigid-body
   collision theory (corner impulses in sequence): the mean gap over the draws shrinks as
   E^(-1/3), the scaling of the contact's depth and duration with the stiffness.
2. The exact disc's area law is a viscoelastic (Hertz-like) force at small overlap, so its
   e_N(v) follows 1 - e_N = C eps + O(eps^2) with eps ~ gamma v^(1/5) and C from the closed form.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import restitution as rs
from restitution import theory

STIFFNESSES = (1e7, 1e9, 1e11)
R, V, THETA = 0.01, 0.0357, 60.0


def gaps(n: int) -> list[float]:
    """Mean |e_N (engine) - e_N (rigid)| + |omega' r / v (engine) - (rigid)| over 200 orientations."""
    out = []
    for E in STIFFNESSES:
        scene = rs.Scene(shape=rs.RegularPolygon(R, n), mu=0.0, gamma=0.0, E=E, v=V, integrator="adaptive", tol=1e-10)
        df = rs.ensemble(scene, 200, vary={"phi0_deg": rs.Uniform(0.0, 360.0 / n)}, seed=n, theta_deg=THETA).samples
        vx, vy, w, _ = theory.polygon_impact(n, df["phi0_deg"].to_numpy(), THETA, v=V, r=R)
        e_n = vy / (V * math.sin(math.radians(THETA)))
        assert np.allclose(df["vx_out"].to_numpy(), vx, rtol=0, atol=1e-12)  # no friction: v_x untouched
        out.append(float(np.mean(np.abs(df["e_n"].to_numpy() - e_n) + np.abs(df["omega_out"].to_numpy() - w) * R / V)))
    return out


@pytest.mark.parametrize("n", [3, 4, 6])
def test_stiff_polygons_approach_rigid_body_theory(n: int) -> None:
    g = gaps(n)
    assert g[0] > g[1] > g[2], g
    slope = np.polyfit(np.log(STIFFNESSES), np.log(g), 1)[0]
    # -1/3 (depth and contact time ~ E^(-1/3)); the band allows the next order and the draws' noise
    assert -0.45 < slope < -0.25, (slope, g)
    assert g[2] < 0.01


def test_rigid_polygon_theory_conserves_energy_and_momentum() -> None:
    phi = np.random.default_rng(0).uniform(0.0, 120.0, 50)
    for e in (1.0, 0.5):
        vx, vy, w, k = theory.polygon_impact(3, phi, 35.0, omega_in=2.0, v=0.05, r=R, e=e)
        kappa = theory.kappa_polygon(3)
        before = 0.05**2 + kappa * (R * 2.0) ** 2
        after = vx**2 + vy**2 + kappa * (R * w) ** 2
        if e == 1.0:
            np.testing.assert_allclose(after, before, rtol=1e-12)
        else:
            assert np.all(after < before)
        assert np.all(k >= 1) and np.all(vy > 0)


# --- the disc's e_N(v) -----------------------------------------------------------------------


def test_the_first_order_coefficient_is_the_closed_form() -> None:
    # (1 - e_N) / (C eps) -> 1 as eps -> 0 at small depth (v = 1e-4 m/s: depth / r = 5e-5); the
    # intercept of a quadratic in eps over gamma = 0.003 ... 0.3.
    gammas = np.geomspace(0.003, 0.3, 7)
    df = rs.sweep(rs.Scene(mu=0.0, integrator="reference", v=1e-4), theta_deg=90.0, gamma=gammas)
    eps = theory.viscoelastic_epsilon(1e-4, gamma=1.0, E=1e7, rho=2500.0, r=R) * gammas
    ratio = (1.0 - df["e_n"].to_numpy()) / (theory.VISCOELASTIC_C * eps)
    intercept = np.polyfit(eps, ratio, 2)[-1]
    assert abs(intercept - 1.0) < 1e-3, intercept
    assert np.all(np.diff(ratio) < 0)  # the next order lowers it: restitution above first order


def test_e_n_depends_on_gamma_and_v_only_through_eps() -> None:
    # gamma v^(1/5) fixed: the same e_N at speeds 1000 times apart, up to the depth's O(d / r).
    pairs = [(0.2, 1e-4), (0.1, 32e-4), (0.05, 1024e-4)]
    e = [rs.simulate(rs.Scene(mu=0.0, integrator="reference", gamma=g, v=v), 90.0) for g, v in pairs]
    assert max(r.max_depth for r in e[:2]) / R < 1e-3
    assert abs(e[0].e_n - e[1].e_n) < 1e-5, [r.e_n for r in e]
    assert abs(e[0].e_n - e[2].e_n) < 1e-4, [r.e_n for r in e]  # depth / r = 0.009 there


def test_one_minus_e_n_grows_as_v_to_the_one_fifth() -> None:
    v = np.geomspace(1e-4, 1e-2, 5)
    df = rs.sweep(rs.Scene(mu=0.0, integrator="reference", gamma=0.01), theta_deg=90.0, v=v)
    slope = np.polyfit(np.log(v), np.log(1.0 - df["e_n"].to_numpy()), 1)[0]
    eps_max = float(theory.viscoelastic_epsilon(1e-2, gamma=0.01, E=1e7, rho=2500.0, r=R))
    # the next order, O(eps) relative, changes the log-slope by O(eps): a few eps_max at most
    assert abs(slope - 0.2) < 0.2 * 5 * eps_max, (slope, eps_max)
    first_order = theory.e_n_viscoelastic(v, gamma=0.01, E=1e7, rho=2500.0, r=R)
    assert np.all(np.abs(df["e_n"].to_numpy() - first_order) < 2 * (1.0 - first_order) * eps_max)
