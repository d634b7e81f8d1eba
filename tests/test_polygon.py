"""Polygon particles through the Python API: validation of ConvexPolygon, the n and phi0_deg
sweep axes, the overlap paths, energy conservation, re-contacts, and the n-gon -> disc limit."""

from __future__ import annotations

import math

import numpy as np
import pytest

import restitution as rs

R = 0.01


def regular_vertices(n: int, phi0_deg: float = 0.0, r: float = R) -> list[tuple[float, float]]:
    a = np.deg2rad(phi0_deg) + 2 * np.pi * np.arange(n) / n
    return [(float(r * math.cos(t)), float(r * math.sin(t))) for t in a]


# --- ConvexPolygon validation: every failure names `vertices` ------------------------------

@pytest.mark.parametrize(("vertices", "fragment"), [
    ([(0, 0), (0.01, 0.01), (0.02, 0), (0.01, 0.03)], "convex"),           # non-convex (dent)
    ([(0, 0), (0, 0.02), (0.02, 0.02), (0.02, 0)], "counter-clockwise"),   # clockwise
    ([(0, 0), (0.01, 0), (0.02, 0)], "counter-clockwise"),                 # degenerate: no area
    ([(0, 0), (0.01, 0), (0.02, 0), (0.02, 0.02)], "collinear"),           # degenerate corner
    ([(0, 0), (0.02, 0), (0.02, 0), (0, 0.02)], "distinct"),               # duplicated vertex
    ([(0, 0), (0.02, math.nan), (0, 0.02)], "finite"),                     # non-finite
    ([(0, 0), (0.02, 0), (0, math.inf)], "finite"),
])
def test_convex_polygon_refuses_bad_vertices(vertices, fragment: str) -> None:
    with pytest.raises(ValueError, match="`vertices`") as err:
        rs.ConvexPolygon(vertices)
    assert fragment in str(err.value)


def test_convex_polygon_equals_the_regular_polygon_it_describes() -> None:
    # The same square given by its vertices or as RegularPolygon(n=4): same mass, inertia and
    # hence the same impact, to round-off (the vertices differ only by their rounding).
    phi0 = 20.0
    scene_reg = rs.Scene(shape=rs.RegularPolygon(r=R, n=4, phi0_deg=phi0))
    scene_cvx = rs.Scene(shape=rs.ConvexPolygon(regular_vertices(4), phi0_deg=phi0))
    assert scene_cvx.shape.r == pytest.approx(R, rel=1e-14)
    a = rs.simulate(scene_reg, 35.0, omega_in=2.0)
    b = rs.simulate(scene_cvx, 35.0, omega_in=2.0)
    for name in ("e_n", "e_t", "e_kin", "omega_out", "energy_out"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-9, abs=1e-12), name


# --- the overlap paths -----------------------------------------------------------------------

def test_overlap_is_a_validated_scene_field() -> None:
    assert rs.Scene().overlap == "auto"
    with pytest.raises(ValueError, match="`overlap`"):
        rs.Scene(overlap="exact")
    with pytest.raises(ValueError, match="`overlap`.*Disc"):
        rs.Scene(shape=rs.Disc(r=R), overlap="parry")
    assert rs.Scene.paper(overlap="parry").overlap == "parry"


def test_verlet_is_refused_for_the_linear_law_on_a_polygon_naming_integrator() -> None:
    # Each corner's dashpot force jumps as the corner crosses the plate; only Gear-5 and the
    # adaptive path locate the jumps (docs/consistency.md).
    square = rs.RegularPolygon(r=R, n=4, phi0_deg=45.0)
    with pytest.raises(ValueError, match="`integrator`.*gear5.*adaptive") as err:
        rs.Scene(shape=square, normal_law="linear", kn=1e5, integrator="verlet")
    assert err.value.parameter == "integrator"
    for integrator in ("gear5", "adaptive"):
        scene = rs.Scene(shape=square, normal_law="linear", kn=1e5, integrator=integrator)
        assert math.isfinite(rs.simulate(scene, 40.0).e_n)
    # Verlet keeps the linear law on the disc and the area law on polygons.
    rs.Scene(shape=rs.Disc(r=R), normal_law="linear", kn=1e5, integrator="verlet")
    rs.Scene(shape=square, integrator="verlet")


@pytest.mark.parametrize("shape", [
    rs.RegularPolygon(r=R, n=120, phi0_deg=0.0),
    rs.RegularPolygon(r=R, n=4, phi0_deg=45.0),     # face first: an edge parallel to the plate
    rs.RegularPolygon(r=R, n=3, phi0_deg=30.0),     # corner first
    rs.ConvexPolygon([(0, 0), (0.02, 0.002), (0.015, 0.012), (0.003, 0.01)], phi0_deg=7.0),
])
def test_half_plane_and_parry_paths_give_the_same_impact(shape) -> None:
    # The two paths agree to round-off at every step, so the records agree closely.
    base = rs.Scene(shape=shape, mu=0.5)
    a = rs.simulate(base.replace(overlap="halfplane"), 40.0, omega_in=1.0)
    b = rs.simulate(base.replace(overlap="parry"), 40.0, omega_in=1.0)
    for name in ("e_n", "e_t", "e_kin", "max_area"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-9), name
    assert b.omega_out == pytest.approx(a.omega_out, rel=1e-9, abs=1e-9)
    assert a.contacts == b.contacts and abs(a.steps - b.steps) <= 1


# --- sweep axes: n and phi0_deg --------------------------------------------------------------

def test_n_axis_approaches_the_exact_disc() -> None:
    # n = 0 is the exact disc; the regular n-gon's e_n tends to it as n grows.
    frame = rs.sweep(rs.Scene.paper(), theta_deg=[20.0, 60.0], n=[0, 30, 120, 480, 1920])
    assert frame.height == 10
    disc = frame.filter(frame["n"] == 0).sort("theta_deg")["e_n"].to_numpy()
    errors = []
    for n in (30, 120, 480, 1920):
        e_n = frame.filter(frame["n"] == n).sort("theta_deg")["e_n"].to_numpy()
        errors.append(float(np.max(np.abs(e_n - disc))))
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert errors[-1] < 1e-5, errors


def test_phi0_axis_is_periodic_with_the_polygon() -> None:
    # Rotating a regular n-gon by 360 / n degrees places the same polygon.
    for n in (3, 4, 7):
        phis = [11.0, 11.0 + 360.0 / n, 11.0 - 2 * 360.0 / n]
        frame = rs.sweep(rs.Scene(shape=rs.RegularPolygon(r=R, n=n)), theta_deg=[30.0], phi0_deg=phis,
                         omega_in=[3.0])
        assert frame["phi0_deg"].to_list() == phis
        for name in ("e_n", "e_t", "e_kin", "omega_out"):
            col = frame[name].to_numpy()
            assert np.ptp(col) < 1e-10 * max(1.0, float(np.max(np.abs(col)))), (n, name, col)
    # ...while a generic rotation does change the impact of a square.
    frame = rs.sweep(rs.Scene(shape=rs.RegularPolygon(r=R, n=4)), theta_deg=[30.0], phi0_deg=[0.0, 20.0])
    assert abs(frame["e_n"][0] - frame["e_n"][1]) > 1e-3


# --- energy -------------------------------------------------------------------------------------

@pytest.mark.parametrize("shape", [
    rs.RegularPolygon(r=R, n=3, phi0_deg=30.0),     # triangle, corner first
    rs.RegularPolygon(r=R, n=4, phi0_deg=0.0),      # square, corner first
    rs.RegularPolygon(r=R, n=5, phi0_deg=17.0),
    rs.ConvexPolygon([(0, 0), (0.02, 0.002), (0.015, 0.012), (0.003, 0.01)], phi0_deg=123.0),
])
def test_frictionless_undamped_polygons_conserve_energy(shape) -> None:
    # mu = 0, gamma = 0: the area law is conservative (torque included), no tangential force.
    # Rotation couples in, so e_n and omega change while the kinetic energy is kept.
    scene = rs.Scene(shape=shape, mu=0.0, gamma=0.0)
    frame = rs.sweep(scene, theta_deg=[15.0, 45.0, 75.0, 90.0], omega_in=[-5.0, 0.0, 5.0])
    change = (frame["energy_out"] / frame["energy_in"] - 1.0).abs().max()
    assert change < 1e-6
    assert (frame["work_friction"] == 0.0).all()
    assert frame["separated"].all() and not frame["timed_out"].any()


def test_energy_audit_for_squares_and_triangles() -> None:
    # The paper preset's damping and friction: the balance closes, no energy is gained.
    for n, phis in ((4, (0.0, 45.0)), (3, (30.0, 90.0))):
        frame = rs.sweep(rs.Scene(shape=rs.RegularPolygon(r=R, n=n)), theta_deg=[10.0, 45.0, 90.0],
                         phi0_deg=list(phis), omega_in=[-10.0, 0.0, 10.0], mu=[0.0, 0.5])
        assert frame["energy_residual"].abs().max() < 1e-6
        assert (frame["energy_out"] <= frame["energy_in"] * (1 + 1e-6)).all()
        assert frame["separated"].all()


def test_spinning_square_hits_again_and_contacts_are_counted() -> None:
    # Corner first at a shallow angle with spin: a second corner reaches the plate.
    rec = rs.simulate(rs.Scene(shape=rs.RegularPolygon(r=R, n=4, phi0_deg=0.0)), 10.0, omega_in=-20.0,
                      trace=True)
    assert rec.contacts >= 2 and rec.separated and not rec.timed_out
    depth = rec.trace["depth"].to_numpy()
    inside = depth > 0
    inside[0] = True  # the trace starts at first touch (zero depth): the first contact
    entries = int(np.sum(inside[1:] & ~inside[:-1]))
    assert rec.contacts == 1 + entries
    assert abs(rec.energy_residual) < 1e-6
