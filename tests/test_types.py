"""One type rule everywhere (issue 42, item 3).

``Scene`` refuses a bool or a string where a number is expected and a number where a name is;
sweep axes, ``cases`` columns, ensemble axes and draws, and a collision operator's axes apply
the same rule (``_engine.is_real``, ``_engine.code``), so ``theta_deg=[True]`` no longer runs at
1 degree and a ``cases`` column of strings "1e1" no longer runs at 10 degrees. In a cases table
every refused value, a wrong type or a bad name as much as a number out of range, names its row
in ``.case``.
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np
import polars as pl
import pytest

import restitution as rs

SCENE = rs.Scene(integrator="gear5")


def _refusal(call: Callable[[], Any]) -> rs.RestitutionError:
    with pytest.raises(TypeError) as info:
        call()
    err = info.value
    assert isinstance(err, rs.RestitutionError), f"{type(err).__name__}: {err}"
    return err


def _number_rule() -> str:
    """Scene's own rule, read from Scene's own refusal: every other place must state the same one."""
    return _refusal(lambda: rs.Scene(mu=True)).expected


@pytest.mark.parametrize("value", [[True], True, "1e1", ["30"], [30.0, "45"], np.array([True, False]),
                                   [np.bool_(True)], [30.0, None]])
def test_sweep_axes_refuse_bools_and_strings_as_scene_does(value: Any) -> None:
    err = _refusal(lambda: rs.sweep(SCENE, theta_deg=value))
    assert err.parameter == "theta_deg" and err.expected == _number_rule()
    err = _refusal(lambda: rs.sweep(SCENE, theta_deg=30.0, mu=value))
    assert err.parameter == "mu" and err.expected == _number_rule()


def test_numbers_are_refused_for_names_in_scene_and_in_sweeps() -> None:
    scene_err = _refusal(lambda: rs.Scene(integrator=1))  # type: ignore[arg-type]
    sweep_err = _refusal(lambda: rs.sweep(SCENE, theta_deg=30.0, integrator=["gear5", 1]))
    assert scene_err.parameter == sweep_err.parameter == "integrator"
    assert scene_err.expected == sweep_err.expected


def test_numbers_of_any_numeric_kind_still_run() -> None:
    df = rs.sweep(SCENE, theta_deg=np.array([30, 60], dtype=np.int32), mu=[np.float32(0.5), 1])
    assert df["theta_deg"].to_list() == [30.0, 30.0, 60.0, 60.0]
    assert df["mu"].to_list() == [0.5, 1.0, 0.5, 1.0]


@pytest.mark.parametrize("column, values, bad_row", [
    ("theta_deg", ["30", "1e1"], 0),
    ("theta_deg", [True, False], 0),
    ("mu", ["0.1", None, "x"], 0),
    ("integrator", [1, 2], 0),
])
def test_a_cases_column_of_the_wrong_type_names_its_row(column: str, values: Any, bad_row: int) -> None:
    cases = pl.DataFrame({"theta_deg": [30.0, 45.0, 60.0][:len(values)]}).with_columns(pl.Series(column, values))
    err = _refusal(lambda: rs.sweep(SCENE, cases=cases))
    assert err.parameter == column and err.case == bad_row


@pytest.mark.parametrize("column, values, bad_row", [
    ("integrator", ["gear5", "rk4", "gear5"], 1),
    ("integrator", ["gear5", "gear5", None], 2),
    ("mu", [0.1, 0.2, -1.0], 2),
    ("theta_deg", [30.0, 120.0, 45.0], 1),
])
def test_every_bad_value_in_a_cases_table_carries_its_row(column: str, values: list, bad_row: int) -> None:
    cases = pl.DataFrame({"theta_deg": [30.0, 45.0, 60.0]}).with_columns(pl.Series(column, values))
    with pytest.raises(rs.RestitutionError) as err:
        rs.sweep(SCENE, cases=cases)
    assert err.value.parameter == column and err.value.case == bad_row, str(err.value)


def test_ensemble_axes_and_draws_follow_the_same_rule() -> None:
    vary = {"phi0_deg": rs.Uniform(0.0, 90.0)}
    err = _refusal(lambda: rs.ensemble(SCENE, 4, vary=vary, seed=1, theta_deg=[True]))
    assert err.parameter == "theta_deg" and err.expected == _number_rule()
    err = _refusal(lambda: rs.ensemble(SCENE, 4, vary={"integrator": rs.Choice([1, 2])}, seed=1, theta_deg=30.0))
    assert err.parameter == "integrator"
    err = _refusal(lambda: rs.ensemble(SCENE, 4, vary={"mu": rs.Choice(["0.1", "0.2"])}, seed=1, theta_deg=30.0))
    assert err.parameter == "mu" and err.expected == _number_rule()


@pytest.mark.parametrize("axes", [{"theta_deg": [True, 60.0]}, {"theta_deg": "45"},
                                  {"theta_deg": [30.0, 60.0], "omega_in": [False]},
                                  {"theta_deg": [30.0, 60.0], "v": ["0.03"]}])
def test_operator_axes_follow_the_same_rule(axes: dict[str, Any]) -> None:
    err = _refusal(lambda: rs.CollisionOperator.build(SCENE, **axes, n_check=2))
    assert err.parameter in axes and err.expected == _number_rule()
