"""Reduced models: fitted to a table made by themselves they give back their parameters; fitted to
the engine's disc, Walton's friction is the contact law's and it costs far less than constant
coefficients on the tangential outputs; the reported errors are the models' distance from the table."""

from __future__ import annotations

import numpy as np
import polars as pl
import pytest

import restitution as rs
from restitution.collision import CollisionOperator, fit_constant, fit_walton
from restitution.collision.reduced import FIT_POINTS, ReducedModel, kappa_of
from restitution.collision.table import OUTPUTS, Table


def synthetic(model: ReducedModel, scene: rs.Scene) -> CollisionOperator:
    """An operator whose table is ``model`` itself, on the fitting grid's points (one speed)."""
    theta = np.linspace(5.0, 90.0, FIT_POINTS[0])
    spin = np.linspace(-0.6, 0.6, FIT_POINTS[1])
    th, sp = np.meshgrid(theta, spin, indexing="ij")
    rad = np.radians(th)
    vn, vt = -np.sin(rad), np.where(th == 90.0, 0.0, np.cos(rad))
    unit = ReducedModel(model.name, model.params, model.errors, model.kappa, 1.0, model.error)
    out = unit(vn, vt, sp)
    values = np.stack(out, axis=-1)[:, :, None, None, :]
    table = Table(theta, spin, np.array([scene.v]), values, scene.r)
    error = pl.DataFrame({"output": list(OUTPUTS), "max_abs": [0.0] * 3})
    return CollisionOperator(table, scene=scene, vary={}, seed=0, tol=1.0, error=error,
                             rough=np.zeros((len(theta) - 1, len(spin) - 1, 1), dtype=bool), info={})


@pytest.mark.parametrize("params", [{"e": 0.8, "mu": 0.25, "beta_0": 0.35}, {"e": 0.95, "mu": 0.6, "beta_0": -0.2}])
def test_walton_fitted_to_itself_gives_its_parameters_back(params: dict[str, float]) -> None:
    scene = rs.Scene()
    truth = ReducedModel("walton", params, {}, kappa_of(scene), scene.r, pl.DataFrame())
    fit = fit_walton(synthetic(truth, scene))
    for k, v in params.items():
        assert fit.params[k] == pytest.approx(v, abs=1e-6), (k, fit.params)
    assert fit.error["max_abs"].max() < 1e-6


def test_constant_fitted_to_itself_gives_its_parameters_back() -> None:
    scene = rs.Scene.paper()
    truth = ReducedModel("constant", {"e_n": 0.85, "e_t": 0.7}, {}, kappa_of(scene), scene.r, pl.DataFrame())
    fit = fit_constant(synthetic(truth, scene))
    assert fit.params == pytest.approx({"e_n": 0.85, "e_t": 0.7}, abs=1e-12)
    assert fit.error["max_abs"].max() < 1e-12


def test_kappa_of_the_shapes() -> None:
    assert kappa_of(rs.Scene()) == 0.5 and kappa_of(rs.Scene(inertia="sphere")) == 0.4
    square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]  # I = m a^2 / 6, a = 2, r^2 = 2
    assert kappa_of(rs.Scene(shape=rs.ConvexPolygon(square))) == pytest.approx(1.0 / 3.0, rel=1e-12)
    assert kappa_of(rs.Scene(shape=rs.RegularPolygon(0.01, 4, 45.0))) == pytest.approx(1.0 / 3.0, rel=1e-12)


@pytest.fixture(scope="module")
def disc_op() -> CollisionOperator:
    scene = rs.Scene(mu=0.3, integrator="adaptive", tol=1e-9)
    return CollisionOperator.build(scene, theta_deg=np.linspace(5, 90, 18), omega_in=np.linspace(-2, 2, 5),
                                   tol=2e-3, seed=1)


def test_walton_on_the_engines_disc_has_the_contact_laws_friction(disc_op: CollisionOperator) -> None:
    # The disc slides by Coulomb's law (docs/model.md, 11.3), so Walton's mu is the scene's, up to
    # the spread of e_N over the table, which Walton's sliding impulse mu (1 + e) takes as constant.
    walton, const = disc_op.fit_walton(), disc_op.fit_constant()
    theta = disc_op.table.theta_deg[:, None, None]
    e_n = disc_op.table.mean[..., 0] / np.sin(np.radians(theta))
    assert e_n.min() <= walton.params["e"] <= e_n.max()
    bound = 0.3 * (e_n.max() - e_n.min()) / (1.0 + e_n.min())
    assert abs(walton.params["mu"] - 0.3) <= bound, (walton.params, bound)
    assert all(v is not None and v > 0 for v in walton.errors.values())
    w, c = (m.error.filter(pl.col("output") != "vn_ratio") for m in (walton, const))
    assert (w["rms"] < 0.2 * c["rms"]).all(), (w, c)
    assert walton.error["operator_max_abs"].to_list() == disc_op.error["max_abs"].to_list()
    assert "mu = 0.3" in walton.summary()


def test_reduced_models_act_in_si_like_the_operator(disc_op: CollisionOperator) -> None:
    walton = disc_op.fit_walton()
    vn, vt, om = np.array([-0.02, -0.03]), np.array([0.02, -0.01]), np.array([0.3, -1.0])
    out = walton(vn, vt, om)
    mirrored = walton(vn, -vt, -om)
    assert np.allclose(out[0], -walton.params["e"] * vn)
    assert np.allclose(out[1], -mirrored[1]) and np.allclose(out[2], -mirrored[2])
    # the contact point's impulse: v_t' - v_t = kappa r (omega' - omega)
    assert np.allclose(out[1] - vt, walton.kappa * walton.r * (out[2] - om))
