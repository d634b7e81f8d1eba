"""The Hertz-Mindlin sphere from Python (docs/model.md, section 14): mass and inertia per
particle, Hertz's closed forms (Chung & Ooi Test 2), e_N = cor (Test 3), rigid-body theory on
the gross-sliding branch (Test 4), refusals, sweeps and the validate pipeline."""

import math

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.study import validate


def alumina(**changes):
    base = dict(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98,
                mu=0.092, v=3.9, integrator="gear5")  # the study's method, as validate.py
    return rs.Scene(**{**base, **changes})


def test_energy_is_per_particle():
    rec = rs.simulate(alumina(mu=0.0), 90.0)
    m = 4.0 / 3.0 * math.pi * 2.5e-3**3 * 4000.0
    assert rec.energy_in == pytest.approx(0.5 * m * 3.9**2, rel=1e-14)


def test_hertz_closed_forms_test2():
    table, _ = validate.test2()
    assert np.abs(table["deviation"].to_numpy()).max() < 1e-4


@pytest.mark.parametrize("integrator", ["gear5", "verlet", "reference"])
def test_restitution_is_cor_test3(integrator):
    for cor in (0.2, 0.5, 0.8, 1.0):
        scene = alumina(cor=cor, mu=0.0, integrator=integrator, dt_factor=1.0 if integrator == "reference" else 0.01)
        assert abs(rs.simulate(scene, 90.0).e_n - cor) < 1e-3


def test_gross_sliding_is_rigid_body_theory_test4():
    scene = alumina()
    for theta_n in (35.0, 50.0, 70.0, 85.0):
        rec = rs.simulate(scene, 90.0 - theta_n)
        a = 0.092 * (1.0 + rec.e_n)
        assert rec.e_t == pytest.approx(1.0 - a / math.tan(math.radians(theta_n)), rel=1e-3)
        assert -rec.omega_out == pytest.approx(2.5 * a * 3.9 * math.cos(math.radians(theta_n)) / 2.5e-3, rel=1e-3)
        assert rec.omega_out == pytest.approx(
            rs.theory.omega_out(90.0 - theta_n, 0.092, rec.e_n, r=2.5e-3, v=3.9, kappa="sphere"), rel=1e-3)


@pytest.mark.parametrize("changes, parameter", [
    (dict(shape=rs.Disc(r=0.01)), "normal_law"),
    (dict(normal_law="area"), "normal_law"),
    (dict(nu=None), "nu"),
    (dict(cor=None), "cor"),
    (dict(cor=1.5), "cor"),
    (dict(nu=0.7), "nu"),
    (dict(plate_E=70e9), "plate_nu"),
    (dict(plate_nu=0.25), "plate_nu"),
    (dict(tangential="linear"), "kt"),
    (dict(overlap="parry"), "overlap"),
])
def test_refusals_name_the_parameter(changes, parameter):
    with pytest.raises(rs.RestitutionError) as err:
        alumina(**changes)
    assert err.value.parameter == parameter


def test_mindlin_needs_hertz():
    with pytest.raises(rs.RestitutionError) as err:
        rs.Scene(tangential="mindlin")
    assert err.value.parameter == "tangential"


@pytest.mark.parametrize("history", ["mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force"])
def test_a_tangential_history_needs_mindlins_spring(history):
    assert alumina(tangential_history=history).tangential_history == history
    for scene in (dict(shape=rs.Disc(r=0.01), normal_law="area", nu=None, cor=None),
                  dict(tangential="linear", kt=1e8)):
        with pytest.raises(rs.RestitutionError) as err:
            alumina(tangential_history=history, **scene)
        assert err.value.parameter == "tangential_history"
    with pytest.raises(rs.RestitutionError, match="tangential_history"):
        alumina(tangential_history="mindlin/displacement")


def test_tangential_history_is_a_sweep_axis():
    """Near the normal the contact sticks and the histories differ; beyond 35 deg from it the contact
    slides throughout and the force histories agree to round-off (rigid-body theory)."""
    df = rs.sweep(alumina(), theta_deg=[85.0, 40.0], tangential_history=list(validate.HISTORIES), progress=False)
    assert df["tangential_history"].to_list() == list(validate.HISTORIES) * 2  # the first axis slowest
    near, sliding = df.filter(pl.col("theta_deg") == 85.0), df.filter(pl.col("theta_deg") == 40.0)
    assert near["e_t"].n_unique() == 4
    forces = sliding.filter(pl.col("tangential_history").str.ends_with("/force"))["e_t"].to_numpy()
    assert forces[0] == pytest.approx(forces[1], abs=1e-12)


def test_auto_is_mindlin_force():
    for theta in (85.0, 70.0, 40.0):
        assert rs.simulate(alumina(), theta) == rs.simulate(alumina(tangential_history="mindlin/force"), theta)


def test_history_verdict_against_test4():
    """Each history against Chung & Ooi's Test 4: the table has every published point inside our range
    for every history, the default is its own reference (never closer, never farther), and the verdict
    is what the points say."""
    dev = validate.history_deviations(validate.test4_histories())
    verdict = validate.history_verdict(dev)
    assert set(verdict["history"]) == set(validate.HISTORIES)
    inside = sum(int(np.sum((np.asarray(table[case][0]) >= 5.0) & (np.asarray(table[case][0]) <= 85.0)))
                 for _, table in validate.QUANTITIES for case in ("oxide", "alloy") if case in table)
    assert dev.group_by("history").len()["len"].to_list() == [inside] * 4
    default = verdict.filter(pl.col("history") == validate.DEFAULT_HISTORY).row(0, named=True)
    assert (default["points_closer"], default["points_farther"]) == (0, 0)
    for row in verdict.iter_rows(named=True):
        assert row["better_everywhere"] == (row["points_farther"] == 0 and row["points_closer"] > 0)


def test_sweep_over_cor_and_angle():
    df = rs.sweep(alumina(mu=0.0), theta_deg=[30.0, 90.0], cor=[0.3, 0.9], progress=False)
    assert df.height == 4
    np.testing.assert_allclose(df["e_n"].to_numpy(), df["cor"].to_numpy(), atol=1e-3)


def test_elastic_plate_softens_the_contact():
    rigid = rs.simulate(alumina(mu=0.0), 90.0)
    glass = rs.simulate(alumina(mu=0.0, plate_E=70e9, plate_nu=0.25), 90.0)
    # Hertz: t_c ~ E*^(-2/5); E* falls from 401 to 70.6 GPa on glass.
    e_rigid = 380e9 / (1 - 0.23**2)
    e_glass = 1 / ((1 - 0.23**2) / 380e9 + (1 - 0.25**2) / 70e9)
    assert glass.contact_time / rigid.contact_time == pytest.approx((e_rigid / e_glass) ** 0.4, rel=1e-4)


def test_validate_writes_figures(tmp_path):
    paths = validate.write_validation(tmp_path)
    names = {p.name for p in paths}
    assert {"test4.png", "kharaz.png", "test6.png", "test4_histories.png", "report.md"} <= names
    assert "Test 4 per history of Mindlin's spring" in (tmp_path / "report.md").read_text()
    # The terminal gets a few lines, each closed-form check against its bound; report.md the rest.
    lines = validate.summary(tmp_path)
    assert len(lines) == 4 and all(line.endswith(": pass") for line in lines[:3]), lines
