"""Bayesian calibration: a posterior over scene fields from measured impacts (docs/model.md,
"Calibration").

The target is p(theta | data) ~ prior(theta) prod_i L(value_i | model_i(theta), sigma_i), each
point's likelihood Gaussian (or Student-t) with its own sigma. emcee's affine-invariant ensemble
samples it (the engine gives no gradients, which HMC or NUTS would need); each iteration
updates the ensemble's two halves in turn, each half at all data points in one engine call
(:func:`._forward.predict`). The
chain grows in batches until it passes its convergence tests or reaches ``max_iter``.
"""

from __future__ import annotations

import math
import time
from typing import Any, Callable, Mapping

import numpy as np
import polars as pl

from ..datasets import check_measurements
from ..errors import RestitutionError
from ..runs.distributions import Distribution, check_seed
from ..runs._progress import Progress, want_progress
from ..scene import Scene
from . import _forward
from .diagnostics import Convergence, convergence
from .posterior import Posterior
from .problem import Problem

LIKELIHOODS = ("gaussian", "student-t")
#: Iterations between two convergence checks.
BATCH = 50
#: The integrator's error is kept this many times below the smallest sigma.
TOL_MARGIN = 100.0
#: The range of the chosen tol: the adaptive path's own limits are [1e-12, 1e-2].
TOL_RANGE = (1e-9, 1e-3)


def require_emcee() -> Any:
    """The emcee module, or an ImportError saying which extra installs it."""
    try:
        import emcee
    except ImportError:
        raise ImportError('restitution.calibrate.fit needs emcee: pip install "restitution[calibrate]"') from None
    return emcee


def _dimensionless_scale(scene: Scene, quantity: str) -> float:
    """What turns a sigma of ``quantity`` into the units of the adaptive path's ``tol`` (absolute
    error of e_N, e_T, e_kin and omega r / v)."""
    if quantity in ("omega_out", "partner_omega_out"):
        return scene.r / scene.v
    if quantity.endswith("_deg"):
        return math.pi / 180.0
    if quantity.startswith(("vx", "vy", "partner_v")):
        return 1.0 / scene.v
    return 1.0


def choose_tol(scene: Scene, data: pl.DataFrame) -> float | None:
    """The adaptive path's tol for a fit: the smallest sigma (made dimensionless) over
    :data:`TOL_MARGIN`, within :data:`TOL_RANGE`; None for the fixed-step integrators (their
    ``dt_factor`` is the user's choice)."""
    if scene.integrator not in ("adaptive", "reference"):
        return None
    relative = ("contact_time", "max_depth", "max_area")
    scaled = [s * _dimensionless_scale(scene, q) if q not in relative else s / max(abs(v), 1e-300)
              for q, s, v in zip(data["quantity"], data["sigma"], data["value"])]
    return float(np.clip(min(scaled) / TOL_MARGIN, *TOL_RANGE))


class Target:
    """The log posterior over an ensemble of walkers, as emcee's ``vectorize=True`` calls it;
    counts the impacts it runs."""

    def __init__(self, problem: Problem) -> None:
        self.problem, self.impacts = problem, 0

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        theta = np.atleast_2d(theta)
        lp = self.problem.log_prior(theta)
        inside = np.isfinite(lp)
        if inside.any():
            model = self.problem.model(theta[inside])
            self.impacts += model.shape[0] * self.problem.layout[0].height
            lp[inside] += self.problem.pointwise_log_lik(model).sum(axis=1)
        return lp


def make_problem(scene: Scene, data: pl.DataFrame, free: Mapping[str, Any], likelihood: str, df: float,
                 tol: float | None) -> Problem:
    """Checks every input of a fit once: a :class:`RestitutionError` names the first bad one."""
    if not isinstance(scene, Scene):
        raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
    data = check_measurements(data)
    if not isinstance(free, Mapping) or not free:
        raise RestitutionError("free", repr(free), "a dict of scene field -> prior distribution, at least one")
    for name, prior in free.items():
        if not isinstance(prior, Distribution):
            raise RestitutionError(f"free.{name}", repr(prior), "a distribution (rs.Uniform, rs.Normal, ...)")
        prior.logpdf(np.zeros(1))  # refuses a Choice
    _forward.check_names(list(free), data["quantity"].unique().to_list())
    if likelihood not in LIKELIHOODS:
        raise RestitutionError("likelihood", repr(likelihood), "one of " + ", ".join(map(repr, LIKELIHOODS)))
    if not (isinstance(df, (int, float)) and math.isfinite(df) and df > 0):
        raise RestitutionError("df", df, "finite and > 0 (the Student-t's degrees of freedom)")
    if tol is not None and not (isinstance(tol, (int, float)) and 1e-12 <= tol <= 1e-2):
        raise RestitutionError("tol", tol, "in [1e-12, 1e-2], or None to choose it from the data's sigma")
    chosen = choose_tol(scene, data) if tol is None else float(tol)
    return Problem(scene, data, dict(free), likelihood, float(df), chosen)


def fit(scene: Scene, data: pl.DataFrame, free: Mapping[str, Distribution], *, seed: int = 1,
        likelihood: str = "gaussian", df: float = 4.0, walkers: int | None = None, tol: float | None = None,
        max_iter: int = 20_000, min_ess: int = 400, rhat_max: float = 1.01, progress: bool | None = None) -> Posterior:
    """The posterior of the ``free`` scene fields given measured impacts.

    Parameters
    ----------
    scene : Scene
        Every field that is not free (shape, law, speed, ...).
    data : polars.DataFrame
        Measurements (:func:`restitution.datasets.check_measurements`: theta_deg, omega_in,
        quantity, value, sigma).
    free : dict
        Scene field -> its prior (``rs.Uniform``, ``rs.Normal``, ``rs.LogNormal``).
    seed : int
        Seeds the walkers' start and moves: the same seed gives the same samples.
    likelihood : {"gaussian", "student-t"}
        Each point's error law, scaled by its sigma; Student-t with ``df`` degrees of freedom
        for data with outliers.
    walkers : int, optional
        Ensemble size, even (default max(8, 4 x the number of free fields)).
    tol : float, optional
        The adaptive path's accuracy; default: the smallest sigma / 100 (:func:`choose_tol`).
    max_iter : int
        Most iterations; a chain stopped there is reported as not converged.
    min_ess, rhat_max : int, float
        Convergence: every free field's effective sample size >= ``min_ess`` and rank-normalised
        split R-hat <= ``rhat_max``, with a chain longer than 50 autocorrelation times.
    progress : bool, optional
        A progress line (default: on a terminal).

    Returns
    -------
    Posterior

    Examples
    --------
    >>> import polars as pl, restitution as rs
    >>> data = pl.DataFrame({"theta_deg": [10.0, 20.0], "quantity": ["e_t", "e_t"], "value": [0.93, 0.86],
    ...                      "sigma": [0.01, 0.01]})
    >>> post = rs.calibrate.fit(rs.Scene(), data, {"mu": rs.Uniform(0.0, 1.0)}, seed=1)
    >>> s = post.summary().row(0, named=True)
    >>> s["parameter"], 0.15 < s["q50"] < 0.25, s["converged"]
    ('mu', True, True)
    """
    problem = make_problem(scene, data, free, likelihood, df, tol)
    return run(problem, seed=seed, walkers=walkers, max_iter=max_iter, min_ess=min_ess, rhat_max=rhat_max,
               progress=progress)


def _start(problem: Problem, target: Target, seed: int, walkers: int) -> np.ndarray:
    """The walkers' start: the best ``walkers`` of 8 x as many prior draws (one engine call), so
    that burn-in does not wander the prior's tails."""
    n = 8 * walkers
    draws = np.column_stack([d.draw(seed, name, 0, n) for name, d in problem.free.items()])
    lp = target(draws)
    if not np.isfinite(lp).any():
        raise RestitutionError("free", "priors", "a prior under which the model gives every measured quantity "
                               "(every draw had an undefined value or zero prior density)")
    return draws[np.argsort(-lp, kind="stable")[:walkers]]


def run(problem: Problem, *, seed: int = 1, walkers: int | None = None, max_iter: int = 20_000,
        min_ess: int = 400, rhat_max: float = 1.01, progress: bool | None = None,
        stop: Callable[[], bool] | None = None) -> Posterior:
    """Samples ``problem`` (see :func:`fit`); ``stop()`` true between batches ends the run early
    (``restitution calibrate`` on a first Ctrl-C), reported as not converged."""
    emcee = require_emcee()
    seed = check_seed(seed)
    dim = len(problem.free)
    walkers = max(8, 4 * dim) if walkers is None else int(walkers)
    if walkers < 2 * dim or walkers % 2:
        raise RestitutionError("walkers", walkers, f"an even number >= {2 * dim} (2 x the free fields)")
    if isinstance(max_iter, bool) or not (isinstance(max_iter, int) and max_iter >= BATCH):
        raise RestitutionError("max_iter", max_iter, f"an integer >= {BATCH}")
    if not (isinstance(min_ess, (int, float)) and min_ess > 0):
        raise RestitutionError("min_ess", min_ess, "> 0")
    if not (isinstance(rhat_max, (int, float)) and rhat_max > 1.0):
        raise RestitutionError("rhat_max", rhat_max, "> 1")
    t0 = time.perf_counter()
    target = Target(problem)
    start = _start(problem, target, seed, walkers)
    sampler = emcee.EnsembleSampler(walkers, dim, target, vectorize=True,
                                    moves=[(emcee.moves.DEMove(), 0.8), (emcee.moves.DESnookerMove(), 0.2)])
    sampler.random_state = np.random.RandomState(seed % 2**32).get_state()
    per_iter = walkers * problem.layout[0].height
    bar = Progress(max_iter * per_iter, enabled=want_progress(progress, 10**9))
    state, diag, reason = start, None, "max_iter"
    try:
        while sampler.iteration < max_iter:
            state = sampler.run_mcmc(state, min(BATCH, max_iter - sampler.iteration), progress=False)
            bar.update(BATCH * per_iter)
            diag = convergence(sampler.get_chain(), min_ess=min_ess, rhat_max=rhat_max)
            if diag.converged:
                reason = "converged"
                break
            if stop is not None and stop():
                reason = "interrupted"
                break
    finally:
        bar.close()
    assert diag is not None
    return _posterior(problem, sampler, diag, reason, target.impacts, time.perf_counter() - t0, seed)


def _posterior(problem: Problem, sampler: Any, diag: Convergence, reason: str, impacts: int, seconds: float,
               seed: int) -> Posterior:
    chain = sampler.get_chain(discard=diag.discard, flat=True)
    log_prob = sampler.get_log_prob(discard=diag.discard, flat=True)
    samples = pl.DataFrame({**{name: chain[:, k] for k, name in enumerate(problem.names)}, "log_prob": log_prob})
    return Posterior(problem=problem, samples=samples, convergence=diag, stopped=reason, iterations=sampler.iteration,
                     walkers=sampler.nwalkers, impacts=impacts, seconds=seconds, seed=seed)


__all__ = ["LIKELIHOODS", "choose_tol", "fit"]
