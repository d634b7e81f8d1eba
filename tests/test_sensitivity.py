"""rs.calibrate.sensitivity: Sobol' indices checked where the answer is known.

On the sliding branch rigid-body theory gives e_T = 1 - k mu (1 + e_N) for the sphere (k a
function of the angle), and the Hertz law's e_N is the requested cor: e_T - 1 is a product of
two independent factors, whose Sobol' indices are closed-form. A sphere's e_N on a plate does not
depend on friction at all (ST = 0), and on the disc's sliding branch e_T does not depend on the
tangential stiffness, which takes over near normal incidence.
"""

from __future__ import annotations


import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.calibrate import _forward

SPHERE = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98,
                  mu=0.092, v=3.9)
MU, COR = rs.Uniform(0.05, 0.3), rs.Uniform(0.5, 0.99)


def _moments(d: rs.Uniform) -> tuple[float, float]:
    return 0.5 * (d.lo + d.hi), (d.hi - d.lo) ** 2 / 12.0


def product_indices(x1: rs.Uniform, x2_minus_1: rs.Uniform) -> dict[str, float]:
    """S1 and ST of Y = X1 X2 with X1 ~ x1 and X2 = 1 + (a draw of x2_minus_1), independent:
    V_1 = E[X2]^2 Var X1, V_2 = E[X1]^2 Var X2, Var Y = E[X1^2] E[X2^2] - E[X1]^2 E[X2]^2, and
    with two factors ST_1 = 1 - S1_2."""
    m1, v1 = _moments(x1)
    m2, v2 = _moments(x2_minus_1)
    m2 += 1.0
    var = (v1 + m1 * m1) * (v2 + m2 * m2) - (m1 * m2) ** 2
    s1, s2 = m2 * m2 * v1 / var, m1 * m1 * v2 / var
    return {"S1 mu": s1, "S1 cor": s2, "ST mu": 1.0 - s2, "ST cor": 1.0 - s1}


@pytest.fixture(scope="module")
def sliding() -> pl.DataFrame:
    return rs.calibrate.sensitivity(SPHERE, {"mu": MU, "cor": COR}, n=256, seed=3, theta_deg=[10.0, 20.0, 90.0],
                                    quantities=["e_n", "e_t"], n_resamples=299)



def test_sliding_branch_indices_are_the_products(sliding):
    expected = product_indices(MU, COR)
    for theta in (10.0, 20.0):
        part = sliding.filter((pl.col("quantity") == "e_t") & (pl.col("theta_deg") == theta))
        for row in part.iter_rows(named=True):
            for index in ("S1", "ST"):
                value = expected[f"{index} {row['parameter']}"]
                assert row[f"{index}_lo"] <= value <= row[f"{index}_hi"], (theta, row, value)
                assert abs(row[index] - value) < 0.02, (theta, row, value)
    # e_T - 1 scales with the angle on this branch, and indices do not see a scale.
    at = {t: sliding.filter((pl.col("quantity") == "e_t") & (pl.col("theta_deg") == t))["ST"].to_numpy()
          for t in (10.0, 20.0)}
    assert np.allclose(at[10.0], at[20.0], atol=1e-3), at


def test_e_n_of_a_sphere_ignores_friction(sliding):
    e_n = sliding.filter(pl.col("quantity") == "e_n")
    mu, cor = e_n.filter(pl.col("parameter") == "mu"), e_n.filter(pl.col("parameter") == "cor")
    assert (mu["ST_hi"] < 1e-9).all() and (mu["ST_lo"] <= mu["ST"]).all(), mu
    assert (cor["ST"] > 0.999).all() and (cor["ST_lo"] <= 1.0).all() and (cor["ST_hi"] >= 1.0).all(), cor


def test_head_on_e_t_is_undefined_and_first_order_sums_below_one(sliding):
    head_on = sliding.filter((pl.col("quantity") == "e_t") & (pl.col("theta_deg") == 90.0))
    assert head_on["ST"].null_count() == head_on.height == 2
    sums = sliding.drop_nulls("S1").group_by("quantity", "theta_deg").agg(pl.col("S1").sum(), pl.col("S1_lo").sum())
    assert (sums["S1_lo"] <= 1.0).all() and (sums["S1"] <= 1.02).all(), sums


def test_stiffness_matters_only_off_the_sliding_branch():
    """The disc's linear law: grazing impacts slide throughout (e_T is mu's alone); near normal
    incidence the tangential spring's oscillation sets e_T (kt's, mu barely)."""
    scene = rs.Scene.paper(shape=rs.Disc(r=0.01), normal_law="linear")
    s = rs.calibrate.sensitivity(scene, {"mu": rs.Uniform(0.1, 0.3), "kt": rs.Uniform(1e6, 5e6)}, n=64,
                                 theta_deg=[10.0, 80.0], quantities=["e_t"], n_resamples=199)
    st = {(r["parameter"], r["theta_deg"]): r for r in s.iter_rows(named=True)}
    assert st["kt", 10.0]["ST_hi"] < 1e-3 and st["mu", 10.0]["ST_lo"] > 0.7, st
    assert st["mu", 80.0]["ST_hi"] < 0.05 and st["kt", 80.0]["ST_lo"] > 0.7, st


def test_reproducible_and_plotted(tmp_path):
    kwargs = dict(n=32, seed=7, theta_deg=[20.0, 40.0], omega_in=[0.0, 50.0], quantities=["e_t"], n_resamples=49)
    a = rs.calibrate.sensitivity(SPHERE, {"mu": MU, "cor": COR}, **kwargs)
    b = rs.calibrate.sensitivity(SPHERE, {"mu": MU, "cor": COR}, **kwargs)
    assert a.equals(b) and a.height == 8
    assert a.columns == ["quantity", "parameter", "theta_deg", "omega_in", "S1", "S1_lo", "S1_hi", "ST", "ST_lo",
                         "ST_hi"]
    fig = rs.calibrate.plot_sensitivity(a, path=tmp_path / "s.png")
    assert len(fig.axes) == 2 and (tmp_path / "s.png").exists()
    import matplotlib.pyplot as plt

    plt.close(fig)


@pytest.mark.parametrize("kwargs, name", [
    (dict(n=100), "n"),
    (dict(n=8), "n"),
    (dict(quantities=["e_x"]), "quantities"),
    (dict(vary={}), "vary"),
    (dict(vary={"integrator": rs.Choice(["gear5", "adaptive"])}), "vary"),
    (dict(vary={"theta_deg": MU}), "vary"),
    (dict(seed=-1), "seed"),
    (dict(confidence_level=1.5), "confidence_level"),
    (dict(n_resamples=0), "n_resamples"),
])
def test_refusals_name_the_parameter(kwargs, name):
    args = {"vary": {"mu": MU, "cor": COR}, "n": 32, "theta_deg": [20.0], **kwargs}
    with pytest.raises(rs.RestitutionError) as err:
        rs.calibrate.sensitivity(SPHERE, **args)
    assert err.value.parameter == name


def test_without_scipy_the_error_names_the_extra(monkeypatch):
    monkeypatch.setitem(__import__("sys").modules, "scipy.stats", None)
    with pytest.raises(ImportError, match=r'pip install "restitution\[calibrate\]"'):
        rs.calibrate.sensitivity(SPHERE, {"mu": MU, "cor": COR}, n=32, theta_deg=[20.0])
