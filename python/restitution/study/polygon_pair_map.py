"""The negative-e_N map of two polygons at random orientations (docs/model.md, 17.7): for
two hexagons (and a hexagon on a pentagon), under the area law, elastic and damped, with and
without friction, e_n (first-touch normal: the line of centres) and e_n_sep against theta, over
orientations drawn uniformly for both bodies. Corners make e_n a distribution at each angle:
the table gives its quantiles and the fraction of draws with e_n < 0, and the report the angle
below which half the draws are negative, beside the two discs' threshold of the same
circumradius (`pair_map`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import polars as pl

from ..scene import Scene
from ..shapes import RegularPolygon
from ..simulate import simulate

#: The impact angles (degrees) and orientation draws per angle.
ANGLES = np.geomspace(0.2, 45.0, 24)
DRAWS = 48
#: Relative speed (m/s) and circumradius (m): the discs' map's.
SPEED, RADIUS = 1.0, 0.01


def cases() -> list[tuple[str, Scene, int, int]]:
    """(label, scene, n of the particle, n of the partner): the area law (the linear law's
    vertex springs run on Gear-5 too, but measure corner-on-corner depths to the other body's
    edges), elastic or damped, mu 0 or 0.5; Gear-5 at its default step."""
    base = Scene(shape=RegularPolygon(RADIUS, 6), partner=RegularPolygon(RADIUS, 6), v=SPEED, integrator="gear5")
    out = []
    for mu in (0.0, 0.5):
        out += [(f"6+6 area elastic mu {mu:g}", base.replace(gamma=0.0, gamma_t=0.0, mu=mu), 6, 6),
                (f"6+6 area damped mu {mu:g}", base.replace(mu=mu), 6, 6)]
    out.append(("6+5 area damped mu 0.5", base.replace(mu=0.5), 6, 5))
    return out


def polygon_map(angles: np.ndarray = ANGLES, draws: int = DRAWS, seed: int = 28) -> pl.DataFrame:
    """One row per case, angle and draw: the orientations and the record's e_n, e_n_sep."""
    rng = np.random.default_rng(seed)
    rows = []
    for label, scene, n1, n2 in cases():
        for theta in angles:
            for phi1, phi2 in rng.uniform(0.0, 360.0, size=(draws, 2)):
                s = scene.replace(shape=RegularPolygon(RADIUS, n1, float(phi1)),
                                  partner=RegularPolygon(RADIUS, n2, float(phi2)))
                r = simulate(s, float(theta))
                rows.append((label, float(theta), float(phi1), float(phi2), r.e_n, r.e_n_sep, r.e_kin))
    return pl.DataFrame(rows, schema=["case", "theta_deg", "phi1_deg", "phi2_deg", "e_n", "e_n_sep", "e_kin"],
                        orient="row")


def summary(df: pl.DataFrame) -> pl.DataFrame:
    """Per case and angle: e_n's 5, 50 and 95 % quantiles, e_n_sep's median and the fraction of
    draws with e_n < 0."""
    return (df.group_by("case", "theta_deg")
            .agg(pl.col("e_n").quantile(0.05).alias("e_n_q05"), pl.col("e_n").median().alias("e_n_median"),
                 pl.col("e_n").quantile(0.95).alias("e_n_q95"), pl.col("e_n_sep").median().alias("e_n_sep_median"),
                 (pl.col("e_n") < 0.0).mean().alias("p_negative"), pl.len().alias("draws"))
            .sort("case", "theta_deg"))


def half_negative_angle(sub: pl.DataFrame) -> float:
    """The largest angle below which at least half the draws have e_n < 0 (interpolated in log
    theta); NaN where no angle has."""
    theta = sub["theta_deg"].to_numpy()
    p = sub["p_negative"].to_numpy()
    below = np.nonzero(p >= 0.5)[0]
    if below.size == 0:
        return float("nan")
    k = below[-1]
    if k + 1 >= theta.size:
        return float(theta[k])
    f = (p[k] - 0.5) / (p[k] - p[k + 1])
    return float(np.exp(np.log(theta[k]) + f * (np.log(theta[k + 1]) - np.log(theta[k]))))


def figure(stats: pl.DataFrame, path: Path) -> None:
    """e_n's median and 5-95 % band, e_n_sep's median and P(e_n < 0) against theta per case."""
    from .figures import _plt

    plt = _plt()
    labels = [c[0] for c in cases()]
    fig, axes = plt.subplots(1, len(labels), figsize=(4 * len(labels), 4), sharey=True)
    for ax, label in zip(axes, labels):
        sub = stats.filter(pl.col("case") == label)
        ax.fill_between(sub["theta_deg"], sub["e_n_q05"], sub["e_n_q95"], alpha=0.3, label=r"$e_n$ 5-95 %")
        ax.plot(sub["theta_deg"], sub["e_n_median"], label=r"$e_n$ median")
        ax.plot(sub["theta_deg"], sub["e_n_sep_median"], "--", label=r"$e_{n,sep}$ median")
        ax.plot(sub["theta_deg"], sub["p_negative"], ":", color="k", label=r"P($e_n$ < 0)")
        ax.axhline(0.0, color="0.6", lw=0.5)
        # At grazing incidence a corner turns tangential motion into normal: e_n's upper
        # quantiles reach tens (the report gives them); the axis shows the sign change.
        ax.set(xscale="log", title=label, xlabel=r"$\theta$ (deg, from the tangent)", ylim=(-1.2, 2.5))
    axes[0].set_ylabel(r"$e_n$, $e_{n,sep}$, P($e_n$ < 0)")
    axes[0].legend(fontsize=7)
    fig.suptitle(f"Two polygons at random orientations, v = {SPEED:g} m/s")
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)


def report(stats: pl.DataFrame) -> str:
    """The half-negative angles in a table (markdown)."""
    lines = ["", "# Negative e_N: two polygons at random orientations", "",
             f"Regular polygons of circumradius {RADIUS} m (rho 2500, E 1e7 Pa), area law, at v = {SPEED:g} m/s, "
             f"Gear-5 at its default step; {DRAWS} orientation draws per angle (both bodies uniform on [0, 360) deg). "
             "e_n uses the line of centres at first touch. theta_half: the largest angle below which at least half "
             "the draws have e_n < 0.", "",
             "| case | theta_half (deg) | P(e_n<0), e_n 95 % at the smallest angle | median e_n at 45 deg |",
             "|---|---|---|---|"]
    for label, *_ in cases():
        sub = stats.filter(pl.col("case") == label)
        lines.append(f"| {label} | {half_negative_angle(sub):.3g} | {sub['p_negative'][0]:.2f}, "
                     f"{sub['e_n_q95'][0]:.3g} | {sub['e_n_median'][-1]:.3f} |")
    lines += ["", "At grazing incidence a corner turns tangential motion into normal: e_n (normal velocity out "
              "over normal velocity in) reaches tens in the upper quantiles; the figure's axis is clipped."]
    return "\n".join(lines) + "\n"


def write_polygon_map(out: Path, angles: np.ndarray = ANGLES, draws: int = DRAWS) -> tuple[list[Path], str]:
    """The polygons' draws, their summary and figure in ``out``; the paths and the report."""
    out.mkdir(parents=True, exist_ok=True)
    df = polygon_map(angles, draws)
    stats = summary(df)
    paths = [out / "negative_e_n_polygons.parquet", out / "negative_e_n_polygons_summary.parquet",
             out / "negative_e_n_polygons.png"]
    df.write_parquet(paths[0])
    stats.write_parquet(paths[1])
    figure(stats, paths[2])
    return paths, report(stats)
