"""Every public function refuses a bad setting by name; a collision operator's file is read back
whole or refused naming it, and its info never says "converged" where its stated error exceeds
``tol`` (issue 42, item 4). On main (3d9409c) ``max_nodes=0`` and ``max_rounds=-1`` built tables, ``max_nodes="x"``
was a bare TypeError, a 2-node table erring 100x ``tol`` said ``stopped="converged"``, and a
truncated or foreign file raised polars' or json's errors without its path.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.collision import build as _build
from restitution.collision.operator import META_KEY

SCENE = rs.Scene(integrator="verlet", dt_factor=0.09, mu=0.3)


@pytest.mark.parametrize("name, value", [
    ("max_nodes", 0), ("max_nodes", -5), ("max_nodes", "x"), ("max_nodes", 2.5), ("max_nodes", True),
    ("max_rounds", -1), ("max_rounds", "3"), ("max_rounds", None),
    ("tol", 0.0), ("tol", math.nan), ("tol", True), ("tol", "1e-3"),
    ("n_check", 1), ("n_check", 16.0), ("threads", 0), ("progress", "yes"), ("seed", -1), ("n", 0),
    ("sampling", "sobol"),
])
def test_build_refuses_each_bad_setting_by_name(name: str, value: Any) -> None:
    with pytest.raises(rs.RestitutionError) as err:
        rs.CollisionOperator.build(SCENE, theta_deg=[30.0, 60.0], **{name: value})
    assert err.value.parameter == name, str(err.value)


@pytest.mark.parametrize("call", [
    lambda: rs.sweep(SCENE, theta_deg=30.0, progress="no"),
    lambda: rs.ensemble(SCENE, 2, vary={"mu": rs.Uniform(0.0, 1.0)}, seed=1, theta_deg=30.0, progress=1),
])
def test_progress_is_true_false_or_none(call: Any) -> None:
    with pytest.raises(rs.RestitutionError) as err:
        call()
    assert err.value.parameter == "progress"


def test_the_dataset_flags_are_booleans(tmp_path: Path) -> None:
    for name in ("resume", "wait"):
        with pytest.raises(rs.RestitutionError) as err:
            rs.sweep_to_dataset(SCENE, tmp_path / name, theta_deg=30.0, **{name: "no"})
        assert err.value.parameter == name


def test_a_coarse_table_erring_beyond_tol_does_not_say_converged() -> None:
    op = rs.CollisionOperator.build(SCENE, theta_deg=[45.0], omega_in=[-1.0, 1.0], tol=1e-4, n_check=16,
                                    progress=False)
    worst = float(op.error["max_abs"].max())
    assert worst > 10 * op.tol  # two spin nodes cannot carry the spin's curve
    assert op.info["stopped"] == "rough", op.info


def _errors(max_abs: list[float], smooth: list[float | None]) -> pl.DataFrame:
    return pl.DataFrame({"max_abs": max_abs, "max_abs_smooth": smooth},
                        schema={"max_abs": pl.Float64, "max_abs_smooth": pl.Float64})


@pytest.mark.parametrize("stopped, max_abs, smooth, expected", [
    ("converged", [1e-4, 5e-4], [1e-4, 5e-4], "converged"),
    ("converged", [1e-4, 2e-3], [1e-4, 5e-4], "rough"),
    ("converged", [1e-4, 2e-3], [None, None], "rough"),
    ("converged", [1e-4, 2e-3], [1e-4, 2e-3], "unresolved"),
    ("max_rounds", [1e-4, 2e-3], [1e-4, 2e-3], "max_rounds"),
    ("max_nodes", [1e-6, 1e-6], [1e-6, 1e-6], "max_nodes"),
])
def test_the_verdict_says_converged_only_within_tol(stopped: str, max_abs: list[float],
                                                    smooth: list[float | None], expected: str) -> None:
    assert _build.verdict(stopped, _errors(max_abs, smooth), 1e-3) == expected


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> Path:
    op = rs.CollisionOperator.build(SCENE, theta_deg=[30.0, 60.0], tol=1e-2, n_check=4, progress=False)
    return op.save(tmp_path_factory.mktemp("op") / "op.parquet")


def _damage(saved: Path, tmp_path: Path, how: str) -> Path:
    path = tmp_path / "op.parquet"
    meta = json.loads(pl.read_parquet_metadata(saved)[META_KEY])
    frame = pl.read_parquet(saved)
    if how == "truncated":
        path.write_bytes(saved.read_bytes()[: saved.stat().st_size // 2])
    elif how == "not parquet":
        path.write_text("theta_deg,vn_ratio\n30,0.9\n")
    elif how == "foreign parquet":
        frame.write_parquet(path)  # the same rows, no metadata: not written by save
    elif how == "rows cut":
        frame.head(frame.height - 1).write_parquet(path, metadata={META_KEY: json.dumps(meta)})
    elif how == "value edited":
        frame.with_columns(pl.col("vn_ratio") * 1.01).write_parquet(path, metadata={META_KEY: json.dumps(meta)})
    elif how == "metadata edited":
        frame.write_parquet(path, metadata={META_KEY: json.dumps({**meta, "tol": 1e-9})})
    elif how == "metadata not json":
        frame.write_parquet(path, metadata={META_KEY: "{not json"})
    elif how == "metadata lacks a key":
        frame.write_parquet(path, metadata={META_KEY: json.dumps({k: v for k, v in meta.items() if k != "shape"})})
    elif how == "missing":
        pass
    return path


@pytest.mark.parametrize("how", ["truncated", "not parquet", "foreign parquet", "rows cut", "value edited",
                                 "metadata edited", "metadata not json", "metadata lacks a key", "missing"])
def test_load_refuses_a_bad_file_naming_it(saved: Path, tmp_path: Path, how: str) -> None:
    path = _damage(saved, tmp_path, how)
    with pytest.raises(rs.RestitutionError) as err:
        rs.CollisionOperator.load(path)
    assert err.value.parameter == "path" and str(path) in str(err.value), str(err.value)


def test_load_gives_back_the_saved_table(saved: Path) -> None:
    op = rs.CollisionOperator.load(saved)
    again = rs.CollisionOperator.load(op.save(saved.with_name("again.parquet")))
    assert np.array_equal(op.table.values, again.table.values) and op.info == again.info


@pytest.mark.parametrize("call, name", [
    (lambda ens: ens.summary(seed=-1), "seed"),
    (lambda ens: ens.summary("e_n"), "quantities"),
    (lambda ens: ens.summary(n_boot="x"), "n_boot"),
], ids=["seed", "quantities", "n_boot"])
def test_an_ensemble_summary_refuses_its_settings_by_name(call: Any, name: str) -> None:
    ens = rs.ensemble(SCENE, 8, vary={"mu": rs.Uniform(0.0, 1.0)}, seed=1, theta_deg=[30.0])
    with pytest.raises(ValueError, match=f"`{name}`"):
        call(ens)


@pytest.mark.parametrize("call, name", [
    (lambda d: rs.simulate(SCENE, 30.0, trace="no"), "trace"),
    (lambda d: rs.read_dataset(d, allow_partial="yes"), "allow_partial"),
], ids=["trace", "allow_partial"])
def test_boolean_settings_take_booleans_only(tmp_path: Path, call: Any, name: str) -> None:
    d = tmp_path / "d"
    rs.sweep_to_dataset(SCENE, d, theta_deg=[30.0, 60.0])
    with pytest.raises(rs.RestitutionError) as err:
        call(d)
    assert err.value.parameter == name


@pytest.mark.parametrize("call, name", [
    (lambda: rs.calibrate.gamma_for_e_n(SCENE, 0.9, tol="x"), "tol"),
    (lambda: rs.calibrate.gamma_for_e_n(SCENE, 0.9, gamma_max=0.0), "gamma_max"),
    (lambda: rs.calibrate.gamma_for_e_n(SCENE, True), "e_n"),
    (lambda: rs.calibrate.mu_for_e_t(SCENE, 0.85, 20.0, mu_max=-1.0), "mu_max"),
    (lambda: rs.calibrate.mu_for_e_t(SCENE, 0.85, 20.0, tol=0.0), "tol"),
    (lambda: rs.theory.theta_c(0.9, 0.5, v=True), "v"),
    (lambda: rs.theory.e_t(30.0, 0.9, 0.5, r="0.01"), "r"),
], ids=["calibrate-tol-type", "gamma_max", "e_n", "mu_max", "calibrate-tol-range", "theory-v", "theory-r"])
def test_the_study_functions_refuse_their_settings_by_name(call: Any, name: str) -> None:
    with pytest.raises(rs.RestitutionError) as err:
        call()
    assert err.value.parameter == name
