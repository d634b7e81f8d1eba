"""Property-based tests of the Python API (hypothesis): random scenes within the documented bounds
keep the invariants of docs/model.md, and random bad input (NaN, inf, wrong types and shapes) is always
a ValueError or a TypeError, never a crash or a PanicException.

About 10^4 examples in all at the default scale (cheap scenes: Verlet or Gear-5 at the default
step, small polygons); ``RESTITUTION_HYPOTHESIS_SCALE=10`` multiplies every count
(``benchmarks/hypothesis_1e5.py`` runs 10^5)."""

from __future__ import annotations

import math
import os

import numpy as np
import polars as pl
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import restitution as rs

SCALE = int(os.environ.get("RESTITUTION_HYPOTHESIS_SCALE", "1"))

#: Every per-case column of the engine, from its own schema (all float64): a new one is fuzzed too.
ENGINE_FLOAT_COLUMNS = tuple(__import__("restitution._core", fromlist=["CASE_COLUMNS"]).CASE_COLUMNS)


def engine_run(overrides: dict[str, float], scene: rs.Scene | None = None) -> dict[str, np.ndarray]:
    """One case straight through the engine's own entry point (``restitution._core``), past every check
    of the Python side: the scene's columns (theta 45 deg) with ``overrides`` written over them.

    The only place this file calls ``_core``: adapt it here when the binding's signature changes."""
    from restitution import _core

    scene = scene if scene is not None else rs.Scene(integrator="verlet")
    cols = {k: np.array([v], dtype=np.float64) for k, v in scene.engine_values().items()}
    cols["theta_deg"] = np.array([45.0])
    for name, value in overrides.items():
        cols[name] = np.array([value], dtype=np.float64)
    return dict(_core.run_cases(cols, scene.template_vertices(), 1))


def examples(n: int) -> settings:
    return settings(max_examples=n * SCALE, deadline=None, derandomize=SCALE == 1,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


shapes = st.one_of(
    st.just(rs.Disc(r=0.01)),
    st.builds(rs.RegularPolygon, r=st.just(0.01), n=st.integers(3, 40), phi0_deg=st.floats(0.0, 360.0)),
)

scenes = st.builds(
    rs.Scene,
    shape=shapes,
    mu=st.one_of(st.just(0.0), st.floats(0.0, 2.0), st.floats(10.0, 1e3)),
    # Damping below 1e-2 behaves like none: on a polygon it meets the known, pinned O(dt^2) gain
    # of conservative face-first impacts (see the test below), so it is drawn as exactly 0.
    gamma=st.one_of(st.just(0.0), st.floats(1e-2, 3.0)),
    gamma_t=st.floats(0.0, 1.0),
    E=st.one_of(st.just(1e7), st.floats(1e5, 1e9)),
    # Slow grazing impacts of corners last very long (t_c / t_ref grows like v_n^(-1/3)): a
    # triangle at 0.5 deg and 1 mm/s takes 2e8 Verlet steps to its time-out, 60 s. Kept out of
    # this cheap suite; the extremes suites and the issue 7 report cover them.
    v=st.floats(1e-2, 0.3),
    integrator=st.sampled_from(["verlet", "gear5"]),
    # Built with a small step, then given the default 0.01 or the scene's own stability bound
    # where strong damping makes that smaller (a larger step is refused at construction).
    dt_factor=st.just(1e-6),
).map(lambda scene: scene.replace(dt_factor=min(0.01, scene.max_dt_factor)))


def simulate_or_refuse(scene: rs.Scene, theta: float, omega: float) -> rs.Record | None:
    """The record, or None where the scene is refused naming `v` (too deep) or `dt_factor`."""
    try:
        return rs.simulate(scene, theta_deg=theta, omega_in=omega)
    except ValueError as err:
        assert "`v`" in str(err) or "`dt_factor`" in str(err), str(err)
        return None


@examples(6000)
@given(scene=scenes, theta=st.floats(5.0, 90.0), omega=st.floats(-50.0, 50.0))
def test_random_scenes_keep_the_invariants(scene: rs.Scene, theta: float, omega: float) -> None:
    rec = simulate_or_refuse(scene, theta, omega)
    if rec is None:
        return
    values = [rec.e_n, rec.e_kin, rec.omega_out, rec.vx_out, rec.vy_out, rec.energy_out, rec.energy_residual]
    assert all(math.isfinite(x) for x in values)
    assert rec.e_t is None or math.isfinite(rec.e_t)
    assert rec.separated and not rec.timed_out
    known_gain = (not isinstance(scene.shape, rs.Disc) and scene.gamma == 0.0
                  and (scene.integrator == "verlet" or scene.mu > 0.0))
    if not known_gain:
        # Undamped polygons still gain up to ~5e-6 at the default step with Verlet (its own
        # O(dt^2) error) and, with friction too weak to dissipate it, with the plain steps that
        # frictional contacts keep: known, pinned as strict xfails in tests/test_extremes.py.
        assert rec.energy_out <= rec.energy_in * (1 + 1e-6)
    assert abs(rec.energy_residual) < 1e-3
    assert rec.work_friction <= 1e-6 * rec.energy_in
    if isinstance(scene.shape, rs.Disc):
        assert 0.0 < rec.e_n <= 1.0 + 1e-6
    if scene.mu == 0.0:
        # No tangential force: vx is untouched (Gear-5 keeps v dt, so its readback may differ
        # from the input in the last bit).
        assert rec.work_friction == 0.0
        assert rec.e_t is None or abs(rec.e_t - 1.0) <= 1e-12


@examples(200)
@given(scene=scenes, theta=st.lists(st.floats(5.0, 90.0), min_size=1, max_size=8, unique=True))
def test_sweep_rows_equal_single_impacts(scene: rs.Scene, theta: list[float]) -> None:
    try:
        df = rs.sweep(scene, theta_deg=theta)
    except ValueError as err:
        assert "`v`" in str(err) or "`dt_factor`" in str(err), str(err)
        return
    for row in df.iter_rows(named=True):
        rec = rs.simulate(scene, theta_deg=row["theta_deg"])
        assert rec.e_n == row["e_n"] and rec.omega_out == row["omega_out"]


# -- fuzzing: bad input is a ValueError or TypeError, never anything else ------------------------



def sane(x: float) -> bool:
    """Not a finite magnitude that is valid but absurd. Those are left out on purpose (reported in
    issue 7, to be refused at validation): theta_deg = 1e-10 or dt_factor = 1e-300 are accepted
    and then run for hours (the step cap is 1e12), omega_in = 1e300 overflows the energies."""
    return not math.isfinite(x) or x == 0.0 or 1e-3 <= abs(x) <= 1e3


# Invalid values of every kind, and a few valid ones.
junk = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, -1.0, 0.0, -0.0, -1e-300, -1e308, 1.0, 0.5]),
    st.floats(allow_nan=True, allow_infinity=True).filter(sane),
    st.integers(-10**3, 64),
    st.text(max_size=5),
    st.none(),
    st.booleans(),
    st.lists(st.floats().filter(sane), max_size=3),
    st.just(np.array([[1.0, 2.0]])),
    st.just(np.array([math.nan])),
    st.just(complex(1.0, 1.0)),
    st.just(object()),
)

SCENE_FIELDS = ["rho", "E", "gamma", "gamma_t", "mu", "v", "integrator", "dt_factor", "normal_law", "kn", "cn",
                "kt", "inertia", "shape"]


@examples(1500)
@given(field=st.sampled_from(SCENE_FIELDS), value=junk)
def test_fuzz_scene_fields(field: str, value: object) -> None:
    try:
        scene = rs.Scene(**{field: value})
    except (ValueError, TypeError):
        return
    # Accepted: then it must simulate or be refused cleanly.
    simulate_or_refuse(scene, 45.0, 0.0)


@examples(800)
@given(field=st.sampled_from(["r", "n", "phi0_deg", "vertices"]), value=junk)
def test_fuzz_shapes(field: str, value: object) -> None:
    try:
        if field == "vertices":
            shape = rs.ConvexPolygon(vertices=value)  # type: ignore[arg-type]
        elif field == "r":
            shape = rs.Disc(r=value)  # type: ignore[arg-type]
        else:
            shape = rs.RegularPolygon(**{"r": 0.01, "n": 6, "phi0_deg": 0.0, field: value})  # type: ignore[arg-type]
    except (ValueError, TypeError):
        return
    simulate_or_refuse(rs.Scene(shape=shape), 45.0, 0.0)


def as_real(x: object) -> float | None:
    """x as a float when it is a plain real number (bool, str, None, arrays and complex are not)."""
    if isinstance(x, bool) or not isinstance(x, (int, float, np.floating, np.integer)):
        return None
    return float(x)


@examples(1000)
@given(theta=junk | st.floats(-1e3, 1e3).filter(sane), omega=junk | st.floats(-1e3, 1e3).filter(sane))
def test_fuzz_simulate_arguments(theta: object, omega: object) -> None:
    t, w = as_real(theta), as_real(omega)
    valid = (t is not None and math.isfinite(t) and 0.0 < t <= 90.0
             and w is not None and math.isfinite(w) and abs(w) * 0.01 <= 1e6)
    try:
        rec = rs.simulate(rs.Scene(), theta_deg=theta, omega_in=omega)  # type: ignore[arg-type]
    except (ValueError, TypeError) as err:
        # Refused: the message names the argument at fault, or `v` for an impact too grazing to
        # resolve (theta ~ 1e-3 deg at the preset speed).
        assert any(name in str(err) for name in ("theta_deg", "omega_in", "`v`")), str(err)
        assert not valid or "`v`" in str(err), f"valid arguments refused: {err}"
        return
    assert valid, f"accepted theta_deg={theta!r}, omega_in={omega!r}"
    assert rec.separated and all(math.isfinite(x) for x in (rec.e_n, rec.e_kin, rec.omega_out, rec.energy_out))
    assert rec.energy_out <= rec.energy_in * (1 + 1e-6)


@examples(800)
@given(axis=st.sampled_from(["theta_deg", "omega_in", "mu", "v", "E", "n", "phi0_deg", "dt_factor", "gamma",
                             "integrator", "nonsense"]),
       value=junk | st.lists(junk, max_size=3))
def test_fuzz_sweep_axes(axis: str, value: object) -> None:
    axes = {"theta_deg": [30.0, 60.0]}
    axes[axis] = value  # type: ignore[assignment]
    try:
        df = rs.sweep(rs.Scene(integrator="verlet"), **axes)
    except (ValueError, TypeError) as err:
        # Refused: the message names the axis at fault, or the parameter an accepted axis value
        # made impossible (`v` too deep, `dt_factor` above a damped scene's bound).
        assert any(name in str(err) for name in (axis, "`v`", "`dt_factor`")), str(err)
        return
    assert axis != "nonsense", "an unknown axis was accepted"
    values = len(np.atleast_1d(np.asarray(value, dtype=object)))
    assert df.height == (values if axis == "theta_deg" else 2 * values)  # the axis replaced or multiplied
    assert np.isfinite(df["e_n"].to_numpy()).all()
    assert df["separated"].all()


@examples(300)
@given(column=st.sampled_from(["theta_deg", "mu", "v", "omega_in"]),
       values=st.lists(st.floats(allow_nan=True, allow_infinity=True).filter(sane), min_size=1, max_size=4))
def test_fuzz_cases_table(column: str, values: list[float]) -> None:
    cases = pl.DataFrame({"theta_deg": [45.0] * len(values)})
    cases = cases.with_columns(pl.Series(column, values, dtype=pl.Float64))
    try:
        df = rs.sweep(rs.Scene(integrator="verlet"), cases=cases)
    except (ValueError, TypeError):
        return
    assert np.isfinite(df["e_n"].to_numpy()).all()


def test_panics_never_escape() -> None:
    # A pyo3 PanicException derives from BaseException: the fuzz tests above would not catch it,
    # and it would fail them. NaN is refused by the Python side first, so it is sent to the engine
    # directly here: the engine itself must refuse it with a ValueError naming the column.
    for column in ("theta_deg", "v", "E", "mu", "rho", "r"):
        with pytest.raises(ValueError, match=column if column != "E" else "`E`"):
            engine_run({column: math.nan})


bad_floats = st.sampled_from([math.nan, math.inf, -math.inf, -1.0, 0.0, -0.0, 1e308, -1e308, 5e-324, 1e-300])


@examples(600)
@given(column=st.sampled_from(ENGINE_FLOAT_COLUMNS), value=bad_floats)
def test_fuzz_engine_columns(column: str, value: float) -> None:
    """The engine's own entry point with bad columns: a ValueError, or finite records that gain no
    energy (some values are valid there: NaN means unset for kn, cn and kt), never a panic."""
    try:
        raw = engine_run({column: value})
    except ValueError as err:
        assert str(err), "an empty message"
        return
    values = np.concatenate([np.asarray(raw[k], dtype=np.float64) for k in ("e_n", "energy_out", "energy_in")])
    assert np.isfinite(values).all(), (column, value)
    assert raw["energy_out"][0] <= raw["energy_in"][0] * (1 + 1e-6)
