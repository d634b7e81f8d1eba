"""Experiment design: which impacts to measure next, so that the posterior of the free
parameters narrows most.

The criterion is Bayesian D-optimality under a linear-Gaussian approximation, averaged over the
prior: around a parameter set x_s the predictions are linear, y(x) ~ y(x_s) + J_s (x - x_s),
with the Jacobian J_s by central differences; measuring quantity q at point p with noise sigma_q
adds J_{s,q,p}^T J_{s,q,p} / sigma_q^2 to the precision, starting from the prior's (a Gaussian
with the prior's variances). The expected information gain of a design D is then

    EIG(D) = mean over s of 1/2 ln det(Lambda_s(D) Sigma_0),   Lambda_s(D) = Sigma_0^-1 + sum_{p in D} M_{s,p},

(exact for a linear model with a Gaussian prior; Chaloner & Verdinelli 1995, section 2.2), and
the expected posterior variance of parameter j is the mean over s of (Lambda_s(D)^-1)_jj. Points
are picked greedily, each the candidate that raises EIG most given those already picked (the
log-determinant is submodular, so the greedy design is within 1 - 1/e of the best one's gain).
Every prediction, for all draws, perturbations and candidates, comes from one engine call.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import polars as pl

from ..errors import RestitutionError
from ..runs.distributions import Distribution, check_seed, from_dict
from ..scene import Scene
from ._forward import check_parameter, check_points, check_quantities, predict

#: Half the central difference's step, in the prior's quantile: x(u +- STEP) with u drawn in
#: [STEP, 1 - STEP], so every perturbed parameter stays inside the prior's support.
STEP = 0.01

#: Quantile points of the quadrature of each prior's variance (midpoint rule in u).
_QUADRATURE = 4096


def design(scene: Scene, free: Mapping[str, Any], candidates: pl.DataFrame, *, k: int = 4,
           quantities: Sequence[str] = ("e_n", "e_t"), sigma: Mapping[str, float], seed: int = 5,
           draws: int = 64, tol: float | None = None) -> pl.DataFrame:
    """The ``k`` candidate points to measure that most reduce the expected posterior uncertainty
    of the ``free`` parameters (expected information gain under a linear-Gaussian
    approximation, averaged over prior draws; picked greedily; see the module doc).

    Parameters
    ----------
    scene : Scene
        Every value that is not free.
    free : mapping
        Scene field -> its prior (``rs.Uniform``, ``rs.Normal``, ``rs.LogNormal`` or their dict
        form), independent.
    candidates : polars.DataFrame
        Where one could measure: ``theta_deg`` and optionally ``omega_in``, one row per point.
    k : int
        Points to pick, distinct rows, 1 <= k <= the candidates' count.
    quantities : sequence of str
        What each measured impact records (``e_n``, ``e_t``, ``omega_out``, ...).
    sigma : mapping
        Quantity -> its measurement's standard deviation (> 0), for every quantity.
    seed : int
        Seeds the prior draws.
    draws : int
        Prior draws the criterion averages over (>= 2).
    tol : float, optional
        The adaptive path's tolerance for these impacts (default: the scene's); keep it far
        below each sigma times the prior's 1 % quantile step.

    Returns
    -------
    polars.DataFrame
        The chosen rows in the order picked: ``pick`` (1 ... k), the candidates' columns,
        ``eig`` (the expected information gain of the first ``pick`` points, nats) and
        ``sd_<name>`` for each free parameter (the expected posterior sd after them).

    Examples
    --------
    >>> import polars as pl, restitution as rs
    >>> scene = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
    ...                  cor=0.98, mu=0.092, v=3.9)
    >>> where = pl.DataFrame({"theta_deg": [10.0, 30.0, 50.0, 70.0, 90.0]})
    >>> d = rs.calibrate.design(scene, {"mu": rs.Uniform(0.05, 0.3)}, where, k=2, quantities=["e_t"],
    ...                         sigma={"e_t": 0.02}, draws=16)
    >>> 90.0 in d["theta_deg"].to_list()          # head-on e_T says nothing about mu
    False
    """
    priors = {check_parameter(name, "free"): from_dict(v, where=f"free.{name}") for name, v in _mapping(free).items()}
    points = check_points(candidates)
    names = check_quantities(quantities)
    noise = _check_sigma(sigma, names)
    k = _check_count("k", k, 1, points.height)
    draws = _check_count("draws", draws, 2, 1 << 16)
    generator = np.random.default_rng(check_seed(seed))
    info = _information(scene, priors, points, names, noise, generator.uniform(STEP, 1.0 - STEP,
                                                                                   (draws, len(priors))), tol)
    prior_precision = np.diag([1.0 / _variance(p) for p in priors.values()])
    precision = np.broadcast_to(prior_precision, (draws, *prior_precision.shape)).copy()
    base = np.linalg.slogdet(prior_precision)[1]
    rows: list[dict[str, Any]] = []
    left = list(range(points.height))
    for pick in range(1, k + 1):
        gains = [np.linalg.slogdet(precision + info[:, p])[1].mean() for p in left]
        best = left.pop(int(np.argmax(gains)))
        precision += info[:, best]
        variance = np.linalg.inv(precision).diagonal(axis1=1, axis2=2).mean(axis=0)
        rows.append({"pick": pick, **points.row(best, named=True),
                     "eig": 0.5 * (np.linalg.slogdet(precision)[1].mean() - base),
                     **{f"sd_{name}": float(np.sqrt(v)) for name, v in zip(priors, variance)}})
    return pl.DataFrame(rows)


def _information(scene: Scene, priors: dict[str, Distribution], points: pl.DataFrame, names: list[str],
                 noise: np.ndarray, u: np.ndarray, tol: float | None) -> np.ndarray:
    """The Fisher information J^T J / sigma^2 of one measurement at each candidate, at each
    draw: shape (draws, candidates, d, d). A quantity undefined at a candidate (``e_t``
    head-on) adds nothing there."""
    draws, d = u.shape
    # Per draw: the draw itself, then each parameter's quantile moved by +STEP and by -STEP.
    shifts = np.concatenate([np.zeros((1, d)), STEP * np.eye(d), -STEP * np.eye(d)])
    sets = (u[:, None, :] + shifts[None, :, :]).reshape(-1, d)
    x = np.column_stack([np.asarray(p.ppf(sets[:, j]), dtype=np.float64) for j, p in enumerate(priors.values())])
    out = predict(scene, dict(zip(priors, x.T)), points, names, tol=tol)
    x = x.reshape(draws, 2 * d + 1, d)
    diagonal = np.arange(d)
    dx = x[:, 1 + diagonal, diagonal] - x[:, 1 + d + diagonal, diagonal]  # (draws, d): x(u + STEP) - x(u - STEP)
    info = np.zeros((draws, points.height, d, d))
    for q, sd in zip(names, noise):
        f = out[q].reshape(draws, 2 * d + 1, points.height)
        jac = (f[:, 1:d + 1] - f[:, d + 1:]) / dx[:, :, None]  # (draws, d, candidates)
        jac = np.where(np.isfinite(jac).all(axis=1, keepdims=True), jac, 0.0) / sd
        info += np.einsum("sip,sjp->spij", jac, jac)
    return info


def _variance(prior: Distribution) -> float:
    """The prior's variance by the midpoint rule on its quantile function."""
    x = np.asarray(prior.ppf((np.arange(_QUADRATURE) + 0.5) / _QUADRATURE), dtype=np.float64)
    return float(x.var())


def _mapping(free: Any) -> Mapping[str, Any]:
    if not isinstance(free, Mapping) or not free:
        raise RestitutionError("free", repr(free), "a mapping of scene fields to their priors")
    return free


def _check_sigma(sigma: Any, names: list[str]) -> np.ndarray:
    if not isinstance(sigma, Mapping):
        raise RestitutionError("sigma", repr(sigma), "a mapping of each quantity to its measurement sd")
    out = []
    for q in names:
        value = sigma.get(q)
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not 0 < value < np.inf:
            raise RestitutionError(f"sigma.{q}", repr(value), "a finite standard deviation > 0")
        out.append(float(value))
    return np.array(out)


def _check_count(name: str, value: Any, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
        raise RestitutionError(name, repr(value), f"an integer in [{lo}, {hi}]")
    return int(value)
