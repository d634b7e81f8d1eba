"""A posterior's figures: the fit over the data, and the corner plot (matplotlib, no other
dependency)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import polars as pl

from ..study.figures import _plt

if TYPE_CHECKING:
    from .posterior import Posterior

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
