"""sweep: the same numbers as single simulate calls, in Cartesian-product order, as a polars frame."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import polars as pl
import pytest
from polars.testing import assert_frame_equal

import restitution as rs
from restitution._engine import RECORD_COLUMNS

#: Axes of issue 3 (theta, mu, gamma, omega_in), small enough to check every row one by one.
AXES = {
    "theta_deg": np.array([10.0, 45.0, 90.0]),
    "mu": np.array([0.0, 0.4]),
    "gamma": np.array([0.0, 0.33]),
    "omega_in": np.array([-2.0, 0.0, 1.5]),
}


def record_row(rec: rs.Record) -> dict[str, object]:
    return {k: getattr(rec, k) for k in RECORD_COLUMNS}


@pytest.fixture(scope="module")
def base_scene() -> rs.Scene:
    return rs.Scene(gamma_t=0.25)  # a non-default value that only the scene carries


@pytest.fixture(scope="module")
def product_frame(base_scene: rs.Scene) -> pl.DataFrame:
    return rs.sweep(base_scene, threads=1, **AXES)


def test_rows_are_the_cartesian_product_first_axis_slowest(product_frame: pl.DataFrame) -> None:
    expected = list(itertools.product(*(a.tolist() for a in AXES.values())))
    assert product_frame.select(list(AXES)).rows() == expected
    assert product_frame.columns == list(AXES) + list(RECORD_COLUMNS)


@pytest.mark.parametrize("threads", [1, 2])
def test_sweep_equals_simulate_bit_for_bit(base_scene: rs.Scene, product_frame: pl.DataFrame, threads: int) -> None:
    df = product_frame if threads == 1 else rs.sweep(base_scene, threads=threads, **AXES)
    for row in df.iter_rows(named=True):
        scene = base_scene.replace(mu=row["mu"], gamma=row["gamma"])
        rec = rs.simulate(scene, theta_deg=row["theta_deg"], omega_in=row["omega_in"])
        got = {k: row[k] for k in RECORD_COLUMNS}
        assert got == record_row(rec), f"row {row['theta_deg'], row['mu'], row['gamma'], row['omega_in']}"


def test_thread_count_does_not_change_a_bit(base_scene: rs.Scene, product_frame: pl.DataFrame) -> None:
    two = rs.sweep(base_scene, threads=2, **AXES)
    assert_frame_equal(product_frame, two, check_exact=True)
    # nor does the chunking into engine calls
    chunked = rs.sweep(base_scene, threads=2, chunk_size=5, **AXES)
    assert_frame_equal(product_frame, chunked, check_exact=True)


def test_cases_frame_gives_the_rows_of_the_equivalent_product(base_scene: rs.Scene,
                                                             product_frame: pl.DataFrame) -> None:
    cases = pl.DataFrame(list(itertools.product(*(a.tolist() for a in AXES.values()))),
                         schema=list(AXES), orient="row")
    df = rs.sweep(base_scene, cases=cases, threads=2)
    assert_frame_equal(df, product_frame, check_exact=True)
    # a shuffled table gives the same rows, in its own order
    perm = np.random.default_rng(3).permutation(cases.height)
    shuffled = rs.sweep(base_scene, cases=cases[perm], threads=2)
    assert_frame_equal(shuffled, product_frame[perm], check_exact=True)


def test_dtypes(product_frame: pl.DataFrame) -> None:
    schema = product_frame.schema
    for name in list(AXES) + ["e_n", "e_t", "e_kin", "omega_out", "beta", "vx_out", "vy_out", "contact_time",
                              "max_depth", "energy_in", "energy_out", "energy_residual"]:
        assert schema[name] == pl.Float64, name
    for name in ("steps", "contacts", "slip_events"):
        assert schema[name].is_integer(), name
    for name in ("separated", "timed_out"):
        assert schema[name] == pl.Boolean, name


def test_undefined_ratios_are_null_never_nan(product_frame: pl.DataFrame) -> None:
    df = product_frame
    floats = [c for c, t in df.schema.items() if t == pl.Float64]
    assert not df.select(pl.any_horizontal(pl.col(floats).is_nan()).any()).item()
    assert not df.select(pl.any_horizontal(pl.col(floats).is_infinite()).any()).item()
    head_on = pl.col("theta_deg") == 90.0
    # e_t = vx'/vx: undefined exactly at 90 deg.
    assert df.filter(head_on)["e_t"].null_count() == df.filter(head_on).height
    assert df.filter(~head_on)["e_t"].null_count() == 0
    # beta = -v_cp'/v_cp with v_cp = vx + r omega_in: undefined only where both vanish.
    no_cp = head_on & (pl.col("omega_in") == 0.0)
    assert df.filter(no_cp)["beta"].null_count() == df.filter(no_cp).height > 0
    assert df.filter(~no_cp)["beta"].null_count() == 0


def test_energy_audit_across_a_sweep(product_frame: pl.DataFrame) -> None:
    df = product_frame
    assert df["energy_residual"].abs().max() < 1e-6
    assert (df["energy_out"] <= df["energy_in"] * (1 + 1e-6)).all()
    assert df["separated"].all() and not df["timed_out"].any()
    elastic = df.filter((pl.col("mu") == 0.0) & (pl.col("gamma") == 0.0))
    assert (elastic["e_n"] - 1.0).abs().max() < 1e-6
    assert (elastic["e_t"].drop_nulls() - 1.0).abs().max() < 1e-12  # exactly 1: test_simulate


@pytest.mark.parametrize("integrator", [
    "gear5",
    "verlet",
    "reference",
])
def test_frictionless_e_t_is_exactly_one_at_every_angle(integrator: str) -> None:
    # Issue 3: mu = 0 gives e_t = 1 exactly (no tangential force ever acts), at any angle.
    scene = rs.Scene(mu=0.0, gamma=0.0, integrator=integrator)
    df = rs.sweep(scene, theta_deg=np.arange(1.0, 90.0), omega_in=[0.0, 2.0])
    assert df.filter(pl.col("e_t") != 1.0).select("theta_deg", "e_t").rows() == []
    assert (df["omega_out"] == df["omega_in"]).all()


def test_r_and_material_axes_equal_the_scenes_they_stand_for() -> None:
    base = rs.Scene(mu=0.3)
    df = rs.sweep(base, theta_deg=[35.0], r=[0.004, 0.02], E=[5e6, 2e7], rho=[1000.0], v=[0.02, 0.05], threads=2)
    for row in df.iter_rows(named=True):
        scene = base.replace(shape=rs.Disc(r=row["r"]), E=row["E"], rho=row["rho"], v=row["v"])
        assert {k: row[k] for k in RECORD_COLUMNS} == record_row(rs.simulate(scene, theta_deg=35.0))


def test_n_and_phi0_axes_make_regular_polygons() -> None:
    base = rs.Scene(mu=0.5, shape=rs.RegularPolygon(r=0.01, n=6, phi0_deg=0.0))
    df = rs.sweep(base, theta_deg=[30.0, 75.0], n=[0, 5, 8], phi0_deg=[0.0, 17.0], threads=2)
    assert df.schema["n"].is_integer()
    assert df.select("theta_deg", "n", "phi0_deg").rows() == list(
        itertools.product([30.0, 75.0], [0, 5, 8], [0.0, 17.0]))
    for row in df.iter_rows(named=True):
        shape = (rs.Disc(r=0.01) if row["n"] == 0 else
                 rs.RegularPolygon(r=0.01, n=row["n"], phi0_deg=row["phi0_deg"]))
        rec = rs.simulate(base.replace(shape=shape), theta_deg=row["theta_deg"])
        assert {k: row[k] for k in RECORD_COLUMNS} == record_row(rec), (row["n"], row["phi0_deg"])
    # The orientation matters for a pentagon and not for the disc.
    at = {(row["theta_deg"], row["n"], row["phi0_deg"]): row for row in df.iter_rows(named=True)}
    assert at[(30.0, 5, 0.0)]["e_n"] != at[(30.0, 5, 17.0)]["e_n"]
    assert at[(30.0, 0, 0.0)]["e_n"] == at[(30.0, 0, 17.0)]["e_n"]


def test_regular_polygon_is_symmetric_under_a_turn_by_its_corner_angle() -> None:
    # Turning a pentagon by 72 deg gives the same body: the same impact up to rounding.
    base = rs.Scene(mu=0.5, shape=rs.RegularPolygon(r=0.01, n=5))
    df = rs.sweep(base, theta_deg=[40.0], phi0_deg=[7.0, 79.0, 7.0 - 144.0], threads=1)
    for col in ("e_n", "e_t", "omega_out", "contact_time"):
        vals = df[col].to_numpy()
        np.testing.assert_allclose(vals, vals[0], rtol=1e-8, err_msg=col)


def test_convex_polygon_scene_sweeps_like_simulate() -> None:
    tri = rs.ConvexPolygon([(0.0, 0.0), (0.02, 0.0), (0.005, 0.015)], phi0_deg=10.0)
    base = rs.Scene(mu=0.4, shape=tri)
    df = rs.sweep(base, theta_deg=[25.0, 60.0], omega_in=[0.0, -3.0], threads=2)
    for row in df.iter_rows(named=True):
        rec = rs.simulate(base, theta_deg=row["theta_deg"], omega_in=row["omega_in"])
        assert {k: row[k] for k in RECORD_COLUMNS} == record_row(rec)


def test_integrator_axis_is_a_string_column_and_matches_the_scene() -> None:
    base = rs.Scene(mu=0.5)
    df = rs.sweep(base, theta_deg=[50.0], integrator=["gear5", "verlet"], threads=1)
    assert df.schema["integrator"] == pl.String
    assert df["integrator"].to_list() == ["gear5", "verlet"]
    for row in df.iter_rows(named=True):
        rec = rs.simulate(base.replace(integrator=row["integrator"]), theta_deg=50.0)
        assert {k: row[k] for k in RECORD_COLUMNS} == record_row(rec)
    # Two integrators of the same law agree closely at the default step (docs/model.md, section 7.6: ~1e-4).
    assert math.isclose(df["e_t"][0], df["e_t"][1], rel_tol=1e-3)


def test_scalar_axes_and_integer_theta_are_accepted(disc_scene: rs.Scene) -> None:
    df = rs.sweep(disc_scene, theta_deg=45, mu=0.2)
    assert df.height == 1 and df.schema["theta_deg"] == pl.Float64
    assert df.row(0, named=True)["e_n"] == rs.simulate(disc_scene.replace(mu=0.2), theta_deg=45.0).e_n
    ints = rs.sweep(disc_scene, theta_deg=np.arange(40, 43))
    assert ints["theta_deg"].to_list() == [40.0, 41.0, 42.0]


def test_parquet_round_trip(product_frame: pl.DataFrame, tmp_path: Path) -> None:
    path = tmp_path / "sweep.parquet"
    product_frame.write_parquet(path)
    back = pl.read_parquet(path)
    assert_frame_equal(back, product_frame, check_exact=True)
    assert back["e_t"].null_count() == product_frame["e_t"].null_count() > 0
