"""``restitution reproduce``: the study's figures 2-5, the e_T = 0.9 inverse map and a report
that sets our fits beside the study's, all on the paper preset.

``--quick`` runs an exact disc on coarse grids (seconds; the CI smoke test); the default runs the
study's 120-gon on fine grids (18 000 impacts: about 45 s of CPU on two cores).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

import numpy as np

from .._core import __version__ as ENGINE_VERSION
from ..runs.sweep import sweep
from ..scene import Scene
from ..shapes import Disc
from ..simulate import simulate

#: omega_in values of Fig. 5 (deg/s): the study's range [-50, 50] with the spins it quotes.
SPINS_DEG = (-50.0, -20.0, -10.0, -5.0, 0.0, 5.0, 10.0, 20.0, 50.0)
#: The study's e_T = 0.9 example: omega_in (deg/s) -> quoted angles (deg), for mu = 0.1.
STUDY_E_T_09 = {-50.0: [30.0, 70.0], -20.0: [30.0, 83.0], -10.0: [30.0, 85.0], -5.0: [30.0, 87.0], 0.0: [30.0],
                5.0: [30.0], 10.0: [30.0], 20.0: [30.0], 50.0: [30.0]}
STUDY_E_T_RANGE = (-4.17, 5.37)
#: theta_c from rigid-body theory at mu = 1 that docs/model.md (section 10) quotes, and the study's fit there.
THETA_C_MU1_MODEL = 9.95


@dataclass(frozen=True)
class Grids:
    theta2: np.ndarray
    mus2: np.ndarray
    theta4: np.ndarray
    mus4: np.ndarray
    theta5: np.ndarray
    theta_ms: np.ndarray
    gamma_factors: tuple[float, float] = (0.5, 2.0)
    gamma_ts: tuple[float, ...] = (0.25, 0.5, 1.0)
    spins_deg: tuple[float, ...] = SPINS_DEG


def grids(quick: bool) -> Grids:
    """Quick: coarse grids for a smoke test. Full: 0.5 deg for Figs. 2, 3; 0.2 deg and mu in
    steps of 0.05 for Fig. 4 (theta_c is refined between grid points anyway); 0.25 deg for Fig. 5."""
    mus = np.round(np.arange(0.0, 1.0 + 1e-9, 0.1), 10)
    if quick:
        return Grids(theta2=np.arange(4.0, 89.0 + 1e-9, 1.0), mus2=mus,
                     theta4=np.arange(4.0, 89.0 + 1e-9, 0.5), mus4=mus[1:],
                     theta5=np.arange(4.0, 89.0 + 1e-9, 0.5), theta_ms=np.arange(20.0, 89.0 + 1e-9, 0.5))
    return Grids(theta2=np.arange(4.0, 89.0 + 1e-9, 0.5), mus2=mus,
                 theta4=np.round(np.arange(4.0, 89.0 + 1e-9, 0.2), 10), mus4=np.round(np.arange(0.05, 1.0 + 1e-9, 0.05), 10),
                 theta5=np.arange(4.0, 89.0 + 1e-9, 0.25), theta_ms=np.arange(20.0, 89.0 + 1e-9, 0.25))


def reproduce(out: Path | str, *, quick: bool = False, threads: int | None = None, shape: str | None = None,
              log: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Runs every sweep, writes figures, Parquet files and report.md to ``out``; returns the numbers."""
    from . import analysis, figures, theory

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    shape = shape or ("disc" if quick else "polygon")
    scene = Scene.paper() if shape == "polygon" else Scene.paper(shape=Disc(r=0.01))
    g = grids(quick)
    t0 = time.perf_counter()
    o = _Outputs(out, scene, threads, log or (lambda s: None))
    title = (f"{'120-gon' if shape == 'polygon' else 'exact disc'}, paper preset "
             f"(r = {scene.r} m, v = {scene.v} m/s, gamma = {scene.gamma})")

    # The steps in the order the files, timings and log lines have always come in; each is timed
    # whole (its sweeps, fits and figures), so that the stages add up to the total.
    stages: dict[str, float] = {}
    cal, e_n_head_on = _timed(stages, "calibration", _calibration, scene)
    df2, gammas, e_n_gamma = _timed(stages, "Figs. 2-3", _figs_2_3, o, g, title)
    df4, crit, fits = _timed(stages, "Fig. 4", _fig4, o, g, title, quick)
    df5, sol = _timed(stages, "Fig. 5 and the inverse map", _fig5_inverse, o, g, title)
    ms, ms_mu, sond = _timed(stages, "micro-slip", _micro_slip, o, g, df2, df4)
    elapsed = time.perf_counter() - t0

    numbers = dict(scene=scene, shape=shape, quick=quick, grids=g, cal=cal, e_n_head_on=e_n_head_on,
                   gammas=gammas, e_n_gamma=e_n_gamma, crit=crit, fits=fits, df5=df5, sol=sol, ms=ms, ms_mu=ms_mu,
                   sond=sond, timings=o.timings, stages=stages, impacts=o.impacts, elapsed=elapsed, df2=df2)
    report = _report(numbers, theory, analysis, figures)
    (out / "report.md").write_text(report)
    o.files.append(out / "report.md")
    summary = _summary(numbers, analysis, figures)
    return {"files": o.files, "elapsed": elapsed, "impacts": o.impacts, "summary": summary, "crit": crit,
            "fits": fits, "inverse": sol, "calibration": cal, "report": report}


class _Outputs:
    """Where :func:`reproduce` puts things: runs named sweeps of the scene into Parquet files,
    saves figures and frames, and keeps what the report and the caller are told (the files in
    the order written, the time of each sweep, the number of impacts)."""

    def __init__(self, out: Path, scene: Any, threads: int | None, say: Callable[[str], None]) -> None:
        self.out, self.scene, self.threads, self.say = out, scene, threads, say
        self.files: list[Path] = []
        self.impacts = 0
        self.timings: dict[str, float] = {}

    def sweep(self, name: str, **axes: Any):
        """Sweeps the scene over ``axes``, timed, and writes ``<name>.parquet``."""
        t = time.perf_counter()
        df = sweep(self.scene, threads=self.threads, **axes)
        self.timings[name] = time.perf_counter() - t
        self.impacts += df.height
        path = self.out / f"{name}.parquet"
        df.write_parquet(path)
        self.files.append(path)
        self.say(f"{name}: {df.height} impacts in {self.timings[name]:.1f} s")
        return df

    def save(self, fig, name: str) -> None:
        """Saves a figure as ``name`` and closes it (a full run makes several)."""
        import matplotlib.pyplot as plt

        path = self.out / name
        fig.savefig(path, bbox_inches="tight")
        plt.close(fig)
        self.files.append(path)

    def frame(self, df, name: str) -> None:
        """Writes a derived frame (not a sweep) as ``name``."""
        df.write_parquet(self.out / name)
        self.files.append(self.out / name)


def _calibration(scene: Any) -> tuple[Any, float]:
    """Calibration of the preset: the gamma that gives e_N = 0.90 head-on on this shape, and the
    e_N the preset's rounded gamma gives there."""
    from .. import calibrate

    cal = calibrate.gamma_for_e_n(scene, 0.90)
    e_n_head_on = simulate(scene, 90.0).e_n
    return cal, e_n_head_on


def _figs_2_3(o: _Outputs, g: Grids, title: str) -> tuple[Any, list[float], dict[float, float]]:
    """Fig. 2 and 3: theta x mu, plus mu = 0 and 1 with lower and higher damping.
    Returns the main sweep, the damping variants' gammas and their head-on e_N."""
    from . import analysis, figures

    scene = o.scene
    r, v = scene.r, scene.v
    df2 = o.sweep("fig2", theta_deg=g.theta2, mu=g.mus2)
    gammas = [round(scene.gamma * f, 6) for f in g.gamma_factors]
    dfg = o.sweep("fig2_gamma", theta_deg=g.theta2, mu=[0.0, 1.0], gamma=gammas)
    e_n_gamma = {gm: simulate(scene.replace(gamma=gm), 90.0).e_n for gm in gammas}
    o.save(figures.fig2(df2, dfg, r=r, v=v, gamma=scene.gamma, title=title), "fig2_restitution.png")
    crit2 = analysis.critical_angles(df2, r=r, v=v)
    o.save(figures.fig3(df2, crit2, r=r, v=v, title=title), "fig3_spin.png")
    return df2, gammas, e_n_gamma


def _fig4(o: _Outputs, g: Grids, title: str, quick: bool) -> tuple[Any, Any, dict[str, dict[str, Any]]]:
    """Fig. 4: theta_c and e_kin,min against mu on a finer theta grid, and the exponential fits.
    Returns the sweep, the critical angles per mu and the fits per set of mu (the study's first)."""
    from . import analysis, figures

    df4 = o.sweep("fig4", theta_deg=g.theta4, mu=g.mus4)
    crit = analysis.critical_angles(df4, r=o.scene.r, v=o.scene.v).sort("mu")
    o.frame(crit, "fig4_critical.parquet")
    study_set = np.round(np.arange(0.1, 1.0 + 1e-9, 0.1), 10)
    sets = {"mu = 0.1 ... 1.0 (the study's)": study_set}
    if len(g.mus4) != len(study_set) or not np.allclose(g.mus4, study_set):
        sets[f"mu = {g.mus4[0]:g} ... {g.mus4[-1]:g} step {g.mus4[1] - g.mus4[0]:g}"] = g.mus4
    fits: dict[str, dict[str, Any]] = {}
    for label, mset in sets.items():
        sub = crit.filter(np.isin(crit["mu"].to_numpy(), mset))
        m = sub["mu"].to_numpy()
        fits[label] = {"theta_c": analysis.fit_exp(m, sub["theta_c"].to_numpy()),
                       "e_kin_min": analysis.fit_exp(m, sub["e_kin_min"].to_numpy()),
                       "n": len(m)}
    head = next(iter(fits))
    # The quick run's mu grid is the study's; a full run plots every mu of its finer grid.
    o.save(figures.fig4(crit.filter(np.isin(crit["mu"].to_numpy(), study_set)) if quick else crit,
                        {"theta_c": fits[head]["theta_c"], "e_kin_min": fits[head]["e_kin_min"]}, title=title),
           "fig4_thetac.png")
    return df4, crit, fits


def _fig5_inverse(o: _Outputs, g: Grids, title: str) -> tuple[Any, Any]:
    """Fig. 5 (spin before impact, mu = 0.1 and 1) and, from its sweep, the inverse map for
    e_T = 0.9 (+- 0.01). Returns the sweep and the solutions."""
    from . import figures, inverse

    r, v = o.scene.r, o.scene.v
    df5 = o.sweep("fig5", theta_deg=g.theta5, mu=[0.1, 1.0], omega_in=np.radians(g.spins_deg))
    o.save(figures.fig5(df5, r=r, v=v, title=title), "fig5_spin_in.png")
    sol = inverse.find(df5, "e_t", 0.9, tol=0.01)
    o.frame(sol, "inverse_e_t_0.9.parquet")
    o.save(figures.inverse_figure(sol, df5, quantity="e_t", value=0.9, tol=0.01, reference=STUDY_E_T_09,
                                  title=title, r=r, v=v), "inverse_e_t_0.9.png")
    return df5, sol


def _micro_slip(o: _Outputs, g: Grids, df2: Any, df4: Any) -> tuple[Any, Any, Any]:
    """Micro-slip in the rolling regime against gamma_t at mu = 1 (its own sweep) and against mu
    (from Fig. 4's), and the residuals of Eq. 2 in the sliding regime (from Fig. 2's)."""
    from . import analysis

    r, v = o.scene.r, o.scene.v
    dfm = o.sweep("micro_slip", theta_deg=g.theta_ms, mu=[1.0], gamma_t=list(g.gamma_ts))
    ms = analysis.micro_slip(dfm, r=r, v=v).sort("gamma_t")
    ms_mu = analysis.micro_slip(df4, r=r, v=v).sort("mu")
    sond = analysis.sondergaard_residuals(df2, r=r, v=v)
    return ms, ms_mu, sond


def _fit_rows(fit, study: dict[str, tuple[float, float]], analysis, digits: int) -> tuple[list[str], list[str]]:
    rows, flags = [], []
    for name, val, err in zip("abc", fit.params, fit.errors):
        sv, se = study[name]
        d, flag = analysis.compare((val, err), (sv, se))
        mark = "**yes**" if flag else "no"
        rows.append(f"| {name} | {val:.{digits}f} ± {err:.{digits}f} | {sv} ± {se} | {d:.1f} | {mark} |")
        if flag:
            flags.append(name)
    return rows, flags


def _summary(n: dict[str, Any], analysis, figures) -> list[str]:
    head = next(iter(n["fits"]))
    out = [f"gamma for e_N = 0.90 head-on: {n['cal'].value:.4f} (preset {n['scene'].gamma})"]
    for q in ("theta_c", "e_kin_min"):
        f = n["fits"][head][q]
        _, flags = _fit_rows(f, figures.STUDY_FITS[q], analysis, 3)
        out.append(f"{q}: a = {f.a:.3g} ± {f.errors[0]:.2g}, b = {f.b:.3g} ± {f.errors[1]:.2g}, "
                   f"c = {f.c:.3g} ± {f.errors[2]:.2g}; beyond 2 sigma of the study: {', '.join(flags) or 'none'}")
    et = n["df5"]["e_t"]
    out.append(f"Fig. 5: e_T from {et.min():.2f} to {et.max():.2f} (study: {STUDY_E_T_RANGE[0]} to {STUDY_E_T_RANGE[1]})")
    return out


def _report(n: dict[str, Any], theory, analysis, figures) -> str:
    """report.md: one function per section, each returning its lines (blank lines included)."""
    L: list[str] = []
    L += _report_header(n)
    L += _report_calibration(n, theory)
    L += _report_fig4_fits(n, analysis, figures)
    L += _report_fig4_per_mu(n, theory, figures)
    L += _report_fig2(n, theory)
    L += _report_micro_slip(n)
    L += _report_fig5_inverse(n)
    L += _report_timings(n)
    return "\n".join(L)


def _report_header(n: dict[str, Any]) -> list[str]:
    """Title, the version, command and scene the numbers come from, and the quick run's caveat."""
    sc = n["scene"]
    shape_txt = "the study's 120-gon (RegularPolygon(r=0.01, n=120))" if n["shape"] == "polygon" else "an exact disc"
    L = ["# Reproducing Krengel's oblique-impact study", ""]
    L.append(f"restitution {ENGINE_VERSION}, `restitution reproduce{' --quick' if n['quick'] else ''}`: paper preset on "
             f"{shape_txt}; r = {sc.r} m, v = {sc.v} m/s, rho = {sc.rho}, E = {sc.E:g} Pa, gamma = {sc.gamma}, "
             f"gamma_t = {sc.gamma_t}, integrator {sc.integrator}, dt_factor {sc.dt_factor}. "
             f"{n['impacts']} impacts, {n['elapsed']:.1f} s in all.")
    if n["quick"]:
        L += ["", "**Quick run** (coarse grids, exact disc): a smoke test. Run without `--quick` for the study's "
                  "120-gon on fine grids."]
    return L


def _report_calibration(n: dict[str, Any], theory) -> list[str]:
    """The calibrated gamma, and rigid-body theta_c at mu = 1 set beside docs/model.md's value."""
    import polars as pl

    sc, cal, crit = n["scene"], n["cal"], n["crit"]
    L = ["", "## Calibration and the rigid-body reference", ""]
    L.append(f"- gamma for e_N = 0.90 head-on at v = {sc.v} m/s on this shape: **{cal.value:.5f}** "
             f"(simulated e_N there {cal.achieved:.7f}; {cal.evaluations} impacts). The preset rounds it to {sc.gamma}, "
             f"which gives e_N(90 deg) = {n['e_n_head_on']:.5f}.")
    en_c1 = crit.filter(pl.col("mu") == 1.0)
    tc_090 = float(theory.theta_c(1.0, 0.90))
    lo, hi = theory.e_n_for_theta_c(THETA_C_MU1_MODEL + 0.005, 1.0), theory.e_n_for_theta_c(THETA_C_MU1_MODEL - 0.005, 1.0)
    L.append(f"- Rigid-body theta_c (disc, no spin): tan theta_c = 1 / (3 mu (1 + e_N)). At mu = 1 it is "
             f"{tc_090:.4f} deg for e_N = 0.90 (the preset's head-on calibration); docs/model.md's 9.95 deg is e_N = 0.90 "
             f"(any e_N in [{lo:.4f}, {hi:.4f}] rounds to it; exactly 9.95 needs e_N = "
             f"{theory.e_n_for_theta_c(THETA_C_MU1_MODEL, 1.0):.5f}).")
    if en_c1.height:
        e1 = float(en_c1["e_n_at_theta_c"][0])
        L.append(f"  The measured e_N near theta_c at mu = 1 is {e1:.4f} (e_N rises at flat angles), which moves the "
                 f"theory to {float(theory.theta_c(1.0, e1)):.3f} deg; the tables use the measured e_N.")
    return L


def _report_fig4_fits(n: dict[str, Any], analysis, figures) -> list[str]:
    """How theta_c and e_kin,min are found and fitted, and one table of fit parameters against
    the study's per quantity and set of mu."""
    L = ["", "## Fig. 4: theta_c and e_kin,min against mu, fitted with a exp(-b mu) + c", ""]
    L.append("theta_c is where |omega_out| peaks (the kink where the sliding branch meets the rolling one), "
             "located between grid points by intersecting the two branches; e_kin,min likewise (a kink at large mu, "
             "a smooth minimum at small mu, where it lies below theta_c). Fits: least squares with errors from the "
             "scatter about the fit (chi2/dof scaling), as the study's data carry no error bars either; a flag marks "
             "parameters more than 2 combined standard errors from the study's (distance = |ours - study| / "
             "sqrt(err_ours^2 + err_study^2)). The study does not say what its ± are; if they are 95 % confidence "
             "bounds (a common fitting-tool default) its standard errors are half as large and the distances grow.")
    for label, fset in n["fits"].items():
        for q, digits, unit in (("theta_c", 2, " (deg)"), ("e_kin_min", 3, "")):
            L += ["", f"**{q}{unit}**, {label}, {fset['n']} points:", ""]
            L += ["| | ours | study | distance (sigma) | beyond 2 sigma |", "|---|---|---|---|---|"]
            rows, _ = _fit_rows(fset[q], figures.STUDY_FITS[q], analysis, digits)
            L.extend(rows)
    return L


def _study_fit_at(fit: dict[str, tuple[float, float]], mu: float) -> float:
    """The study's fit a exp(-b mu) + c (central values) at ``mu``."""
    return fit["a"][0] * np.exp(-fit["b"][0] * mu) + fit["c"][0]


def _report_fig4_per_mu(n: dict[str, Any], theory, figures) -> list[str]:
    """Per mu: simulation, rigid body and the study's fit side by side; then where (large mu)
    the model follows rigid-body theory rather than the study's plateau."""
    import polars as pl

    crit = n["crit"]
    L = ["", "Per mu (simulation, rigid body with the measured e_N at theta_c, the study's fit):", ""]
    L.append("| mu | theta_c sim | theta_c rigid | theta_c study fit | theta(e_kin min) | e_kin,min sim | "
             "e_kin,min rigid | e_kin,min study fit |")
    L.append("|---|---|---|---|---|---|---|---|")
    st, se = figures.STUDY_FITS["theta_c"], figures.STUDY_FITS["e_kin_min"]
    for row in crit.iter_rows(named=True):
        if row["theta_c"] is None:
            continue
        mu = row["mu"]
        t_st, e_st = _study_fit_at(st, mu), _study_fit_at(se, mu)
        ek_th, _ = theory.e_kin_min([mu], row["e_n_at_theta_c"])
        L.append(f"| {mu:g} | {row['theta_c']:.2f} | {row['theta_c_theory']:.2f} | {t_st:.2f} | "
                 f"{row['theta_e_kin_min']:.2f} | {row['e_kin_min']:.4f} | {ek_th[0]:.4f} | {e_st:.4f} |")
    big = crit.filter(pl.col("mu") >= 0.5)
    if big.height:
        dev = (big["theta_c"] - big["theta_c_theory"]).abs().max()
        L.append("")
        m1 = crit.filter(pl.col("mu") == crit["mu"].max())
        mu1 = float(m1["mu"][0])
        fit_st = _study_fit_at(st, mu1)
        L.append(f"**Where the model follows rigid-body theory instead of the study's fit.** For mu >= 0.5 the "
                 f"simulated theta_c stays within {dev:.2f} deg of rigid-body theory; at mu = {mu1:g} it is "
                 f"{float(m1['theta_c'][0]):.2f} deg (theory {float(m1['theta_c_theory'][0]):.2f}), where the study's fit "
                 f"gives {fit_st:.2f}. The study's offset c = 16.26 ± 2.85 deg is a plateau that theory does not have "
                 f"(theta_c -> 0 as mu grows); we do not tune to it. The soft contact puts theta_c slightly above the "
                 f"rigid-body value (tangential compliance delays the end of sliding).")
    return L


def _report_fig2(n: dict[str, Any], theory) -> list[str]:
    """Fig. 2: Eq. 2 in the sliding regime, e_N at both ends of the theta grid, and the damping variants."""
    import polars as pl

    sc, g, df2 = n["scene"], n["grids"], n["df2"]
    L = ["", "## Fig. 2: e_N, e_T, e_kin against theta", ""]
    sl = n["sond"].filter(pl.col("sliding") & (pl.col("mu") > 0) & pl.col("e_t_residual").is_not_null())
    # Compare with Eq. 2 away from the rounded corner at theta_c (3 deg margin).
    tc = theory.theta_c(sl["mu"].to_numpy(), sl["e_n"].to_numpy(), r=sc.r, v=sc.v)
    sl = sl.filter(sl["theta_deg"].to_numpy() <= tc - 3.0)
    if sl.height:
        L.append(f"- In the sliding regime (theta < theta_c - 3 deg, mu > 0; {sl.height} impacts) e_T follows the "
                 f"study's Eq. 2, e_T = 1 - mu (1 + e_N) tan theta with the measured e_N, to |residual| <= "
                 f"{float(sl['e_t_residual'].abs().max()):.1e}.")
    e_n90 = df2.filter(pl.col("theta_deg") == pl.col("theta_deg").max())
    e_n_lo = df2.filter(pl.col("theta_deg") == g.theta2[0])["e_n"]
    L.append(f"- e_N at theta = {g.theta2[-1]:g} deg: {_spread(e_n90['e_n'])}; at {g.theta2[0]:g} deg: "
             f"{_spread(e_n_lo)} (e_N falls with theta).")
    L.append("- Damping variants (mu = 0 and 1): " + ", ".join(
        f"gamma = {gm:g} gives e_N(90 deg) = {e:.4f}" for gm, e in n["e_n_gamma"].items()) + ".")
    return L


def _report_micro_slip(n: dict[str, Any]) -> list[str]:
    """Micro-slip: e_T's deviation from rolling per gamma_t at mu = 1, and its extremes over mu."""
    L = ["", "## Micro-slip in the rolling regime (e_T around 2/3)", ""]
    L += ["Relative deviation of e_T from the rigid-body rolling value for theta >= theta_c + 3 deg, mu = 1:", ""]
    L += ["| gamma_t | min | max | std |", "|---|---|---|---|"]
    for row in n["ms"].iter_rows(named=True):
        L.append(f"| {row['gamma_t']:g} | {100 * row['rel_min']:+.2f} % | {100 * row['rel_max']:+.2f} % | "
                 f"{100 * row['rel_std']:.2f} % |")
    ms_mu = n["ms_mu"]
    if ms_mu.height:
        L.append("")
        L.append(f"With the preset gamma_t = {n['scene'].gamma_t} the extremes over mu = {ms_mu['mu'].min():g} ... "
                 f"{ms_mu['mu'].max():g} are {100 * float(ms_mu['rel_min'].min()):+.2f} % and "
                 f"{100 * float(ms_mu['rel_max'].max()):+.2f} % (the study: about 2 %).")
    return L


def _report_fig5_inverse(n: dict[str, Any]) -> list[str]:
    """Fig. 5's range of e_T, and every e_T = 0.9 solution beside the angles the study quotes."""
    import polars as pl

    g: Grids = n["grids"]
    et = n["df5"]["e_t"]
    L = ["", "## Fig. 5 and the inverse map", ""]
    L.append(f"- e_T over omega_in in [-50, 50] deg/s, mu = 0.1 and 1: {et.min():.3f} to {et.max():.3f} "
             f"(the study: {STUDY_E_T_RANGE[0]} to {STUDY_E_T_RANGE[1]}).")
    sol = n["sol"].filter(pl.col("kind") == "crossing")
    L += ["- Every impact with e_T = 0.9 (crossings located between grid points; in brackets the angles within "
          "±0.01):", ""]
    L += ["| mu | omega_in (deg/s) | theta (deg) | study (mu = 0.1) |", "|---|---|---|---|"]
    for mu in sorted(sol["mu"].unique().to_list()):
        for om in g.spins_deg:
            s = sol.filter((pl.col("mu") == mu) & ((pl.col("omega_in") - np.radians(om)).abs() < 1e-9))
            if s.height == 0:
                continue
            ths = ", ".join(f"{r_['theta_deg']:.1f} [{r_['theta_lo']:.1f}, {r_['theta_hi']:.1f}]"
                            for r_ in s.iter_rows(named=True))
            ref = ", ".join(f"~{t:g}" for t in STUDY_E_T_09.get(om, [])) if mu == 0.1 else ""
            L.append(f"| {mu:g} | {om:+g} | {ths} | {ref} |")
    L.append("")
    L.append("At mu = 1 the sliding solution lies below 4 deg (1 - 1.9 tan theta = 0.9 at 3.0 deg), outside the swept "
             "range, so the study's 'theta ~ 30 for all omega_in' is the mu = 0.1 panel. The steep solutions follow "
             "the rolling formula e_T = 2/3 - r omega_in / (3 v cos theta) and do not depend on mu.")
    return L


def _timed(stages: dict[str, float], name: str, step: Callable[..., Any], *args: Any) -> Any:
    """Runs one step of :func:`reproduce`, adding its wall time to ``stages`` under ``name``."""
    t = time.perf_counter()
    result = step(*args)
    stages[name] = time.perf_counter() - t
    return result


def _report_timings(n: dict[str, Any]) -> list[str]:
    """Seconds per stage (sweeps, fits and figures together), which add up to the total, and the
    sweeps' share of each; the report ends with a newline."""
    stages, sweeps = n["stages"], n["timings"]
    other = n["elapsed"] - sum(stages.values())
    lines = ["", "## Timings", "", f"{n['elapsed']:.1f} s in all: " + ", ".join(
        f"{k} {t:.1f} s" for k, t in stages.items()) + (f", between stages {other:.1f} s." if other >= 0.05 else "."),
        "", "Of which the sweeps: " + ", ".join(f"{k} {t:.1f} s" for k, t in sweeps.items()) + ".", ""]
    return lines


def _spread(values: Any) -> str:
    """The range of ``values`` over the friction coefficients, "a to b" where four decimals tell
    its ends apart, else the one value and the spread (at 89 deg e_N moves by ~1e-6 with mu)."""
    lo, hi = float(values.min()), float(values.max())
    if f"{lo:.4f}" != f"{hi:.4f}":
        return f"{lo:.4f} to {hi:.4f} over mu"
    if lo == hi:  # the exact disc: its normal force does not depend on friction at all
        return f"{lo:.4f} for every mu"
    return f"{0.5 * (lo + hi):.4f} for every mu (spread {hi - lo:.1e})"
