"""A calibration problem, checked: the scene, the measured data, the free fields' priors and the
likelihood; the model's value at every data row and the log-likelihood of each row (what the
sampler, the posterior and the comparison read)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import polars as pl

from ..runs.distributions import Distribution
from ..scene import Scene
from . import _forward


@dataclass(frozen=True)
class Problem:
    """A checked calibration problem: the scene, the data, the priors and the likelihood."""

    scene: Scene
    data: pl.DataFrame
    free: dict[str, Distribution]
    likelihood: str
    df: float
    tol: float | None

    @property
    def names(self) -> list[str]:
        return list(self.free)

    @cached_property
    def layout(self) -> tuple[pl.DataFrame, np.ndarray, list[str], np.ndarray]:
        """(the distinct points, each row's point index, the quantities, each row's quantity index)."""
        keys = self.data.select("theta_deg", "omega_in")
        points = keys.unique(maintain_order=True)
        index = {k: i for i, k in enumerate(points.iter_rows())}
        quantities = list(dict.fromkeys(self.data["quantity"].to_list()))
        return (points, np.array([index[k] for k in keys.iter_rows()]), quantities,
                np.array([quantities.index(q) for q in self.data["quantity"]]))

    def model(self, theta: np.ndarray) -> np.ndarray:
        """The model's value at every data row for each parameter set: (S, N)."""
        points, p_idx, quantities, q_idx = self.layout
        params = {name: theta[:, k] for k, name in enumerate(self.names)}
        pred = _forward.predict(self.scene, params, points, quantities, tol=self.tol)
        stack = np.stack([pred[q] for q in quantities])  # (Q, S, P)
        return stack[q_idx, :, p_idx].T

    def pointwise_log_lik(self, model: np.ndarray) -> np.ndarray:
        """log L of each data row under each model row: (S, N); -inf where the model is NaN."""
        y = self.data["value"].to_numpy()
        sigma = self.data["sigma"].to_numpy()
        r = (y - model) / sigma
        if self.likelihood == "gaussian":
            ll = -0.5 * r * r - np.log(sigma) - 0.5 * math.log(2.0 * math.pi)
        else:
            nu = self.df
            c = math.lgamma((nu + 1) / 2) - math.lgamma(nu / 2) - 0.5 * math.log(nu * math.pi)
            ll = c - np.log(sigma) - (nu + 1) / 2 * np.log1p(r * r / nu)
        return np.where(np.isnan(ll), -np.inf, ll)

    def log_prior(self, theta: np.ndarray) -> np.ndarray:
        return np.sum([d.logpdf(theta[:, k]) for k, d in enumerate(self.free.values())], axis=0)


__all__ = ["Problem"]
