"""``restitution calibrate CONFIG --out DIR``: the posterior of contact parameters from measured
impacts (docs/model.md, "Calibration"): samples, report, fit and corner figures."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "calibrate"
HELP = "fit contact parameters to measured impacts from a TOML config (posterior, check, figures)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("config", type=Path, help="TOML calibration config (see examples/calibrate_kharaz.toml)")
    p.add_argument("--out", type=Path, required=True,
                   help="output directory: samples.parquet, check.parquet, report.md, fit.png, corner.png")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress line (default: on a terminal)")


def run(args: argparse.Namespace) -> int:
    from ..calibrate import config, report
    from ..calibrate.sampler import run as sample
    from ..runs._progress import StopOnInterrupt

    problem, options = config.load(args.config)
    try:
        with StopOnInterrupt() as guard:
            post = sample(problem, progress=args.progress, stop=lambda: guard.stopped, **options)
    except ImportError as err:
        raise ValueError(str(err)) from None
    except TypeError as err:  # a [fit] value of the wrong type
        raise ValueError(f"{args.config}: fit: {err}") from None
    report.write(post, args.out, str(args.config))
    line = ", ".join(f"{r['parameter']} = {r['q50']:.4g} [{r['q05']:.4g}, {r['q95']:.4g}]"
                     for r in post.summary().iter_rows(named=True))
    state = "converged" if post.converged else f"NOT converged ({post.stopped})"
    print(f"{line} (median [5 %, 95 %]); {state}; p = {post.p_value:.3f}; tol = {post.tol}; "
          f"{post.impacts:,} impacts in {post.seconds:.1f} s; wrote {args.out}")
    if post.stopped == "interrupted":
        print(f"restitution calibrate: stopped early; {args.out} holds the unconverged chain", file=sys.stderr)
        raise KeyboardInterrupt
    return 0
