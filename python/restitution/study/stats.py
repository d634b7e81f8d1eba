"""Estimators of a sample's distribution with confidence intervals (numpy only).

For a sample x_1 ... x_n (the finite records of one ensemble point):

- mean and standard deviation (``ddof = 1``);
- quantiles at 5, 25, 50, 75, 95 %, numpy's default estimator (linear interpolation between
  order statistics, Hyndman & Fan's type 7);
- each of these with a percentile bootstrap interval: ``n_boot`` resamples of size n drawn
  with replacement, the estimator on each, the interval between the resamples' (1 - level) / 2
  and (1 + level) / 2 quantiles;
- the probability of a negative value, k / n, with Wilson's score interval (a bootstrap gives
  [0, 0] when no draw is negative, which claims a certainty the sample does not hold).

Examples
--------
>>> import numpy as np
>>> from restitution.study import stats
>>> d = stats.describe(np.arange(1.0, 101.0), rng=np.random.default_rng(0))
>>> d["mean"], d["q50"], d["p_neg"]
(50.5, 50.5, 0.0)
>>> d["mean_lo"] < 50.5 < d["mean_hi"], round(d["p_neg_hi"], 4)   # Wilson: 3.84 / 103.84
(True, 0.037)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..runs.distributions import normal_ppf

#: The quantiles every summary reports, and their column names.
QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
QUANTILE_NAMES = ("q05", "q25", "q50", "q75", "q95")
#: The estimators with a bootstrap interval, in column order.
ESTIMATES = ("mean", "sd") + QUANTILE_NAMES
#: Resampled values held at once (bounds the bootstrap's memory to ~32 MB).
_BOOT_BLOCK = 4_000_000


def _estimates(x: np.ndarray) -> np.ndarray:
    """mean, sd, q05 ... q95 along the last axis: shape (..., 7)."""
    mean = x.mean(axis=-1)
    sd = x.std(axis=-1, ddof=1) if x.shape[-1] > 1 else np.full(mean.shape, np.nan)
    q = np.quantile(x, QUANTILES, axis=-1)
    return np.concatenate([mean[None], sd[None], q], axis=0).T


def wilson(k: int, n: int, level: float = 0.95) -> tuple[float, float]:
    """Wilson's score interval of a binomial proportion k / n.

    Examples
    --------
    >>> [round(b, 4) for b in wilson(0, 10)]
    [0.0, 0.2775]
    """
    z = float(normal_ppf(np.array([0.5 + level / 2.0]))[0])
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / denom
    return max(0.0, centre - half), min(1.0, centre + half)


def describe(x: Any, *, level: float = 0.95, n_boot: int = 1000,
             rng: np.random.Generator) -> dict[str, float | None]:
    """The estimates of :data:`ESTIMATES` with ``_lo`` / ``_hi`` bootstrap bounds, ``p_neg``
    with its Wilson bounds, and ``n``. Undefined values (an sd of one value, intervals with
    ``n_boot = 0``) are None.

    Parameters
    ----------
    x : array-like
        The sample (finite values).
    level : float
        Confidence level of the intervals, in (0, 1).
    n_boot : int
        Bootstrap resamples (0: no intervals for the estimators).
    rng : numpy.random.Generator
        Draws the resamples (pass a seeded one: the intervals are then reproducible).
    """
    if not 0.0 < level < 1.0:
        raise ValueError(f"require `level` in (0, 1) (found {level})")
    if isinstance(n_boot, bool) or not isinstance(n_boot, (int, np.integer)) or n_boot < 0:
        raise ValueError(f"require `n_boot` an integer >= 0 (found {n_boot!r})")
    x = np.asarray(x, dtype=np.float64).ravel()
    n = x.size
    out: dict[str, float | None] = {"n": float(n)}
    if n == 0:
        return out | {k: None for k in _columns()[1:]}
    est = _estimates(x)
    lo = hi = np.full(len(ESTIMATES), np.nan)
    if n_boot > 0 and n > 1:
        boot = np.concatenate([_estimates(x[rng.integers(0, n, size=(b, n))])
                               for b in _blocks(n_boot, max(1, _BOOT_BLOCK // n))])
        lo, hi = np.quantile(boot, [(1.0 - level) / 2.0, (1.0 + level) / 2.0], axis=0)
    for k, name in enumerate(ESTIMATES):
        out[name] = _value(est[k])
        out[f"{name}_lo"], out[f"{name}_hi"] = _value(lo[k]), _value(hi[k])
    k_neg = int((x < 0.0).sum())
    out["p_neg"] = k_neg / n
    out["p_neg_lo"], out["p_neg_hi"] = wilson(k_neg, n, level)
    return out


def _blocks(total: int, size: int) -> list[int]:
    return [min(size, total - s) for s in range(0, total, size)]


def _value(v: float) -> float | None:
    return float(v) if np.isfinite(v) else None


def _columns() -> list[str]:
    """The keys of :func:`describe`, in order."""
    cols = ["n"]
    for name in ESTIMATES:
        cols += [name, f"{name}_lo", f"{name}_hi"]
    return cols + ["p_neg", "p_neg_lo", "p_neg_hi"]


COLUMNS = tuple(_columns())

__all__ = ["COLUMNS", "ESTIMATES", "QUANTILES", "describe", "wilson"]
