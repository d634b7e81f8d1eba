"""Two bodies from Python (docs/model.md, section 17): ``Scene(partner=...)``, the partner's spin
in ``simulate`` and as a sweep axis, the partner's fields as axes, the pair's record, refusals.

The physics (identical pair = plate, the identity of the two normal restitutions, momentum,
symmetries) is checked in the kernel (``rust/core/tests/pairs.rs``); here, that the API reaches it.
"""

from __future__ import annotations

import math

import numpy as np
import polars as pl
import pytest

import restitution as rs

# Gear-5 at its default step: the identities below hold to round-off on the fixed-step path
# (the pair's and the plate's loops take the same steps); the adaptive path is checked to its
# tolerance where it differs.
PAIR = rs.Scene(partner=rs.Disc(r=0.01), integrator="gear5")


def test_identical_discs_head_on_are_one_disc_on_the_plate() -> None:
    plate = rs.simulate(rs.Scene(integrator="gear5"), 90.0)
    pair = rs.simulate(PAIR.replace(v=2 * PAIR.v), 90.0)
    assert pair.e_n == pytest.approx(plate.e_n, rel=1e-12)
    assert pair.contact_time == pytest.approx(plate.contact_time, rel=1e-12)
    assert pair.max_depth == pytest.approx(2 * plate.max_depth, rel=1e-12)


def test_identical_discs_on_the_default_adaptive_path_agree_with_the_plate_to_its_tolerance() -> None:
    # Scene()'s adaptive path integrates the pair and the plate in separate loops: each record
    # is within 3 tol of the truth (docs/model.md, 7.3), so the two within 6 tol of each other.
    plate = rs.simulate(rs.Scene(), 90.0)
    pair = rs.simulate(rs.Scene(partner=rs.Disc(r=0.01), v=2 * PAIR.v), 90.0)
    assert abs(pair.e_n - plate.e_n) <= 6 * rs.Scene().tol
    assert abs(pair.e_n - plate.e_n) <= pair.err_est + plate.err_est


def test_the_plate_record_has_no_partner() -> None:
    rec = rs.simulate(rs.Scene(), 30.0)
    assert rec.partner_omega_in == 0.0 and rec.partner_omega_out == 0.0
    assert rec.e_n_sep == rec.e_n and rec.normal_rotation_deg == 0.0
    assert rec.momentum_residual is None and rec.angular_momentum_residual is None


def test_elastic_frictionless_pair_turns_e_n_negative_at_grazing_incidence() -> None:
    scene = PAIR.replace(mu=0.0, gamma=0.0, v=1.0)
    df = rs.sweep(scene, theta_deg=[0.5, 1.0, 2.0, 30.0])
    assert (df["e_n_sep"] - 1.0).abs().max() < 1e-6
    # From the identity e_n = cos(dpsi) + cot(theta) sin(dpsi) (elastic): e_n < 0 iff |dpsi| > theta.
    turned = df["normal_rotation_deg"].abs().to_numpy()
    np.testing.assert_array_equal(df["e_n"].to_numpy() < 0, turned > df["theta_deg"].to_numpy())
    assert (df["e_n"] < 0).sum() >= 2


def test_partner_spin_and_fields_are_sweep_axes() -> None:
    df = rs.sweep(PAIR.replace(mu=0.5), theta_deg=[30.0], partner_omega_in=[-2.0, 0.0, 2.0],
                  partner_rho=[2500.0, 7800.0])
    assert df.height == 6 and {"partner_omega_in", "partner_rho"} <= set(df.columns)
    for row in df.iter_rows(named=True):
        rec = rs.simulate(PAIR.replace(mu=0.5, partner_rho=row["partner_rho"]), 30.0,
                          partner_omega_in=row["partner_omega_in"])
        assert rec.partner_omega_out == row["partner_omega_out"] and rec.e_n == row["e_n"]
        assert rec.momentum_residual < 1e-12 and abs(rec.angular_momentum_residual) < 1e-12


def test_swapping_particle_and_partner_swaps_the_spins() -> None:
    a = rs.Scene(shape=rs.Disc(0.006), partner=rs.Disc(0.012), partner_rho=4000.0, mu=0.4)
    b = rs.Scene(shape=rs.Disc(0.012), rho=4000.0, partner=rs.Disc(0.006), partner_rho=2500.0, mu=0.4)
    ra = rs.simulate(a, 40.0, omega_in=1.0, partner_omega_in=-3.0)
    rb = rs.simulate(b, 40.0, omega_in=-3.0, partner_omega_in=1.0)
    assert rb.e_n == pytest.approx(ra.e_n, rel=1e-9) and rb.e_kin == pytest.approx(ra.e_kin, rel=1e-9)
    assert rb.omega_out == pytest.approx(ra.partner_omega_out, rel=1e-9)
    assert rb.partner_omega_out == pytest.approx(ra.omega_out, rel=1e-9)


def test_sphere_pairs_run_the_hertz_law() -> None:
    glass = rs.Scene(shape=rs.Sphere(0.01), normal_law="hertz", E=4.8e10, rho=2800.0, nu=0.2, cor=1.0, mu=0.0, v=10.0,
                     integrator="gear5")
    plate = rs.simulate(glass, 90.0)
    pair = rs.simulate(glass.replace(partner=rs.Sphere(0.01), v=20.0), 90.0)
    assert pair.e_n == pytest.approx(plate.e_n, rel=1e-12)
    assert pair.contact_time == pytest.approx(plate.contact_time, rel=1e-12)


@pytest.mark.parametrize(("changes", "name"), [
    ({"partner": rs.Sphere(0.01)}, "partner"),
    ({"partner": rs.RegularPolygon(0.01, 6), "normal_law": "linear", "integrator": "verlet"}, "integrator"),
    ({"partner": rs.Disc(0.01), "partner_rho": -1.0}, "partner_rho"),
    ({"partner_rho": 3000.0}, "partner_rho"),
])
def test_what_a_pair_cannot_be_is_refused_naming_the_parameter(changes: dict, name: str) -> None:
    with pytest.raises(rs.RestitutionError) as info:
        rs.Scene(**changes)
    assert info.value.parameter == name


def test_partner_must_be_a_shape() -> None:
    with pytest.raises(TypeError, match="partner"):
        rs.Scene(partner=0.01)  # type: ignore[arg-type]
    with pytest.raises(rs.RestitutionError) as info:
        rs.simulate(PAIR, 30.0, partner_omega_in=math.inf)
    assert info.value.parameter == "partner_omega_in"


def test_chung_ooi_test1_is_hertz_for_the_pair() -> None:
    from restitution.study import validate_pairs

    table, _ = validate_pairs.test1()
    assert table["deviation"].abs().max() < 1e-4, table


def test_chung_ooi_test7_opposite_spins_without_slip_change_nothing_tangential() -> None:
    from restitution.study import validate_pairs

    t7 = validate_pairs.test7()
    assert t7["spin_change"].abs().max() < 1e-12 and t7["partner_spin_change"].abs().max() < 1e-12
    assert t7["tangential_after"].abs().max() < 1e-12
    assert (t7["e_n"] - 0.5).abs().max() < 1e-3  # cor 0.5 head-on


def test_chung_ooi_test8_sliding_branch_is_rigid_body_theory() -> None:
    from restitution.study import validate_pairs

    t8 = validate_pairs.test8()
    sliding = t8.filter(t8["sliding"])
    assert sliding.height >= 8
    # The compliant contact sticks for an instant at touch (Maw et al.): a few thousandths.
    assert (sliding["recoil"] - sliding["recoil_theory"]).abs().max() < 1e-2
    # Far below the sliding threshold the rigid contact stops slipping; the compliant one recoils
    # a little (micro-slip), never by more than a small fraction of the incident slip.
    slow = t8.filter(t8["psi"] < 0.5)
    assert (slow["recoil"].abs() < 0.05).all()


def test_negative_e_n_map_obeys_the_exact_criterion_and_reports_the_estimate(tmp_path, capsys) -> None:
    """The map's frictionless cases: e_n < 0 exactly where tan|dpsi| > e_n_sep tan(theta) (the
    identity of docs/model.md 17.4); every case turns negative at grazing incidence, friction
    lowers the threshold (Müller, Krengel & Pöschel: less pronounced with friction), and the CLI
    writes the table, figure and report."""
    import polars as pl

    from restitution import cli
    from restitution.study import pair_map

    df = pair_map.negative_e_n_map(np.geomspace(0.1, 30.0, 25))
    smooth = df.filter(pl.col("case").str.ends_with("mu 0"))
    lhs = np.tan(np.radians(smooth["normal_rotation_deg"].abs().to_numpy()))
    rhs = smooth["e_n_sep"].to_numpy() * np.tan(np.radians(smooth["theta_deg"].to_numpy()))
    clear = np.abs(lhs - rhs) > 1e-9 * rhs
    np.testing.assert_array_equal((smooth["e_n"].to_numpy() < 0)[clear], (lhs > rhs)[clear])
    cross = pair_map.crossings(df)
    assert cross["theta_star_deg"].is_not_nan().all() and (cross["min_e_n"] < -0.9).all()
    for law in ("area elastic", "area damped", "linear elastic", "linear damped"):
        t = dict(zip(cross["case"], cross["theta_star_deg"]))
        assert t[f"{law} mu 0.5"] < t[f"{law} mu 0"], law
    capsys.readouterr()
    assert cli.main(["pairs", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out.splitlines()  # a short summary; the tables are in report.md
    assert len(printed) <= 4 and "report.md" in printed[0] and "theta*" in printed[1], printed
    assert (tmp_path / "negative_e_n.png").stat().st_size > 20_000
    assert "criterion" in (tmp_path / "report.md").read_text()


def test_polygon_pairs_run_and_swap() -> None:
    """A hexagon on a pentagon and a disc on a square (docs/model.md 17.8): finite records that
    end separated, momentum kept, and the picture turned by 180 degrees with the bodies
    swapped is the same impact with the spins exchanged."""
    cases = [(rs.RegularPolygon(0.01, 6, 10.0), rs.RegularPolygon(0.012, 5, 40.0)),
             (rs.Disc(0.01), rs.RegularPolygon(0.01, 4, 30.0))]
    for shape, partner in cases:
        a = rs.Scene(shape=shape, partner=partner, mu=0.4, gamma=0.2, tol=1e-9)
        ra = rs.simulate(a, 35.0, omega_in=2.0, partner_omega_in=-1.0)
        assert ra.separated and not ra.timed_out
        assert ra.momentum_residual < 1e-12 and abs(ra.angular_momentum_residual) < 1e-12
        turned = lambda s: s if isinstance(s, rs.Disc) else rs.RegularPolygon(s.r, s.n, s.phi0_deg + 180.0)  # noqa: E731
        b = rs.Scene(shape=turned(partner), partner=turned(shape), mu=0.4, gamma=0.2, tol=1e-9)
        rb = rs.simulate(b, 35.0, omega_in=-1.0, partner_omega_in=2.0)
        assert rb.e_n == pytest.approx(ra.e_n, abs=1e-6) and rb.e_kin == pytest.approx(ra.e_kin, abs=1e-6)
        assert rb.omega_out == pytest.approx(ra.partner_omega_out, abs=1e-4)
        assert rb.partner_omega_out == pytest.approx(ra.omega_out, abs=1e-4)


def test_polygon_map_gives_a_distribution_of_e_n_per_angle(tmp_path) -> None:
    """Two polygons at random orientations (docs/model.md 17.7): finite records; at grazing
    incidence the line of centres turns past the impact angle in a good share of the draws
    (e_n < 0, as for two discs below their theta*), at 45 degrees in fewer (a corner grazing
    a corner can still send the bodies past each other), and the median e_n is positive."""
    from restitution.study import polygon_pair_map as pm

    paths, text = pm.write_polygon_map(tmp_path, angles=np.array([0.5, 45.0]), draws=12)
    df = pl.read_parquet(paths[0])
    assert df.height == len(pm.cases()) * 2 * 12 and df["e_n"].is_finite().all()
    stats = pl.read_parquet(paths[1])
    grazing, steep = stats.filter(pl.col("theta_deg") < 1.0), stats.filter(pl.col("theta_deg") > 40.0)
    assert (grazing["p_negative"] >= 0.25).all()
    assert (steep["p_negative"].to_numpy() < grazing["p_negative"].to_numpy()).all()
    assert (steep["e_n_median"] > 0.0).all()
    assert "theta_half" in text and paths[2].stat().st_size > 20_000


def test_polygon_pairs_sweep_and_draw_their_orientations() -> None:
    """The partner's corners and orientation are axes of a sweep and draws of an ensemble:
    every case runs, and turning the partner by a full 360/n changes nothing."""
    s = rs.Scene(shape=rs.RegularPolygon(0.01, 6), partner=rs.RegularPolygon(0.01, 6), integrator="gear5")
    df = rs.sweep(s, theta_deg=[30.0], partner_phi0_deg=[10.0, 70.0], partner_n=[5, 6], progress=False)
    assert df.height == 4 and df["e_n"].is_finite().all()
    six = df.filter(pl.col("partner_n") == 6).sort("partner_phi0_deg")["e_n"]
    assert six[0] == pytest.approx(six[1], abs=1e-9)
    e = rs.ensemble(s, 16, vary={"partner_phi0_deg": rs.Uniform(0.0, 360.0)}, seed=3, theta_deg=[20.0], progress=False)
    assert e.samples["partner_phi0_deg"].n_unique() == 16 and e.samples["e_n"].is_finite().all()


def test_convex_polygon_partners_are_their_vertices() -> None:
    """A ConvexPolygon partner carries its own vertices to the engine: given a hexagon's, it is
    the RegularPolygon hexagon (the same record to round-off), and any convex partner runs with
    momentum kept; its vertex count is not a sweep axis."""
    hexagon = rs.RegularPolygon(0.01, 6, 20.0)
    corners = [(0.01 * math.cos(math.radians(60 * k)), 0.01 * math.sin(math.radians(60 * k))) for k in range(6)]
    convex = rs.ConvexPolygon(tuple(corners), phi0_deg=20.0)
    base = rs.Scene(shape=rs.RegularPolygon(0.01, 5, 10.0), mu=0.4, gamma=0.2)
    a = rs.simulate(base.replace(partner=hexagon), 35.0, omega_in=2.0)
    b = rs.simulate(base.replace(partner=convex), 35.0, omega_in=2.0)
    for name in ("e_n", "e_t", "e_kin", "omega_out", "partner_omega_out", "contact_time"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-9, abs=1e-12), name
    tri = rs.ConvexPolygon(((0.01, 0.0), (-0.004, 0.009), (-0.006, -0.007)))
    r = rs.simulate(rs.Scene(shape=tri, partner=tri, mu=0.3), 40.0, omega_in=1.0)
    assert r.separated and r.momentum_residual < 1e-12 and abs(r.angular_momentum_residual) < 1e-12
    with pytest.raises(ValueError, match="partner_n"):
        rs.sweep(base.replace(partner=convex), theta_deg=[30.0], partner_n=[5, 6], progress=False)


def test_convex_partner_round_trips_through_a_config_and_the_digest_sees_it() -> None:
    """A ConvexPolygon partner is a [scene.partner] table that reads back to the same scene,
    and the dataset digest tells it from the RegularPolygon with the same corners."""
    from restitution.runs.config import spec_from_dict, spec_to_dict
    from restitution.runs.dataset import make_manifest
    from restitution.runs.sweep import SweepSpec

    corners = tuple((0.01 * math.cos(math.radians(60 * k)), 0.01 * math.sin(math.radians(60 * k))) for k in range(6))
    convex = rs.Scene(partner=rs.ConvexPolygon(corners, phi0_deg=5.0), integrator="gear5")
    spec = SweepSpec(convex, axes={"theta_deg": [30.0, 60.0]})
    back, _ = spec_from_dict(spec_to_dict(spec))
    assert back.scene == convex
    regular = SweepSpec(convex.replace(partner=rs.RegularPolygon(0.01, 6, 5.0)), axes={"theta_deg": [30.0, 60.0]})
    assert make_manifest(spec, 1)["spec_sha256"] != make_manifest(regular, 1)["spec_sha256"]
