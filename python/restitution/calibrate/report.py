"""A fit written to a directory: samples.parquet, check.parquet, report.md, fit.png, corner.png."""

from __future__ import annotations

from pathlib import Path

import polars as pl

from ..study.validate import _markdown
from .diagnostics import TAU_FACTOR
from .posterior import Posterior

#: |z| above this marks a point the model misses in the report.
Z_FLAG = 3.0


def write(post: Posterior, out: Path, source: str) -> list[Path]:
    """Writes the fit's outputs to ``out`` (created if needed); returns their paths."""
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "samples.parquet", out / "check.parquet", out / "report.md", out / "fit.png", out / "corner.png"]
    post.samples.write_parquet(paths[0])
    check = post.check()
    check.write_parquet(paths[1])
    paths[2].write_text(report(post, check, source), encoding="utf-8")
    for path, fig in ((paths[3], post.plot_fit()), (paths[4], post.plot_corner())):
        fig.savefig(path)
        fig.clf()
    return paths


def report(post: Posterior, check: pl.DataFrame, source: str) -> str:
    """report.md: the run, the summary, convergence, the chosen tol and the predictive check."""
    p = post.problem
    verdict = {"converged": "converged", "max_iter": f"NOT converged: stopped at max_iter = {post.iterations}",
               "interrupted": "NOT converged: interrupted (Ctrl-C)"}[post.stopped]
    tol = (f"tol = {p.tol:.3g} (the adaptive path's absolute accuracy: the smallest sigma / 100)"
           if p.tol is not None else f"integrator {p.scene.integrator}: dt_factor as configured (tol unused)")
    missed = check.filter(pl.col("z").abs() > Z_FLAG)
    lines = [
        "# Calibration", "",
        f"Config: `{source}`. Free: {', '.join(p.names)}; {p.data.height} measurements; likelihood {p.likelihood}"
        + (f" (df = {p.df:g})" if p.likelihood == "student-t" else "") + ".", "",
        f"Sampler: emcee, {post.walkers} walkers, {post.iterations} iterations "
        f"({post.convergence.discard} dropped as burn-in), {post.impacts:,} impacts in {post.seconds:.1f} s, "
        f"seed {post.seed}. **{verdict}.**", "",
        f"Integrator accuracy: {tol}.", "",
        "## Posterior", "", _markdown(post.summary()), "",
        f"Convergence requires a chain longer than {TAU_FACTOR} autocorrelation times (tau), every ESS >= the "
        "minimum and every rank-normalised split R-hat <= the maximum (fit's `min_ess`, `rhat_max`).", "",
        "## Posterior predictive check", "",
        f"p-value of the chi-square discrepancy: **{post.p_value:.3f}** (near 0: the model cannot explain the data "
        "within their sigma).", "",
        f"{missed.height} of {check.height} points with |z| > {Z_FLAG:g}"
        + (":" if missed.height else "."), "",
    ]
    if missed.height:
        lines += [_markdown(missed), ""]
    lines += ["All points:", "", _markdown(check), "", "Figures: `fit.png` (data over the 5-95 % posterior band), "
              "`corner.png`. Samples: `samples.parquet`; the check: `check.parquet`."]
    return "\n".join(lines) + "\n"


__all__ = ["report", "write"]
