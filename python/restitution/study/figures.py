"""The study's figures (2-5) and the inverse map, drawn with matplotlib from sweep frames.

Each function takes frames (and fits) already computed, draws one figure with the rigid-body
theory overlaid, saves it when given a path and returns the matplotlib figure. Colours are
colourblind-safe: viridis (perceptually ordered) for mu, the ColorBrewer RdBu diverging map for
omega_in (spin-free curves in black), the Okabe-Ito palette for categories; line styles tell
simulation (solid), rigid-body theory (black dashed) and the study's fits (grey dash-dot) apart.

Needs the ``plot`` extra (``pip install "restitution[plot]"``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Sequence

import numpy as np
import polars as pl

from . import theory
from .analysis import ExpFit, _curves

#: Okabe-Ito colours (colourblind-safe categorical palette).
OKABE_ITO = ("#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7")

#: The study's fits a exp(-b mu) + c (values and the +- it gives).
STUDY_FITS = {
    "e_kin_min": {"a": (0.22, 0.03), "b": (4.07, 1.39), "c": (0.68, 0.02)},
    "theta_c": {"a": (73.45, 4.58), "b": (5.44, 0.79), "c": (16.26, 2.85)},
}

THETA_LABEL = r"impact angle $\theta$ (deg, from the plate)"
THEORY_STYLE: dict[str, Any] = dict(color="black", lw=0.9, ls=(0, (4, 2)), zorder=5)


def _plt():
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "cairo", "ps"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({"font.size": 10, "axes.titlesize": 11, "axes.labelsize": 10, "legend.fontsize": 8,
                         "axes.grid": True, "grid.alpha": 0.3, "savefig.dpi": 150})
    return plt


def mu_colours(mus: Sequence[float]) -> dict[float, Any]:
    """One viridis colour per mu, 0 -> dark purple, 1 -> yellow-green (the yellow end is cut: it
    vanishes on white)."""
    plt = _plt()
    mus = sorted(set(float(m) for m in mus))
    cmap = plt.get_cmap("viridis")
    top = max(mus) if mus and max(mus) > 0 else 1.0
    return {m: cmap(0.88 * m / top) for m in mus}


def spin_colours(omegas_deg: Sequence[float]) -> dict[float, Any]:
    """RdBu by omega_in (deg/s): backspin (omega > 0) red, forward spin blue, none black; the pale
    middle of the map is skipped so that small spins stay visible."""
    plt = _plt()
    cmap = plt.get_cmap("RdBu")
    vals = sorted(set(float(o) for o in omegas_deg))
    top = max((abs(o) for o in vals), default=1.0) or 1.0
    out = {}
    for o in vals:
        if o == 0.0:
            out[o] = "black"
            continue
        # |o| on a log-ish scale so that 5 and 50 deg/s both read; 0.5 is the pale centre.
        s = 0.18 + 0.32 * np.log1p(abs(o)) / np.log1p(top)
        out[o] = cmap(0.5 - s if o > 0 else 0.5 + s)
    return out


def _label(quantity: str) -> str:
    return {"e_t": "$e_T$", "e_kin": "$e_{kin}$", "e_n": "$e_N$", "omega_out": r"$\omega_{out}$ (rad/s)",
            "beta": r"$\beta$"}.get(quantity, quantity)


def _save(fig, path: Any) -> None:
    if path is not None:
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, bbox_inches="tight")


def _theory_for(part: pl.DataFrame, fn, mu: float, omega_in: float = 0.0, *, r: float, v: float) -> tuple[np.ndarray, np.ndarray]:
    """Rigid-body curve on the part's theta grid, with its measured e_N (finite values only)."""
    th = part["theta_deg"].to_numpy().astype(float)
    en = np.clip(part["e_n"].to_numpy().astype(float), 0.0, 1.0)
    y = fn(th, mu, en, omega_in, r=r, v=v)
    ok = np.isfinite(y)
    return th[ok], y[ok]


def fig2(df: pl.DataFrame, gamma_df: pl.DataFrame | None = None, *, r: float = theory.R_PAPER,
         v: float = theory.V_PAPER, gamma: float | None = None, path: Any = None, title: str | None = None):
    """Fig. 2: e_N, e_T and e_kin against theta for every mu of ``df`` (a sweep over theta_deg
    and mu), with the rigid-body e_T and e_kin (with the measured e_N) dashed; ``gamma_df`` (a
    sweep over theta_deg, mu and gamma) adds the lower/higher damping curves, dotted/dash-dotted."""
    plt = _plt()
    mus = sorted(df["mu"].unique().to_list())
    col = mu_colours(mus)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.6), constrained_layout=True)
    for key, part in _curves(df):
        mu = float(key["mu"])
        th = part["theta_deg"].to_numpy()
        for ax, name in zip(axes, ("e_n", "e_t", "e_kin")):
            ax.plot(th, part[name].to_numpy(), color=col[mu], lw=1.6, label=f"{mu:g}")
        if mu > 0:
            for ax, fn in ((axes[1], theory.e_t), (axes[2], theory.e_kin)):
                tt, yy = _theory_for(part, fn, mu, r=r, v=v)
                ax.plot(tt, yy, **THEORY_STYLE)
    styles = {}
    if gamma_df is not None:
        gammas = sorted(gamma_df["gamma"].unique().to_list())
        lss = [(0, (1, 1.5)), (0, (5, 1.5, 1, 1.5)), (0, (7, 2))]
        for i, g in enumerate(gammas):
            styles[g] = lss[i % len(lss)]
        for key, part in _curves(gamma_df):
            mu, g = float(key["mu"]), float(key["gamma"])
            c = col.get(mu, "grey")
            for ax, name in zip(axes, ("e_n", "e_t", "e_kin")):
                ax.plot(part["theta_deg"].to_numpy(), part[name].to_numpy(), color=c, lw=1.4, ls=styles[g])
    axes[0].set_ylabel(r"normal restitution $e_N$")
    axes[1].set_ylabel(r"tangential restitution $e_T$")
    axes[2].set_ylabel(r"kinematic restitution $e_{kin}$")
    for ax, letter in zip(axes, "abc"):
        ax.set_xlabel(THETA_LABEL)
        ax.set_xlim(0, 90)
        ax.set_title(f"({letter})", loc="left")
    axes[1].set_ylim(0.55, 1.02)
    axes[2].set_ylim(min(0.6, float(df["e_kin"].to_numpy().min()) - 0.02), 1.02)
    # Legends: mu colours in (b); line styles (theory, damping variants) in (c).
    h, lab = axes[1].get_legend_handles_labels()
    seen: dict[str, Any] = {}
    for hh, ll in zip(h, lab):
        seen.setdefault(ll, hh)
    axes[1].legend(seen.values(), seen.keys(), title=r"$\mu$", ncol=2, loc="center right", fontsize=7)
    from matplotlib.lines import Line2D

    extra = [Line2D([], [], **{k: v for k, v in THEORY_STYLE.items() if k != "zorder"},
                    label="rigid body (measured $e_N$)")]
    gtxt = rf"$\gamma$ = {gamma:g} (preset)" if gamma is not None else r"preset $\gamma$"
    extra.insert(0, Line2D([], [], color="grey", lw=1.6, label=f"simulation, {gtxt}"))
    for g, ls in styles.items():
        extra.append(Line2D([], [], color="grey", lw=1.4, ls=ls, label=rf"$\gamma$ = {g:g} ($\mu$ = 0 and 1)"))
    axes[2].legend(handles=extra, loc="lower right", fontsize=7)
    if title:
        fig.suptitle(title)
    _save(fig, path)
    return fig


def fig3(df: pl.DataFrame, crit: pl.DataFrame | None = None, *, r: float = theory.R_PAPER, v: float = theory.V_PAPER,
         path: Any = None, title: str | None = None):
    """Fig. 3: omega_out against theta per mu, rigid body dashed; ``crit`` (from
    :func:`restitution.analysis.critical_angles`) marks theta_c at the peak of |omega_out|."""
    plt = _plt()
    mus = sorted(df["mu"].unique().to_list())
    col = mu_colours(mus)
    fig, ax = plt.subplots(figsize=(7.5, 4.8), constrained_layout=True)
    for key, part in _curves(df):
        mu = float(key["mu"])
        ax.plot(part["theta_deg"].to_numpy(), part["omega_out"].to_numpy(), color=col[mu], lw=1.6, label=f"{mu:g}")
        if mu > 0:
            tt, yy = _theory_for(part, theory.omega_out, mu, r=r, v=v)
            ax.plot(tt, yy, **THEORY_STYLE)
    if crit is not None:
        c = crit.filter(pl.col("theta_c").is_not_null())
        ax.scatter(c["theta_c"].to_numpy(), c["omega_out_max"].to_numpy(), s=28, facecolor="white",
                   edgecolor="black", zorder=6, label=r"$\theta_c$ (peak of $|\omega_{out}|$)")
    ax.plot([], [], **{k: v for k, v in THEORY_STYLE.items() if k != "zorder"}, label="rigid body")
    ax.set_xlabel(THETA_LABEL)
    ax.set_ylabel(r"spin after impact $\omega_{out}$ (rad/s; < 0: forward roll)")
    ax.set_xlim(0, 90)
    ax.legend(title=r"$\mu$", ncol=2, fontsize=7, loc="lower right")
    if title:
        ax.set_title(title)
    _save(fig, path)
    return fig


def fig4(crit: pl.DataFrame, fits: dict[str, ExpFit], *, theory_e_n: float | None = None, path: Any = None,
         title: str | None = None):
    """Fig. 4: theta_c and e_kin,min against mu: simulation points, our fit a exp(-b mu) + c, the
    study's fit and rigid-body theory (with the measured e_N at theta_c, or ``theory_e_n``)."""
    plt = _plt()
    c = crit.filter(pl.col("theta_c").is_not_null()).sort("mu")
    mu = c["mu"].to_numpy().astype(float)
    grid = np.linspace(0.0, max(1.0, float(mu.max())), 300)
    gpos = grid[grid > 0]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
    # (a) theta_c
    ax = axes[0]
    ax.plot(mu, c["theta_c"].to_numpy(), "o", color=OKABE_ITO[5], ms=6, zorder=6,
            label=r"simulation: peak of $|\omega_{out}|$")
    if "theta_e_kin_min" in c.columns:
        ax.plot(mu, c["theta_e_kin_min"].to_numpy(), "s", mfc="none", color=OKABE_ITO[6], ms=6, zorder=6,
                label=r"simulation: minimum of $e_{kin}$")
    f = fits.get("theta_c")
    if f is not None:
        ea, eb, ec = f.errors
        inside = (grid >= f.x_range[0]) & (grid <= f.x_range[1])
        ax.plot(grid[grid <= f.x_range[0]], f(grid[grid <= f.x_range[0]]), color=OKABE_ITO[5], lw=1.2, ls=":")
        ax.plot(grid[inside], f(grid[inside]), color=OKABE_ITO[5], lw=1.5,
                label=rf"fit: {f.a:.1f}$\pm${ea:.1f} exp(-{f.b:.2f}$\pm${eb:.2f} $\mu$) + {f.c:.2f}$\pm${ec:.2f}"
                      + rf" ($\mu \geq$ {f.x_range[0]:g})")
    s = STUDY_FITS["theta_c"]
    ax.plot(grid, s["a"][0] * np.exp(-s["b"][0] * grid) + s["c"][0], color="grey", lw=1.5, ls="-.",
            label="study's fit: 73.45 exp(-5.44 $\\mu$) + 16.26")
    en_c = np.interp(gpos, mu, c["e_n_at_theta_c"].to_numpy()) if theory_e_n is None else theory_e_n
    ax.plot(gpos, theory.theta_c(gpos, en_c), **THEORY_STYLE, label=r"rigid body: $\tan\theta_c = 1 / (3\mu(1+e_N))$")
    ax.set_xlabel(r"friction coefficient $\mu$")
    ax.set_ylabel(r"critical angle $\theta_c$ (deg, from the plate)")
    ax.set_xlim(0, grid[-1])
    ax.set_ylim(0, 92)
    ax.set_title("(a)", loc="left")
    ax.legend(fontsize=7, loc="upper right")
    # (b) e_kin,min
    ax = axes[1]
    ax.plot(mu, c["e_kin_min"].to_numpy(), "o", color=OKABE_ITO[3], ms=6, zorder=6, label="simulation")
    f = fits.get("e_kin_min")
    if f is not None:
        ea, eb, ec = f.errors
        inside = (grid >= f.x_range[0]) & (grid <= f.x_range[1])
        ax.plot(grid[grid <= f.x_range[0]], f(grid[grid <= f.x_range[0]]), color=OKABE_ITO[3], lw=1.2, ls=":")
        ax.plot(grid[inside], f(grid[inside]), color=OKABE_ITO[3], lw=1.5,
                label=rf"fit: {f.a:.3f}$\pm${ea:.3f} exp(-{f.b:.2f}$\pm${eb:.2f} $\mu$) + {f.c:.3f}$\pm${ec:.3f}"
                      + rf" ($\mu \geq$ {f.x_range[0]:g})")
    s = STUDY_FITS["e_kin_min"]
    ax.plot(grid, s["a"][0] * np.exp(-s["b"][0] * grid) + s["c"][0], color="grey", lw=1.5, ls="-.",
            label="study's fit: 0.22 exp(-4.07 $\\mu$) + 0.68")
    ek_th, _ = theory.e_kin_min(gpos, en_c)
    ax.plot(gpos, ek_th, **THEORY_STYLE, label=r"rigid body (measured $e_N$)")
    ax.set_xlabel(r"friction coefficient $\mu$")
    ax.set_ylabel(r"minimal kinematic restitution $e_{kin,min}$")
    ax.set_xlim(0, grid[-1])
    ax.set_title("(b)", loc="left")
    ax.legend(fontsize=7, loc="upper right")
    if title:
        fig.suptitle(title)
    _save(fig, path)
    return fig


def fig5(df: pl.DataFrame, *, r: float = theory.R_PAPER, v: float = theory.V_PAPER, path: Any = None,
         title: str | None = None):
    """Fig. 5: e_T (top: full range; middle: zoom on 0.35 ... 1.1) and e_kin (bottom) against theta
    for every omega_in of ``df`` (a sweep over theta_deg, mu and omega_in in rad/s; shown in
    deg/s), one column per mu, rigid body dashed."""
    plt = _plt()
    mus = sorted(df["mu"].unique().to_list())
    oms = sorted(df["omega_in"].unique().to_list())
    deg = {o: float(np.round(np.degrees(o), 6)) for o in oms}
    col = spin_colours(list(deg.values()))
    fig, axes = plt.subplots(3, len(mus), figsize=(6.2 * len(mus), 11.0), constrained_layout=True, squeeze=False,
                             sharex=True, gridspec_kw={"height_ratios": [1.0, 0.9, 1.0]})
    for j, mu in enumerate(mus):
        sub = df.filter(pl.col("mu") == mu)
        for key, part in _curves(sub):
            o = float(key["omega_in"])
            th = part["theta_deg"].to_numpy()
            c = col[deg[o]]
            lab = f"{deg[o]:+g}" if deg[o] else "0"
            e_t = part["e_t"].to_numpy().astype(float)
            axes[0, j].plot(th, e_t, color=c, lw=1.5, label=lab)
            axes[1, j].plot(th, e_t, color=c, lw=1.5)
            axes[2, j].plot(th, part["e_kin"].to_numpy(), color=c, lw=1.5)
            for i, fn in ((0, theory.e_t), (1, theory.e_t), (2, theory.e_kin)):
                tt, yy = _theory_for(part, fn, mu, o, r=r, v=v)
                axes[i, j].plot(tt, yy, **THEORY_STYLE)
        axes[0, j].set_title(rf"$\mu$ = {mu:g}")
        axes[0, j].set_ylabel(r"tangential restitution $e_T$")
        axes[1, j].set_ylabel(r"$e_T$ (zoom)")
        axes[1, j].set_ylim(0.35, 1.1)
        axes[2, j].set_ylabel(r"kinematic restitution $e_{kin}$")
        axes[2, j].set_xlabel(THETA_LABEL)
        for i in range(2):
            axes[i, j].axhline(1.0, color="grey", lw=0.6)
        axes[0, j].axhline(0.0, color="grey", lw=0.6)
        for i in range(3):
            axes[i, j].set_xlim(0, 90)
    h, lab = axes[0, 0].get_legend_handles_labels()
    h.append(plt.Line2D([], [], **{k: v for k, v in THEORY_STYLE.items() if k != "zorder"}))
    lab.append("rigid body")
    axes[0, 0].legend(h, lab, title=r"$\omega_{in}$ (deg/s)", fontsize=7, loc="upper left", ncol=2)
    for i, ax in enumerate(axes.flat):
        ax.set_title(f"({'abcdefgh'[i]})", loc="left")
    if title:
        fig.suptitle(title)
    _save(fig, path)
    return fig


def inverse_figure(solutions: pl.DataFrame, df: pl.DataFrame | None = None, *, quantity: str = "e_t",
                   value: float | None = None, tol: float = 0.0, path: Any = None, title: str | None = None,
                   reference: dict[float, list[float]] | None = None, r: float = theory.R_PAPER,
                   v: float = theory.V_PAPER):
    """The inverse map: (left, when ``df`` is given) the curves with the band value +- tol and the
    solutions, rigid-body theory thin dashed; (right) the solutions as theta against omega_in
    (deg/s), one marker per mu, with the tolerance as a horizontal bar. ``reference`` ({omega_in deg/s: [theta, ...]}) adds the
    study's quoted angles as crosses."""
    plt = _plt()
    ncols = 2 if df is not None else 1
    fig, axes = plt.subplots(1, ncols, figsize=(6.3 * ncols, 4.8), constrained_layout=True, squeeze=False)
    axes = axes[0]
    has_spin = "omega_in" in solutions.columns
    has_mu = "mu" in solutions.columns
    if df is not None:
        ax = axes[0]
        sub = df
        if has_mu and "mu" in df.columns:
            mu0 = min(df["mu"].unique().to_list())
            sub = df.filter(pl.col("mu") == mu0)
            ax.set_title(rf"$\mu$ = {mu0:g}: {_label(quantity)} against $\theta$; circles: {_label(quantity)} = {value:g}",
                         fontsize=10)
        if "omega_in" in sub.columns:
            oms = sorted(sub["omega_in"].unique().to_list())
            col = spin_colours([float(np.round(np.degrees(o), 6)) for o in oms])
        for key, part in _curves(sub):
            o = float(np.round(np.degrees(key.get("omega_in", 0.0)), 6))
            c = col[o] if "omega_in" in sub.columns else OKABE_ITO[5]
            ax.plot(part["theta_deg"].to_numpy(), part[quantity].to_numpy().astype(float), color=c, lw=1.3,
                    label=f"{o:+g}" if o else "0")
            fn = {"e_t": theory.e_t, "e_kin": theory.e_kin, "omega_out": theory.omega_out}.get(quantity)
            if fn is not None and "mu" in key and "e_n" in part.columns:
                tt, yy = _theory_for(part, fn, float(key["mu"]), float(key.get("omega_in", 0.0)), r=r, v=v)
                ax.plot(tt, yy, **{**THEORY_STYLE, "lw": 0.7})
        if value is not None:
            ax.axhspan(value - tol, value + tol, color=OKABE_ITO[1], alpha=0.35, lw=0)
            ax.axhline(value, color=OKABE_ITO[1], lw=1.0)
        s = solutions.filter(pl.col("mu") == mu0) if has_mu and "mu" in df.columns else solutions
        ax.plot(s["theta_deg"].to_numpy(), np.full(s.height, value if value is not None else np.nan), "o",
                mfc="white", mec="black", ms=6, zorder=6)
        ax.set_xlabel(THETA_LABEL)
        ax.set_ylabel(_label(quantity))
        ax.set_xlim(0, 90)
        if value is not None:
            ax.set_ylim(value - 0.6, value + 0.8)
        h, lab = ax.get_legend_handles_labels()
        h.append(plt.Line2D([], [], **{k: v_ for k, v_ in THEORY_STYLE.items() if k != "zorder"}))
        lab.append("rigid body")
        ax.legend(h, lab, title=r"$\omega_{in}$ (deg/s)", fontsize=7, ncol=2, loc="lower left")
    ax = axes[-1]
    mus = sorted(solutions["mu"].unique().to_list()) if has_mu else [None]
    markers = ["o", "s", "^", "D", "v"]
    for k, mu in enumerate(mus):
        s = solutions.filter(pl.col("mu") == mu) if mu is not None else solutions
        y = np.degrees(s["omega_in"].to_numpy()) if has_spin else np.zeros(s.height)
        x = s["theta_deg"].to_numpy()
        err = np.vstack([x - s["theta_lo"].to_numpy(), s["theta_hi"].to_numpy() - x])
        # Offset the mu series vertically a little so that coincident solutions stay visible.
        dy = (k - (len(mus) - 1) / 2) * 1.2
        ax.errorbar(x, y + dy, xerr=err, fmt=markers[k % len(markers)], color=OKABE_ITO[(5, 6, 3, 7, 1)[k % 5]],
                    mfc="white" if k else None, ms=6, capsize=2, lw=1,
                    label=(rf"$\mu$ = {mu:g}" if mu is not None else "solutions"))
    if reference:
        first = True
        for o, ths in reference.items():
            for t in ths:
                ax.plot(t, o, "x", color="black", ms=8, mew=1.5, zorder=7, label="study (quoted)" if first else None)
                first = False
    ax.set_xlabel(THETA_LABEL)
    ax.set_ylabel(r"spin before impact $\omega_{in}$ (deg/s)" if has_spin else "")
    ax.set_xlim(0, 90)
    ttl = f"every impact with {_label(quantity)} = {value:g}" + (f" $\\pm$ {tol:g}" if tol else "") if value is not None else ""
    ax.set_title(ttl + "\n(bars: angles within the tolerance)", fontsize=10)
    ax.legend(fontsize=8, loc="center left")
    if title:
        fig.suptitle(title)
    _save(fig, path)
    return fig


__all__ = ["OKABE_ITO", "STUDY_FITS", "fig2", "fig3", "fig4", "fig5", "inverse_figure", "mu_colours", "spin_colours"]
