"""Global sensitivity: which parameter moves which quantity, at which angle (Sobol' indices).

For a quantity Y = f(X_1 ... X_d) of independent random parameters, the first-order index
S1_i = Var(E[Y | X_i]) / Var(Y) is the share of Y's variance that X_i explains alone, and the
total index ST_i = E[Var(Y | X_~i)] / Var(Y) the share it takes part in, interactions included
(ST_i = 0 exactly when Y does not depend on X_i). Both are estimated by scipy's
``scipy.stats.sobol_indices`` (Saltelli et al. 2010's estimators, with Jansen's for ST) from
n (d + 2) impacts per point: two matrices A and B of n parameter sets (a scrambled Sobol'
sequence in 2d dimensions, each column mapped to its prior by the distribution's own inverse
CDF, as scipy samples them) and the d matrices AB_i (A with column i taken from B). Every
impact of every point runs in one engine call; the intervals are percentile bootstrap intervals
over the n rows (``scipy.stats.bootstrap``, seeded).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import polars as pl

from ..errors import RestitutionError
from ..runs.distributions import Distribution, check_seed, from_dict
from ..scene import Scene
from . import _scipy
from ._forward import check_parameter, check_quantities, predict

#: Columns of :func:`sensitivity`'s frame after the axes.
INDEX_COLUMNS = ("S1", "S1_lo", "S1_hi", "ST", "ST_lo", "ST_hi")


def sensitivity(scene: Scene, vary: Mapping[str, Any], *, n: int = 1024, seed: int = 3,
                theta_deg: Sequence[float] | float = (10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 90.0),
                omega_in: Sequence[float] | float = (0.0,),
                quantities: Sequence[str] = ("e_n", "e_t", "omega_out"),
                confidence_level: float = 0.95, n_resamples: int = 999,
                tol: float | None = None) -> pl.DataFrame:
    """First-order and total Sobol' indices of each quantity to each varied parameter, at each
    point (every ``theta_deg`` with every ``omega_in``).

    Parameters
    ----------
    scene : Scene
        Every value that is not varied.
    vary : mapping
        Scene field -> its distribution (``rs.Uniform``, ``rs.Normal``, ``rs.LogNormal`` or their
        dict form): the parameters, independent.
    n : int
        Base sample size, a power of 2 (>= 16): n (d + 2) impacts per point.
    seed : int
        Seeds the Sobol' sequence and the bootstrap: the frame is the same on every run.
    theta_deg, omega_in : float or sequence of float
        The points: their Cartesian product.
    quantities : sequence of str
        Record columns (``e_n``, ``e_t``, ``e_kin``, ``omega_out``, ...).
    confidence_level, n_resamples : float, int
        Of the percentile bootstrap intervals.
    tol : float, optional
        The adaptive path's tolerance for these impacts (default: the scene's). A quantity whose
        spread at a point is below 10 tol (the integrator's noise) gets null indices there, as
        does one undefined there (``e_t`` head-on).

    Returns
    -------
    polars.DataFrame
        One row per (quantity, parameter, point): ``quantity``, ``parameter``, ``theta_deg``,
        ``omega_in``, ``S1``, ``S1_lo``, ``S1_hi``, ``ST``, ``ST_lo``, ``ST_hi``.

    Examples
    --------
    >>> import restitution as rs
    >>> scene = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
    ...                  cor=0.98, mu=0.092, v=3.9)
    >>> s = rs.calibrate.sensitivity(scene, {"mu": rs.Uniform(0.05, 0.3), "cor": rs.Uniform(0.5, 0.99)},
    ...                              n=64, theta_deg=[15.0], quantities=["e_n"], n_resamples=99)
    >>> st = dict(s.select("parameter", "ST").rows())
    >>> st["mu"] < 1e-6 < 0.99 < st["cor"]         # e_N of a sphere on a plate ignores friction
    True
    """
    stats = _scipy.stats()
    priors = _check_vary(vary)
    n = _check_n(n)
    generator = np.random.default_rng(check_seed(seed))
    names = check_quantities(quantities)
    if not (isinstance(confidence_level, float) and 0.0 < confidence_level < 1.0):
        raise RestitutionError("confidence_level", repr(confidence_level), "a float in (0, 1)")
    if isinstance(n_resamples, bool) or not isinstance(n_resamples, (int, np.integer)) or n_resamples < 1:
        raise RestitutionError("n_resamples", repr(n_resamples), "an integer >= 1")
    points = pl.DataFrame(
        [(float(t), float(w)) for t in np.atleast_1d(theta_deg) for w in np.atleast_1d(omega_in)],
        schema={"theta_deg": pl.Float64, "omega_in": pl.Float64}, orient="row")
    d = len(priors)
    sets = _saltelli_sets(stats, list(priors.values()), n, generator)
    out = predict(scene, dict(zip(priors, sets)), points, names, tol=tol)
    # Outputs: one per (quantity, point); f of shape (d + 2, outputs, n): A, B, then the AB_i.
    f = np.stack([out[q] for q in names], axis=1).reshape(d + 2, n, -1).transpose(0, 2, 1)
    floor = 10.0 * (tol if tol is not None else scene.tol)
    live = np.isfinite(f).all(axis=(0, 2)) & (f[:2].std(axis=(0, 2)) > floor)
    s1, st = np.full((f.shape[1], d, 3), np.nan), np.full((f.shape[1], d, 3), np.nan)
    if live.any():
        s1[live], st[live] = _indices(stats, f[:, live], n, generator, confidence_level, n_resamples)
    rows = [(q, name, theta, omega, *s1[k, j], *st[k, j])
            for k, (q, (theta, omega)) in enumerate((q, p) for q in names for p in points.rows())
            for j, name in enumerate(priors)]
    schema = {"quantity": pl.String, "parameter": pl.String, "theta_deg": pl.Float64, "omega_in": pl.Float64,
              **{c: pl.Float64 for c in INDEX_COLUMNS}}
    return pl.DataFrame(rows, orient="row", schema=schema).fill_nan(None)


def _check_vary(vary: Mapping[str, Any]) -> dict[str, Distribution]:
    if not isinstance(vary, Mapping) or not vary:
        raise RestitutionError("vary", repr(vary), "a mapping of scene fields to distributions")
    priors = {check_parameter(k, "vary"): from_dict(v, where=f"vary.{k}") for k, v in vary.items()}
    for k, dist in priors.items():
        if not np.issubdtype(np.asarray(dist.ppf(np.array([0.5]))).dtype, np.number):
            raise RestitutionError(f"vary.{k}", repr(dist), "a distribution of numbers")
    return priors


def _check_n(n: Any) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 16 or n & (n - 1):
        raise RestitutionError("n", repr(n), "a power of 2 >= 16 (the Sobol' sequence's balance needs it)")
    return int(n)


def _saltelli_sets(stats: Any, priors: list[Distribution], n: int, generator: np.random.Generator) -> np.ndarray:
    """The parameter sets of A, B and the AB_i, as in ``scipy.stats.sobol_indices``: one
    scrambled Sobol' sequence of 2d columns, A the first d, B the last d, each column through its
    prior's inverse CDF. Shape (d, (d + 2) n): column block 0 is A, 1 is B, 2 + i is AB_i."""
    d = len(priors)
    sobol = stats.qmc.Sobol(d=2 * d, scramble=True, bits=64, **_scipy.seeded(stats.qmc.Sobol, "seed", generator))
    a_b = sobol.random(n).T.reshape(2, d, n)
    for i, prior in enumerate(priors):
        a_b[:, i] = np.asarray(prior.ppf(a_b[:, i]), dtype=np.float64)
    a, b = a_b
    ab = np.tile(a, (d, 1, 1))
    ab[np.arange(d), np.arange(d)] = b
    return np.concatenate([a, b, *ab], axis=1)


def _indices(stats: Any, f: np.ndarray, n: int, generator: np.random.Generator, confidence_level: float,
             n_resamples: int) -> tuple[np.ndarray, np.ndarray]:
    """(S1, ST) of each output, each as (index, lo, hi): shapes (outputs, d, 3). scipy's
    estimators on the precomputed evaluations, its bootstrap over the n rows."""
    d, outputs = f.shape[0] - 2, f.shape[1]

    def estimate(rows: np.ndarray) -> np.ndarray:
        res = stats.sobol_indices(func={"f_A": f[0][:, rows], "f_B": f[1][:, rows], "f_AB": f[2:][..., rows]}, n=n)
        return np.concatenate([np.reshape(res.first_order, (outputs, d)).ravel(),
                               np.reshape(res.total_order, (outputs, d)).ravel()])

    point = estimate(np.arange(n))
    # Percentile intervals: BCa's jackknife would evaluate the estimator on n - 1 rows, which
    # scipy refuses (its Sobol' balance needs a power of 2), while each resample keeps n rows.
    boot = stats.bootstrap((np.arange(n),), estimate, n_resamples=n_resamples, confidence_level=confidence_level,
                           method="percentile", vectorized=False,
                           **_scipy.seeded(stats.bootstrap, "random_state", generator))
    lo, hi = boot.confidence_interval.low, boot.confidence_interval.high
    table = np.stack([point, lo, hi], axis=-1).reshape(2, outputs, d, 3)
    return table[0], table[1]


def plot_sensitivity(frame: pl.DataFrame, *, index: str = "ST", path: Any = None) -> Any:
    """Which parameter matters at which angle: one panel per quantity (and ``omega_in``), the
    index of each parameter against ``theta_deg`` with its interval as a band.

    Parameters
    ----------
    frame : polars.DataFrame
        What :func:`sensitivity` returned.
    index : {"ST", "S1"}
        Total (default) or first-order indices.
    path : str or Path, optional
        Where to save the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..study.figures import OKABE_ITO, THETA_LABEL, _label, _plt, _save

    if index not in ("ST", "S1"):
        raise RestitutionError("index", repr(index), '"ST" or "S1"')
    plt = _plt()
    panels = frame.partition_by(["quantity", "omega_in"], maintain_order=True)
    fig, axes = plt.subplots(1, len(panels), figsize=(4.0 * len(panels), 3.4), squeeze=False, sharey=True)
    for ax, panel in zip(axes[0], panels):
        for k, part in enumerate(panel.partition_by("parameter", maintain_order=True)):
            part = part.sort("theta_deg")
            x = part["theta_deg"].to_numpy()
            y, lo, hi = (part[c].cast(pl.Float64).fill_null(np.nan).to_numpy()
                         for c in (index, f"{index}_lo", f"{index}_hi"))
            colour = OKABE_ITO[(k + 1) % len(OKABE_ITO)]
            ax.fill_between(x, lo, hi, color=colour, alpha=0.25, lw=0)
            ax.plot(x, y, "o-", color=colour, ms=3, lw=1.2, label=part["parameter"][0])
        omega = panel["omega_in"][0]
        ax.set_title(_label(panel["quantity"][0]) + (f", $\\omega_{{in}}$ = {omega:g}" if omega else ""))
        ax.set_xlabel(THETA_LABEL)
        ax.set_ylim(-0.05, 1.05)
    axes[0][0].set_ylabel("total Sobol' index $S_T$" if index == "ST" else "first-order Sobol' index $S_1$")
    axes[0][0].legend(loc="best")
    fig.tight_layout()
    _save(fig, path)
    return fig
