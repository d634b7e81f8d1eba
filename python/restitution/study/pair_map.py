"""The negative-e_N map (docs/model.md, 17.7): e_n (first-touch normal) and e_n_sep against theta
for two discs, under the area and the linear law, elastic and damped, with and without
friction; where e_n turns negative, measured, against the criterion of Müller, Krengel &
Pöschel (2012).

Their argument: while two particles are in contact the line of their centres turns, by about
the angle dpsi the tangential relative motion sweeps around the pair in the contact time,
|dpsi| ~ v cos(theta) t_c / (r1 + r2) (the normal motion a head-on collision at v sin(theta)),
and e_n with the first-touch normal is negative once the pair turns by more than the impact
angle allows. Our identity for frictionless central forces (17.4) makes that exact:
e_n < 0 iff tan|dpsi| > e_n_sep tan(theta). The criterion's estimate of dpsi uses the head-on
contact time t_c and restitution e_N at the normal speed: for the linear law their closed forms,
for the area law the engine's head-on impacts. The threshold angle theta* where e_n changes sign
is compared with the one the estimate predicts.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import polars as pl

from ..runs.sweep import sweep
from ..scene import Scene
from ..shapes import Disc

#: The impact angles of the map (degrees): log-spaced, where the sign changes.
ANGLES = np.geomspace(0.05, 45.0, 70)
#: The relative speed of the map (m/s) and the discs' radius (m): the preset discs.
SPEED, RADIUS = 1.0, 0.01
#: The linear law's damping ratio of the damped cases: e_N = exp(-pi zeta / sqrt(1 - zeta^2)) = 0.9.
ZETA = -math.log(0.9) / math.sqrt(math.pi**2 + math.log(0.9) ** 2)


def cases() -> list[tuple[str, Scene]]:
    """(label, scene) of the map: two preset discs, area or linear law (k_n = E), elastic or
    damped to e_N ~ 0.9 head-on, mu 0 or 0.5."""
    base = Scene(partner=Disc(RADIUS), v=SPEED, integrator="gear5")
    m_star = 0.5 * base.rho * math.pi * RADIUS**2
    kn = base.E
    # Per body kn, cn; in series k* = kn / 2, c* = cn / 2, and zeta = c* / (2 sqrt(k* m*)).
    cn = 4.0 * ZETA * math.sqrt(0.5 * kn * m_star)
    out = []
    for mu in (0.0, 0.5):
        out += [(f"area elastic mu {mu:g}", base.replace(gamma=0.0, gamma_t=0.0, mu=mu)),
                (f"area damped mu {mu:g}", base.replace(mu=mu)),
                (f"linear elastic mu {mu:g}", base.replace(normal_law="linear", kn=kn, cn=0.0, gamma_t=0.0, mu=mu)),
                (f"linear damped mu {mu:g}", base.replace(normal_law="linear", kn=kn, cn=cn, mu=mu))]
    return out


def negative_e_n_map(angles: np.ndarray = ANGLES) -> pl.DataFrame:
    """e_n, e_n_sep and the normal's turn per case and angle (Gear-5 at its default step)."""
    frames = []
    for label, scene in cases():
        df = sweep(scene, theta_deg=angles, progress=False)
        frames.append(df.select(pl.lit(label).alias("case"), "theta_deg", "e_n", "e_n_sep", "normal_rotation_deg",
                                "contact_time"))
    return pl.concat(frames)


def _sign_change(theta: np.ndarray, e_n: np.ndarray) -> float:
    """The largest angle below which e_n < 0 (interpolated in log theta); NaN where it never is."""
    neg = np.flatnonzero(e_n < 0.0)
    if neg.size == 0:
        return float("nan")
    i = neg[-1]
    if i + 1 >= theta.size:
        return float(theta[-1])
    t0, t1 = math.log(theta[i]), math.log(theta[i + 1])
    f = e_n[i] / (e_n[i] - e_n[i + 1])
    return math.exp(t0 + f * (t1 - t0))


def head_on(scene: Scene, v_n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(t_c, e_N) of the head-on collision at normal speeds ``v_n``: closed forms for the linear
    law (the unclipped dashpot: t_c = pi / omega_d, e_N = exp(-pi zeta / sqrt(1 - zeta^2))), the
    engine's head-on impacts for the area law."""
    if scene.normal_law == "linear":
        assert scene.kn is not None and scene.cn is not None
        m_star = 0.5 * scene.rho * math.pi * RADIUS**2
        k, c = 0.5 * scene.kn, 0.5 * scene.cn
        zeta = c / (2.0 * math.sqrt(k * m_star))
        omega = math.sqrt(k / m_star) * math.sqrt(1.0 - zeta * zeta)
        return np.full(v_n.shape, math.pi / omega), np.full(v_n.shape, math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2)))
    df = sweep(scene.replace(mu=0.0), theta_deg=90.0, v=v_n, progress=False)
    return df["contact_time"].to_numpy(), df["e_n"].to_numpy()


def criterion(scene: Scene, angles: np.ndarray) -> float:
    """Müller, Krengel & Pöschel's threshold angle: the largest theta at which the turn the
    tangential motion sweeps in the head-on contact time, dpsi = v cos(theta) t_c / (2 r),
    satisfies tan(dpsi) > e_N tan(theta)."""
    theta = np.radians(angles)
    v_n = np.maximum(SPEED * np.sin(theta), 1e-12)
    t_c, e_n = head_on(scene, v_n)
    dpsi = SPEED * np.cos(theta) * t_c / (2.0 * RADIUS)
    margin = e_n * np.tan(theta) - np.tan(np.minimum(dpsi, 1.5))
    return _sign_change(angles, margin)


def crossings(df: pl.DataFrame) -> pl.DataFrame:
    """Per case: the measured threshold angle theta*, the criterion's, and their ratio."""
    rows: list[dict[str, Any]] = []
    scenes = dict(cases())
    for label, scene in scenes.items():
        sub = df.filter(pl.col("case") == label).sort("theta_deg")
        measured = _sign_change(sub["theta_deg"].to_numpy(), sub["e_n"].to_numpy())
        predicted = criterion(scene, sub["theta_deg"].to_numpy())
        rows.append({"case": label, "theta_star_deg": measured, "theta_star_mkp_deg": predicted,
                     "ratio": measured / predicted if predicted == predicted else float("nan"),
                     "min_e_n": float(sub["e_n"].min()), "e_n_sep_range": f"{sub['e_n_sep'].min():.3f} .. "
                                                                          f"{sub['e_n_sep'].max():.3f}"})
    return pl.DataFrame(rows)


def figure(df: pl.DataFrame, cross: pl.DataFrame, path: Path) -> None:
    """e_n and e_n_sep against theta per case, the measured and predicted thresholds marked."""
    from .figures import _plt

    plt = _plt()
    labels = [label for label, _ in cases()]
    fig, axes = plt.subplots(2, 4, figsize=(16, 7), sharex=True, sharey=True)
    for ax, label in zip(axes.flat, labels):
        sub = df.filter(pl.col("case") == label).sort("theta_deg")
        ax.plot(sub["theta_deg"], sub["e_n"], label=r"$e_n$ (first-touch normal)")
        ax.plot(sub["theta_deg"], sub["e_n_sep"], "--", label=r"$e_{n,sep}$")
        row = cross.filter(pl.col("case") == label).row(0, named=True)
        if row["theta_star_deg"] == row["theta_star_deg"]:
            ax.axvline(row["theta_star_deg"], color="k", lw=0.8, label=r"$\theta^*$ measured")
        if row["theta_star_mkp_deg"] == row["theta_star_mkp_deg"]:
            ax.axvline(row["theta_star_mkp_deg"], color="r", ls=":", label=r"$\theta^*$ criterion")
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.set(xscale="log", title=label)
    for ax in axes[1]:  # the columns share their x axis: labelled once, below
        ax.set_xlabel(r"$\theta$ (deg, from the tangent)")
    axes[0, 0].set_ylabel("restitution")
    axes[1, 0].set_ylabel("restitution")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"Two preset discs at v = {SPEED:g} m/s: where e_n turns negative")
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)


def write_map(out: Path, angles: np.ndarray = ANGLES) -> list[Path]:
    """The map's table, thresholds, figure and ``report.md`` in ``out``; returns the paths."""
    out.mkdir(parents=True, exist_ok=True)
    df = negative_e_n_map(angles)
    cross = crossings(df)
    paths = [out / "negative_e_n.parquet", out / "negative_e_n_thresholds.parquet", out / "negative_e_n.png",
             out / "report.md"]
    df.write_parquet(paths[0])
    cross.write_parquet(paths[1])
    figure(df, cross, paths[2])
    paths[3].write_text(report(cross))
    return paths


def summary(out: Path) -> list[str]:
    """The headline of a map written to ``out`` (a few lines for the terminal; the rest is in
    ``report.md``): the discs' measured thresholds against the criterion's, and the polygons'
    half-negative angles when they were drawn."""
    cross = pl.read_parquet(out / "negative_e_n_thresholds.parquet")
    ratio = cross["ratio"].drop_nans()
    lines = [f"two discs: e_n turns negative below theta* = {cross['theta_star_deg'].min():.3g} ... "
             f"{cross['theta_star_deg'].max():.3g} deg (from the tangent) over {cross.height} cases; "
             f"measured / criterion {ratio.min():.3f} ... {ratio.max():.3f} ({ratio.len()} cases with a criterion)"]
    polygons = out / "negative_e_n_polygons_summary.parquet"
    if polygons.exists():
        from .polygon_pair_map import half_negative_angle

        stats = pl.read_parquet(polygons)
        halves = [f"{case} {half_negative_angle(sub.sort('theta_deg')):.3g}"
                  for (case,), sub in stats.group_by("case", maintain_order=True)]
        lines.append("two polygons, theta_half (deg): " + ", ".join(halves))
    return lines


def report(cross: pl.DataFrame) -> str:
    """The thresholds in a table, with what was compared (markdown)."""
    lines = ["# Negative e_N: two discs", "",
             f"Two preset discs (r = {RADIUS} m, rho 2500, E 1e7 Pa) at v = {SPEED:g} m/s, Gear-5 at its default "
             "step. theta*: the largest angle below which e_n (the first-touch normal) is negative; the criterion's "
             "theta*: where tan(v cos(theta) t_c / 2r) = e_N tan(theta), t_c and e_N of the head-on collision at "
             "v sin(theta) (closed forms for the linear law, the engine's head-on impacts for the area law). "
             "Nothing is fitted.", "",
             "| case | theta* (deg) | criterion (deg) | ratio | min e_n | e_n_sep |", "|---|---|---|---|---|---|"]
    for r in cross.iter_rows(named=True):
        lines.append(f"| {r['case']} | {r['theta_star_deg']:.3g} | {r['theta_star_mkp_deg']:.3g} | {r['ratio']:.3f} "
                     f"| {r['min_e_n']:.3f} | {r['e_n_sep_range']} |")
    return "\n".join(lines) + "\n"
