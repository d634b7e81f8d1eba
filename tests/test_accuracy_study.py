"""The accuracy study (``restitution accuracy``): the adaptive path at several tolerances sits beside
the fixed steps, and the recommendation per target error is the cheapest configuration that meets it,
whichever integrator that is."""

from __future__ import annotations

import math

import polars as pl
import pytest

from restitution.study import accuracy


@pytest.fixture(scope="module")
def table():
    # The exact disc, two angles, with and without friction: gear5 at two steps, the adaptive path
    # at two tolerances (seconds).
    return accuracy.study(shapes=(0,), steps={"gear5": (0.02, 0.005)}, tols=(1e-4, 1e-8), theta=(20.0, 60.0),
                          mu=(0.0, 0.5))


def test_the_adaptive_path_is_in_the_table_at_each_tolerance(table):
    adaptive = table.filter(pl.col("integrator") == "adaptive")
    assert sorted(adaptive["tol"].to_list()) == [1e-8, 1e-4]
    assert (adaptive["dt_factor"] == accuracy.ADAPTIVE_STEP).all()
    # The fixed-step rows have no tolerance.
    assert table.filter(pl.col("integrator") == "gear5")["tol"].is_nan().all()
    assert "tol=1e-08" in accuracy.markdown(table)


def test_each_configuration_converges_the_way_its_method_says(table):
    gear5 = {r["dt_factor"]: r["err_max"] for r in table.filter(pl.col("integrator") == "gear5").iter_rows(named=True)}
    # Gear-5 with stick/slip is first order at best: a 4x smaller step is at least 2x more accurate.
    assert gear5[0.005] < 0.5 * gear5[0.02]
    for r in table.filter(pl.col("integrator") == "adaptive").iter_rows(named=True):
        # The tolerance is honoured (issue 13: the largest error at most 3 tol), and it costs steps.
        assert r["err_max"] <= 3 * r["tol"], r
    steps = dict(zip(*table.filter(pl.col("integrator") == "adaptive").select("tol", "steps")))
    assert steps[1e-8] > steps[1e-4]


def synthetic(rows):
    """A hand-made study table: (shape, integrator, dt_factor, tol, us, err_max)."""
    return pl.DataFrame([dict(shape=s, integrator=i, dt_factor=d, tol=t, us_per_impact=c, err_max=e)
                         for s, i, d, t, c, e in rows])


def test_recommend_picks_the_cheapest_configuration_that_meets_the_target():
    nan = math.nan
    t = synthetic([
        ("disc", "reference", 0.2, nan, 500.0, 0.0),
        ("disc", "gear5", 0.03, nan, 50.0, 7e-4),
        ("disc", "gear5", 0.01, nan, 110.0, 2e-4),
        ("disc", "adaptive", 1.0, 1e-4, 40.0, 5e-7),
        ("disc", "adaptive", 1.0, 1e-8, 90.0, 1e-9),
    ])
    # 1e-3: gear5 0.03 meets it, but the adaptive path at 1e-4 meets it cheaper.
    assert accuracy.recommend(t, 1e-3)["disc"].startswith("adaptive tol=1e-04")
    assert accuracy.recommend(t, 1e-8)["disc"].startswith("adaptive tol=1e-08")
    # Nothing but the reference reaches 1e-12.
    assert accuracy.recommend(t, 1e-12)["disc"].startswith("reference")
    # Without the adaptive rows the fixed step is chosen again.
    fixed = t.filter(pl.col("integrator") != "adaptive")
    assert accuracy.recommend(fixed, 1e-3)["disc"].startswith("gear5 dt_factor=0.03")
