"""Convergence of an ensemble chain: autocorrelation time, effective sample size, split R-hat.

- The integrated autocorrelation time tau of each parameter is emcee's estimate (Goodman &
  Weare 2010; Sokal's window), from the walkers' mean; it is trusted only on a chain longer than
  :data:`TAU_FACTOR` tau (emcee's own rule).
- Burn-in: the first :data:`BURN_TAUS` tau are dropped.
- ESS = walkers x kept iterations / tau.
- R-hat: rank-normalised split R-hat (Vehtari, Gelman, Simpson, Carpenter & Buerkner 2021), each
  walker's kept chain split in halves and treated as a chain.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..runs.distributions import normal_ppf

#: A chain shorter than this many autocorrelation times gives no reliable tau.
TAU_FACTOR = 50
#: Autocorrelation times dropped as burn-in.
BURN_TAUS = 3


@dataclass(frozen=True)
class Convergence:
    """The diagnostics of one chain: per parameter (in the order of ``free``) tau, ESS and
    R-hat; ``discard`` iterations dropped as burn-in; ``converged`` when every test passed."""

    tau: tuple[float, ...]
    ess: tuple[float, ...]
    rhat: tuple[float, ...]
    discard: int
    tau_reliable: bool
    converged: bool


def split_rhat(chain: np.ndarray) -> np.ndarray:
    """Rank-normalised split R-hat of each parameter of ``chain`` (iterations, chains, params)."""
    n = chain.shape[0] // 2
    halves = np.concatenate([chain[:n], chain[chain.shape[0] - n:]], axis=1)  # (n, 2 chains, params)
    flat = halves.reshape(-1, halves.shape[2])
    ranks = np.argsort(np.argsort(flat, axis=0, kind="stable"), axis=0, kind="stable") + 1.0
    z = normal_ppf((ranks - 0.375) / (flat.shape[0] + 0.25)).reshape(halves.shape)
    means = z.mean(axis=0)
    within = z.var(axis=0, ddof=1).mean(axis=0)
    between = n * means.var(axis=0, ddof=1)
    return np.sqrt(((n - 1) / n * within + between / n) / within)


def convergence(chain: np.ndarray, *, min_ess: float, rhat_max: float) -> Convergence:
    """The diagnostics of an emcee chain (iterations, walkers, params)."""
    from emcee.autocorr import integrated_time

    n_iter, walkers, _ = chain.shape
    with np.errstate(invalid="ignore", divide="ignore"):  # a parameter that has not moved: tau NaN
        tau0 = np.nan_to_num(integrated_time(chain, tol=0), nan=np.inf)
        discard = min(int(BURN_TAUS * np.max(tau0)) if np.isfinite(tau0).all() else n_iter // 2, n_iter // 2)
        kept = chain[discard:]
        tau = np.nan_to_num(integrated_time(kept, tol=0), nan=np.inf)
    reliable = bool(kept.shape[0] > TAU_FACTOR * np.max(tau))
    ess = walkers * kept.shape[0] / tau
    rhat = split_rhat(kept) if kept.shape[0] >= 4 else np.full(tau.shape, np.inf)
    converged = reliable and bool(np.all(ess >= min_ess)) and bool(np.all(rhat <= rhat_max))
    return Convergence(tuple(map(float, tau)), tuple(map(float, ess)), tuple(map(float, rhat)), discard, reliable,
                       converged)


__all__ = ["Convergence", "convergence", "split_rhat"]
