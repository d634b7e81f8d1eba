"""Inputs at the edge of what the engine can do end in a clear ValueError, never a hang."""

import math

import pytest

import restitution as rs


@pytest.mark.parametrize("threads", [0, -1, 10**6])
def test_thread_counts_outside_the_allowed_range_are_refused(threads):
    with pytest.raises(ValueError, match=r"require `threads` an integer in \[1, 4096\]"):
        rs.sweep(rs.Scene(), theta_deg=[30.0], threads=threads)


@pytest.mark.parametrize("theta", [1e-8, 1e-12, 1e-20])
def test_grazing_angles_below_depth_resolution_are_refused_naming_v_and_theta(theta):
    with pytest.raises(ValueError, match=r"require `v` .*raise theta_deg or v"):
        rs.simulate(rs.Scene(), theta_deg=theta)


def test_a_modulus_too_stiff_to_resolve_the_overlap_is_refused():
    with pytest.raises(ValueError, match=r"lower E"):
        rs.simulate(rs.Scene(E=1e30), theta_deg=45.0)


def test_the_finest_resolved_grazing_angle_gives_a_finite_record():
    rec = rs.simulate(rs.Scene(), theta_deg=1e-7)
    assert rec.separated and not rec.timed_out
    assert all(math.isfinite(x) for x in (rec.e_n, rec.e_kin, rec.omega_out, rec.contact_time))
    assert 0.99 < rec.e_n < 1.0
