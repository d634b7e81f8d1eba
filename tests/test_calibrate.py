"""restitution.calibrate: gamma from a target e_N and mu from a measured e_T, checked on the engine."""

from __future__ import annotations

import doctest

import pytest

import restitution as rs
from restitution.calibrate import roots as calibrate


def test_doctests():
    assert doctest.testmod(calibrate).failed == 0


@pytest.mark.parametrize("target", [0.5, 0.75, 0.9, 0.97])
def test_gamma_hits_target_e_n(target):
    cal = calibrate.gamma_for_e_n(rs.Scene(), target)
    # Checked independently of the calibration's own bookkeeping: one more impact at that gamma.
    assert abs(rs.simulate(rs.Scene(gamma=cal.value), 90.0).e_n - target) < 1e-4
    assert abs(cal.achieved - target) < 1e-6
    # e_N falls with gamma, so a little more / less damping brackets the target.
    assert rs.simulate(rs.Scene(gamma=cal.value * 1.01), 90.0).e_n < target < rs.simulate(
        rs.Scene(gamma=cal.value * 0.99), 90.0).e_n


def test_paper_preset_gamma_is_the_calibrated_one():
    """docs/model.md, section 12: gamma ~ 0.33 is the preset calibrated to e_N = 0.90 head-on."""
    for scene in (rs.Scene.paper(), rs.Scene.paper(shape=rs.Disc(r=0.01))):
        cal = calibrate.gamma_for_e_n(scene, 0.90)
        assert round(cal.value, 2) == scene.gamma == 0.33


def test_gamma_depends_on_speed():
    """The area law's e_N depends on v, so calibrating at another speed gives another gamma."""
    slow = calibrate.gamma_for_e_n(rs.Scene(v=0.01), 0.9).value
    fast = calibrate.gamma_for_e_n(rs.Scene(v=0.1), 0.9).value
    assert abs(slow - fast) > 1e-3


@pytest.mark.parametrize("mu, theta", [(0.05, 30.0), (0.3, 15.0), (1.0, 6.0)])
def test_mu_round_trip(mu, theta):
    scene = rs.Scene()
    e_t = rs.simulate(scene.replace(mu=mu), theta).e_t
    cal = calibrate.mu_for_e_t(scene, e_t, theta)
    assert cal.value == pytest.approx(mu, rel=1e-5)


def test_mu_not_identifiable_in_rolling_regime():
    with pytest.raises(ValueError, match="rolling"):
        calibrate.mu_for_e_t(rs.Scene(), 0.6, 45.0)  # below 2/3: only rolling could explain it


@pytest.mark.parametrize("kwargs, name", [(dict(e_n=1.0), "e_n"), (dict(e_n=0.0), "e_n"),
                                          (dict(e_n=0.9, theta_deg=0.0), "theta_deg")])
def test_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        calibrate.gamma_for_e_n(rs.Scene(), **kwargs)
