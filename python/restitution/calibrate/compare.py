"""Which model: contact models (or tangential histories) ranked on the same data by WAIC.

The criterion is the expected log predictive density of a new measurement, estimated by the
widely applicable information criterion from each point's log-likelihood under the posterior
draws (Watanabe 2010; Vehtari, Gelman & Gabry 2017, "Practical Bayesian model evaluation using
leave-one-out cross-validation and WAIC", Statistics and Computing 27:1413):

    elpd_i = log mean_s p(y_i | theta_s) - var_s log p(y_i | theta_s),   elpd = sum_i elpd_i,

with standard error sqrt(N var_i elpd_i); the difference of two models is summed pointwise, so
its standard error sqrt(N var_i (elpd_i^A - elpd_i^B)) accounts for their correlation.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np
import polars as pl

from ..errors import RestitutionError
from ..scene import Scene
from .sampler import fit

#: A point whose WAIC penalty exceeds this makes the estimate unreliable (Vehtari et al. 2017).
P_WAIC_WARN = 0.4


def waic_pointwise(log_lik: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(elpd_i, p_i) of each data point from log-likelihoods (draws, points)."""
    top = log_lik.max(axis=0)
    lppd = top + np.log(np.mean(np.exp(log_lik - top), axis=0))
    penalty = log_lik.var(axis=0, ddof=1)
    return lppd - penalty, penalty


def compare(scenes: Mapping[str, Scene], data: pl.DataFrame, free: Mapping[str, Any], **fit_options: Any
            ) -> pl.DataFrame:
    """Fits each scene to ``data`` (same ``free`` priors, same options as :func:`fit`) and ranks
    them by WAIC's expected log predictive density, best first.

    Returns
    -------
    polars.DataFrame
        model, elpd_waic (higher is better), se, p_waic (effective number of parameters),
        d_elpd (the best's elpd minus this one's, >= 0) with its standard error d_se, rank,
        converged, and ``warning`` (points whose WAIC penalty exceeds 0.4, where the estimate is
        unreliable). A d_elpd within about 2 d_se of 0: the data do not tell the models apart;
        prefer the simpler one.
    """
    if not isinstance(scenes, Mapping) or len(scenes) < 2:
        raise RestitutionError("scenes", repr(scenes)[:80], "a dict of at least two name -> Scene")
    pointwise, meta = {}, {}
    for name, scene in scenes.items():
        post = fit(scene, data, free, **fit_options)
        elpd_i, p_i = waic_pointwise(post.pointwise_log_lik())
        pointwise[name] = elpd_i
        meta[name] = (float(p_i.sum()), bool(post.converged), int(np.sum(p_i > P_WAIC_WARN)))
    best = max(pointwise, key=lambda k: pointwise[k].sum())
    n = len(pointwise[best])
    rows = []
    for name, elpd_i in pointwise.items():
        diff = pointwise[best] - elpd_i
        rows.append({"model": name, "elpd_waic": float(elpd_i.sum()), "se": math.sqrt(n * elpd_i.var(ddof=1)),
                     "p_waic": meta[name][0], "d_elpd": float(diff.sum()),
                     "d_se": math.sqrt(n * diff.var(ddof=1)) if name != best else 0.0,
                     "converged": meta[name][1],
                     "warning": f"p_waic > {P_WAIC_WARN} at {meta[name][2]} of {n} points" if meta[name][2] else ""})
    out = pl.DataFrame(rows).sort("elpd_waic", descending=True)
    return out.with_columns(pl.int_range(1, out.height + 1).alias("rank")).select(
        "rank", "model", "elpd_waic", "se", "p_waic", "d_elpd", "d_se", "converged", "warning")


__all__ = ["compare", "waic_pointwise"]
