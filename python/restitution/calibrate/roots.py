"""Calibration: model parameters from measured restitution coefficients.

- :func:`gamma_for_e_n`: the normal damping gamma that gives a target e_N (head-on by default) at
  the scene's speed, by root finding on :func:`restitution.simulate`.
- :func:`mu_for_e_t`: the friction coefficient that gives a measured e_T at an angle where the
  impact slides throughout (there e_T = 1 - mu (1 + e_N) tan theta, so e_T fixes mu; in the
  rolling regime e_T does not depend on mu and no calibration is possible).

The paper preset's gamma = 0.33 is this calibration rounded to two digits:
``gamma_for_e_n(Scene.paper(), 0.90)`` gives gamma = 0.33249 on the study's 120-gon and 0.33299 on
an exact disc (dt_factor 0.01; 0.33298 at dt_factor 0.003). With gamma = 0.33 the head-on e_N is
0.9008 on the disc. See ``tests/test_calibrate.py`` and the report of ``restitution reproduce``.

Examples
--------
>>> import restitution as rs
>>> from restitution import calibrate
>>> cal = calibrate.gamma_for_e_n(rs.Scene(), 0.90)
>>> round(cal.value, 3), abs(cal.achieved - 0.90) < 1e-6
(0.333, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..study import theory
from .._core import check_theta
from .._engine import real
from ..scene import Scene
from ..simulate import simulate


@dataclass(frozen=True)
class Calibration:
    """A calibrated parameter: ``name`` = ``value``; ``achieved`` is the simulated coefficient at
    that value (``target`` was asked for); ``evaluations`` counts impacts simulated."""

    name: str
    value: float
    target: float
    achieved: float
    evaluations: int
    scene: Scene


def _bisect_secant(f: Callable[[float], float], lo: float, hi: float, flo: float, fhi: float, ftol: float,
                   xtol: float, max_iter: int = 200) -> tuple[float, float, int]:
    """Root of f in [lo, hi] with f(lo), f(hi) of opposite signs: Illinois-style regula falsi
    (superlinear on smooth f), always kept inside the bracket; stops at |f| <= ftol or a
    bracket narrower than xtol. Returns (x, f(x), evaluations)."""
    evals = 0
    side = 0
    x, fx = (lo, flo) if abs(flo) < abs(fhi) else (hi, fhi)
    for _ in range(max_iter):
        if abs(fx) <= ftol or hi - lo <= xtol:
            break
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        fx = f(x)
        evals += 1
        if (fx > 0) == (fhi > 0):
            hi, fhi = x, fx
            if side == 1:
                flo /= 2.0  # Illinois: halve the stale end so the bracket shrinks from both sides
            side = 1
        else:
            lo, flo = x, fx
            if side == -1:
                fhi /= 2.0
            side = -1
    return x, fx, evals


def gamma_for_e_n(scene: Scene, e_n: float, *, theta_deg: float = 90.0, tol: float = 1e-6,
                  gamma_max: float = 50.0) -> Calibration:
    """The normal damping gamma for which ``simulate(scene, theta_deg).e_n == e_n`` within ``tol``.

    e_N falls monotonically from 1 (gamma = 0, no dissipation) as gamma grows; the root is
    bracketed in [0, gamma_max] and found by safeguarded regula falsi. Every other scene field
    (shape, v, E, mu, ...) is kept: e_N depends on v for this contact law, so calibrate at the
    speed you simulate.

    Raises ``ValueError`` when ``e_n`` is not in (0, 1) or is not reached for gamma <= gamma_max.
    """
    if not (0.0 < float(e_n) < 1.0):
        raise ValueError(f"require `e_n` in (0, 1) (found {e_n})")
    if not (0.0 < tol < 1e-2):
        raise ValueError(f"require `tol` in (0, 0.01) (found {tol})")
    th = real("theta_deg", theta_deg)
    check_theta(th)
    if scene.normal_law != "area":
        raise ValueError('gamma is used by the area law only (scene has `normal_law` "linear"; calibrate `cn`)')
    target = float(e_n)

    def f(g: float) -> float:
        return simulate(scene.replace(gamma=g), th).e_n - target

    lo, flo = 0.0, f(0.0)
    hi = 0.5
    fhi = f(hi)
    evals = 2
    while fhi > 0.0:  # e_N still above target: more damping
        lo, flo = hi, fhi
        hi *= 2.0
        if hi > gamma_max:
            raise ValueError(f"`e_n` = {target} is not reached with `gamma` <= {gamma_max} at v = {scene.v} m/s")
        fhi = f(hi)
        evals += 1
    if flo < 0.0:
        raise ValueError(f"`e_n` = {target} is above the undamped value {flo + target:.6f}")
    g, fg, k = _bisect_secant(f, lo, hi, flo, fhi, ftol=tol, xtol=1e-12)
    return Calibration("gamma", g, target, fg + target, evals + k, scene.replace(gamma=g))


def mu_for_e_t(scene: Scene, e_t: float, theta_deg: float, *, omega_in: float = 0.0, tol: float = 1e-6,
               mu_max: float = 10.0) -> Calibration:
    """The friction coefficient for which ``simulate(scene, theta_deg, omega_in).e_t == e_t``.

    The starting bracket comes from Eq. 2 with the head-on e_N of the scene; the root is found on
    the simulation. The angle must be one where the impact slides throughout at the answer: if
    the measured e_T is at or below the rolling value (2/3 for a disc without spin), mu is not
    identifiable from it and a ``ValueError`` says so.

    >>> import restitution as rs
    >>> cal = mu_for_e_t(rs.Scene(), 0.85, theta_deg=20.0)
    >>> round(cal.value, 3)
    0.215
    """
    th = real("theta_deg", theta_deg)
    check_theta(th)
    if th >= 90.0:
        raise ValueError("require `theta_deg` < 90 (e_T is undefined head-on)")
    target = float(e_t)
    if not math.isfinite(target):
        raise ValueError(f"require `e_t` finite (found {e_t})")
    kappa = 0.4 if scene.inertia == "sphere" else theory.DISC
    e_roll = float(theory.e_t_rolling(th, omega_in, r=scene.r, v=scene.v, kappa=kappa))
    e0 = simulate(scene.replace(mu=0.0), th, omega_in).e_t
    if e0 is None:
        raise ValueError("e_T is undefined at this angle")
    if not (e_roll < target < e0) and not (e0 < target < e_roll):
        raise ValueError(
            f"`e_t` = {target} is not between the frictionless value {e0:.4f} and the rolling value {e_roll:.4f} "
            f"at theta = {th} deg: mu cannot be identified from it (choose a flatter angle)")

    def f(m: float) -> float:
        val = simulate(scene.replace(mu=m), th, omega_in).e_t
        assert val is not None
        return val - target

    # Rigid-body guess from Eq. 2, with the head-on e_N as a stand-in for the measured one.
    e_n = simulate(scene.replace(mu=0.0), 90.0).e_n
    guess = abs(1.0 - target) / ((1.0 + e_n) * math.tan(math.radians(th)))
    lo, flo = 0.0, e0 - target
    hi = max(guess * 1.5, 1e-3)
    fhi = f(hi)
    evals = 2
    while np.sign(fhi) == np.sign(flo):
        lo, flo = hi, fhi
        hi *= 2.0
        if hi > mu_max:
            raise ValueError(f"`e_t` = {target} is not reached with `mu` <= {mu_max} at theta = {th} deg")
        fhi = f(hi)
        evals += 1
    m, fm, k = _bisect_secant(f, lo, hi, flo, fhi, ftol=tol, xtol=1e-12)
    cal_scene = scene.replace(mu=m)
    rec = simulate(cal_scene, th, omega_in)
    if not bool(theory.slides(th, m, rec.e_n, omega_in, r=scene.r, v=scene.v, kappa=kappa)):
        raise ValueError(f"at theta = {th} deg and mu = {m:.4g} the impact does not slide throughout: "
                         "e_T there hardly depends on mu (choose a flatter angle)")
    return Calibration("mu", m, target, fm + target, evals + k + 1, cal_scene)


__all__ = ["Calibration", "gamma_for_e_n", "mu_for_e_t"]
