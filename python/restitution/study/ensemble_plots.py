"""Figures of ensembles: quantile ribbons against an axis, and histograms at chosen points.

Needs the ``plot`` extra (``pip install "restitution[plot]"``); called through
:meth:`restitution.study.ensemble.Ensemble.plot_quantiles` and ``plot_histograms``.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import polars as pl

from .figures import OKABE_ITO, THETA_LABEL, _label, _plt, _save

_LABELS = {"theta_deg": THETA_LABEL}


def quantile_ribbons(summary: pl.DataFrame, quantities: list[str], *, x: str, group: list[str],
                     path: Any = None, title: str | None = None) -> Any:
    """One panel per quantity: the median against ``x``, 25-75 % (dark) and 5-95 % (light)
    ribbons, one colour per combination of the ``group`` columns; ``title`` above them (None:
    what the figure shows, in words)."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(quantities), figsize=(4.2 * len(quantities), 3.6), squeeze=False)
    curves = summary.partition_by(group, maintain_order=True) if group else [summary]
    for ax, q in zip(axes[0], quantities):
        for k, curve in enumerate(curves):
            part = curve.filter(pl.col("quantity") == q).sort(x)
            if part.height == 0:
                continue
            colour = OKABE_ITO[(k + 1) % len(OKABE_ITO)] if group else OKABE_ITO[5]
            xs = part[x].to_numpy()
            ax.fill_between(xs, _col(part, "q05"), _col(part, "q95"), color=colour, alpha=0.18, lw=0)
            ax.fill_between(xs, _col(part, "q25"), _col(part, "q75"), color=colour, alpha=0.38, lw=0)
            label = ", ".join(f"{g} = {curve[g][0]}" for g in group) if group else "median"
            ax.plot(xs, _col(part, "q50"), color=colour, lw=1.3, label=label)
        ax.set_xlabel(_LABELS.get(x, x))
        ax.set_ylabel(_label(q))
    axes[0][0].legend(title="median; 25-75 %, 5-95 %", loc="best")
    fig.suptitle(title if title is not None else f"Ensemble: median and quantiles against {_LABELS.get(x, x)}")
    fig.tight_layout()
    _save(fig, path)
    return fig


def _col(part: pl.DataFrame, name: str) -> np.ndarray:
    return part[name].cast(pl.Float64).fill_null(np.nan).to_numpy()


def histograms(frame: pl.DataFrame, quantity: str, *, x: str | None, at: Sequence[float] | None, bins: int,
               path: Any = None) -> Any:
    """Densities of ``quantity`` at up to six values of ``x`` (all draws when ``x`` is None)."""
    plt = _plt()
    frame = frame.filter(~pl.col("timed_out").fill_null(False) & pl.col(quantity).is_not_null())
    if x is None:
        panels = [("all draws", frame)]
    else:
        values = np.unique(frame[x].to_numpy())
        chosen = (values[np.unique(np.linspace(0, len(values) - 1, min(6, len(values))).round().astype(int))]
                  if at is None else [values[np.argmin(np.abs(values - a))] for a in at][:6])
        panels = [(f"{x} = {v:g}", frame.filter(pl.col(x) == v)) for v in chosen]
    cols = min(3, len(panels))
    rows = -(-len(panels) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.8 * cols, 3.0 * rows), squeeze=False)
    for ax, (title, part) in zip(axes.ravel(), panels):
        ax.hist(part[quantity].to_numpy(), bins=bins, density=True, color=OKABE_ITO[5], alpha=0.8)
        ax.set_title(f"{title} ({part.height} draws)")
        ax.set_xlabel(_label(quantity))
        ax.set_ylabel("density")
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    fig.tight_layout()
    _save(fig, path)
    return fig


__all__ = ["histograms", "quantile_ribbons"]
