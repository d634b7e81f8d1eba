"""What a fit returns: the samples and what one asks of them (summary, prediction, check, plots)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np
import polars as pl

from ..errors import RestitutionError
from ..study.figures import _plt
from . import _forward
from .diagnostics import Convergence

if TYPE_CHECKING:
    from .problem import Problem

#: Posterior draws used for predictions and the check (evenly spaced through the samples).
PREDICT_DRAWS = 400


@dataclass(frozen=True)
class Posterior:
    """The posterior of a :func:`restitution.calibrate.fit`.

    Attributes
    ----------
    samples : polars.DataFrame
        One column per free field plus ``log_prob``, one row per kept draw (burn-in dropped).
    convergence : Convergence
        tau, ESS and R-hat per free field, the burn-in dropped, whether every test passed.
    stopped : str
        "converged", "max_iter" or "interrupted".
    tol : float or None
        The adaptive path's accuracy the fit ran at (``problem.tol``).
    """

    problem: Problem
    samples: pl.DataFrame
    convergence: Convergence
    stopped: str
    iterations: int
    walkers: int
    impacts: int
    seconds: float
    seed: int
    _cache: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @property
    def names(self) -> list[str]:
        return self.problem.names

    @property
    def tol(self) -> float | None:
        return self.problem.tol

    @property
    def converged(self) -> bool:
        return self.convergence.converged

    def summary(self) -> pl.DataFrame:
        """One row per free field: mean, sd, q05, q50, q95, ess, rhat, tau, converged (all
        fields together: the chain passed or did not)."""
        rows = []
        for k, name in enumerate(self.names):
            x = self.samples[name].to_numpy()
            q05, q50, q95 = np.quantile(x, [0.05, 0.5, 0.95])
            rows.append({"parameter": name, "mean": float(x.mean()), "sd": float(x.std(ddof=1)), "q05": float(q05),
                         "q50": float(q50), "q95": float(q95), "ess": self.convergence.ess[k],
                         "rhat": self.convergence.rhat[k], "tau": self.convergence.tau[k],
                         "converged": self.converged})
        return pl.DataFrame(rows)

    def draws(self, n: int = PREDICT_DRAWS) -> np.ndarray:
        """``n`` draws evenly spaced through the samples: (n, free fields)."""
        rows = np.unique(np.linspace(0, self.samples.height - 1, min(n, self.samples.height)).astype(np.int64))
        return self.samples.select(self.names).to_numpy()[rows]

    def model_at_data(self, n: int = PREDICT_DRAWS) -> np.ndarray:
        """The model at every data row for ``n`` posterior draws: (n, rows), cached."""
        key = f"model{n}"
        if key not in self._cache:
            self._cache[key] = self.problem.model(self.draws(n))
        return self._cache[key]

    def pointwise_log_lik(self, n: int = 1000) -> np.ndarray:
        """log L of each data row under ``n`` posterior draws: (n, rows) (for WAIC)."""
        return self.problem.pointwise_log_lik(self.model_at_data(n))

    def predict(self, *, theta_deg: Any, omega_in: Any = 0.0, quantities: Sequence[str] | None = None,
                draws: int = PREDICT_DRAWS) -> pl.DataFrame:
        """The model's posterior quantiles at the points (theta_deg x omega_in): one row per
        point and quantity with mean, q05, q50, q95 over ``draws`` posterior draws (the spread
        of the model given the data, without the measurement noise of a new point).

        ``quantities``: default, those of the data.
        """
        qs = list(quantities) if quantities is not None else list(dict.fromkeys(self.problem.data["quantity"]))
        th, om = (np.atleast_1d(np.asarray(a, dtype=float)) for a in (theta_deg, omega_in))
        points = pl.DataFrame({"theta_deg": np.repeat(th, om.size), "omega_in": np.tile(om, th.size)})
        theta = self.draws(draws)
        pred = _forward.predict(self.problem.scene, {n: theta[:, k] for k, n in enumerate(self.names)}, points, qs,
                                tol=self.tol)
        frames = []
        for q in qs:
            with np.errstate(all="ignore"):
                qv = np.nanquantile(pred[q], [0.05, 0.5, 0.95], axis=0) if np.isfinite(pred[q]).any() else \
                    np.full((3, points.height), np.nan)
                mean = np.nanmean(pred[q], axis=0) if np.isfinite(pred[q]).any() else np.full(points.height, np.nan)
            frames.append(points.with_columns(pl.lit(q).alias("quantity"), pl.Series("mean", mean),
                                              pl.Series("q05", qv[0]), pl.Series("q50", qv[1]),
                                              pl.Series("q95", qv[2])))
        return pl.concat(frames)

    def check(self) -> pl.DataFrame:
        """The posterior predictive check, per data row: the model's posterior mean and sd there
        and z = (value - mean) / sqrt(sigma^2 + sd^2); :attr:`p_value` is the overall one."""
        model = self.model_at_data()
        data = self.problem.data
        with np.errstate(all="ignore"):
            mean, sd = np.nanmean(model, axis=0), np.nanstd(model, axis=0)
        z = (data["value"].to_numpy() - mean) / np.sqrt(data["sigma"].to_numpy() ** 2 + sd**2)
        return data.with_columns(pl.Series("model_mean", mean), pl.Series("model_sd", sd), pl.Series("z", z))

    @property
    def p_value(self) -> float:
        """Posterior predictive p-value of the chi-square discrepancy T = sum ((y - m) / sigma)^2:
        the share of posterior draws m whose replicated data (m plus noise from the likelihood)
        are at least as discrepant as the measured ones. Near 0: the model cannot explain the
        data within their sigma (Gelman, Meng & Stern 1996)."""
        if "p_value" not in self._cache:
            self._cache["p_value"] = self._p_value()
        return self._cache["p_value"]

    def _p_value(self) -> float:
        model = self.model_at_data()
        data = self.problem.data
        y, sigma = data["value"].to_numpy(), data["sigma"].to_numpy()
        rng = np.random.default_rng(self.seed)
        if self.problem.likelihood == "gaussian":
            noise = rng.standard_normal(model.shape)
        else:
            noise = rng.standard_t(self.problem.df, model.shape)
        t_obs = np.sum(((y - model) / sigma) ** 2, axis=1)
        t_rep = np.sum(noise**2, axis=1)  # ((m + sigma e - m) / sigma)^2
        ok = np.isfinite(t_obs)
        if not ok.any():
            raise RestitutionError("data", "undefined model values", "quantities the model defines at every point")
        return float(np.mean(np.where(ok, t_rep >= t_obs, False)))

    def plot_fit(self, **kwargs: Any) -> Any:
        """The data with error bars over the model's 5-95 % posterior ribbon and median: one
        panel per quantity (a matplotlib Figure)."""
        return plot_fit(self, **kwargs)

    def plot_corner(self, **kwargs: Any) -> Any:
        """Each free field's histogram and each pair's joint scatter (a matplotlib Figure)."""
        return plot_corner(self, **kwargs)


# A posterior's figures: the fit over the data, and the corner plot (matplotlib, no other
# dependency).

#: Angles of the predictive ribbon across the data's range.
RIBBON_ANGLES = 40


def plot_fit(post: Posterior, *, draws: int = 200) -> Any:
    """The data (error bars: one sigma) over the model's 5-95 % posterior ribbon and median
    against theta_deg, one panel per quantity, one ribbon per incoming spin of the data."""
    plt = _plt()
    data = post.problem.data
    quantities = list(dict.fromkeys(data["quantity"]))
    fig, axes = plt.subplots(1, len(quantities), figsize=(4.5 * len(quantities), 3.6), squeeze=False)
    angles = data["theta_deg"].to_numpy()
    lo, hi = float(angles.min()), float(angles.max())
    grid = np.linspace(lo, hi, RIBBON_ANGLES)
    spins = data["omega_in"].unique(maintain_order=True).to_list()
    pred = post.predict(theta_deg=grid, omega_in=spins, draws=draws)
    for ax, q in zip(axes[0], quantities):
        for k, om in enumerate(spins):
            colour = f"C{k}"
            band = pred.filter((pl.col("quantity") == q) & (pl.col("omega_in") == om)).sort("theta_deg")
            ax.fill_between(band["theta_deg"], band["q05"], band["q95"], color=colour, alpha=0.25, lw=0)
            ax.plot(band["theta_deg"], band["q50"], color=colour, lw=1.2,
                    label=f"model, omega_in = {om:g}" if len(spins) > 1 else "model (median, 5-95 %)")
            pts = data.filter((pl.col("quantity") == q) & (pl.col("omega_in") == om))
            ax.errorbar(pts["theta_deg"], pts["value"], yerr=pts["sigma"], fmt="o", ms=3.5, color=colour,
                        ecolor="k", elinewidth=0.8, capsize=2, label="data" if k == 0 else None)
        ax.set_xlabel("theta (deg, from the plate)")
        ax.set_ylabel(q)
        ax.legend()
    fig.suptitle(f"posterior predictive ({post.problem.likelihood}; p = {post.p_value:.3f})")
    fig.tight_layout()
    return fig


def plot_corner(post: Posterior, *, bins: int = 30) -> Any:
    """Each free field's marginal histogram (diagonal) and each pair's joint draws (below)."""
    plt = _plt()
    names = post.names
    d = len(names)
    x = post.samples.select(names).to_numpy()
    fig, axes = plt.subplots(d, d, figsize=(2.4 * d + 0.6, 2.4 * d + 0.6), squeeze=False)
    for i in range(d):
        for j in range(d):
            ax = axes[i][j]
            if j > i:
                ax.set_visible(False)
                continue
            if i == j:
                ax.hist(x[:, i], bins=bins, color="C0", alpha=0.8)
                for q in np.quantile(x[:, i], [0.05, 0.5, 0.95]):
                    ax.axvline(q, color="k", lw=0.8, ls="--")
                ax.set_yticks([])
            else:
                ax.hist2d(x[:, j], x[:, i], bins=bins, cmap="Blues")
            if i == d - 1:
                ax.set_xlabel(names[j])
            if j == 0 and i > 0:
                ax.set_ylabel(names[i])
    fig.tight_layout()
    return fig


__all__ = ["plot_corner", "plot_fit"]


__all__ = ["Posterior"]
