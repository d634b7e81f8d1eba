"""The adaptive integrator at a requested tolerance, and the records' own error estimate."""

import math

import numpy as np
import pytest

import restitution as rs


def test_adaptive_meets_its_tolerance_against_a_tight_run():
    tight = rs.simulate(rs.Scene(integrator="adaptive", tol=1e-12, dt_factor=0.2), theta_deg=30.0)
    for tol in (1e-4, 1e-6, 1e-8):
        rec = rs.simulate(rs.Scene(integrator="adaptive", tol=tol, dt_factor=1.0), theta_deg=30.0)
        err = max(abs(rec.e_n - tight.e_n), abs(rec.e_t - tight.e_t), abs(rec.e_kin - tight.e_kin))
        assert err <= 3 * tol
        assert rec.err_est is not None and rec.err_est >= err


def test_err_est_is_null_unless_asked_for_fixed_steps():
    assert rs.simulate(rs.Scene(integrator="gear5"), theta_deg=30.0).err_est is None
    assert rs.simulate(rs.Scene(integrator="adaptive"), theta_deg=30.0).err_est is not None
    rec = rs.simulate(rs.Scene(error_estimate=True), theta_deg=30.0)
    ref = rs.simulate(rs.Scene(integrator="reference", dt_factor=0.2), theta_deg=30.0)
    assert rec.err_est is not None and rec.err_est >= abs(rec.e_t - ref.e_t)


def test_tol_is_a_sweep_axis_and_checked():
    df = rs.sweep(rs.Scene(integrator="adaptive", dt_factor=1.0), theta_deg=np.array([20.0, 60.0]),
                  tol=np.array([1e-4, 1e-8]))
    assert df.height == 4 and df["err_est"].null_count() == 0
    with pytest.raises(rs.RestitutionError) as err:
        rs.Scene(integrator="adaptive", tol=0.5)
    assert err.value.parameter == "tol"
    with pytest.raises(TypeError):
        rs.Scene(error_estimate="yes")
    assert math.isfinite(rs.Scene(integrator="adaptive").max_dt_factor)
