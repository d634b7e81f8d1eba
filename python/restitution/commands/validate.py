"""``restitution validate``: argument parsing for :mod:`restitution.study.validate` (the
Hertz-Mindlin sphere against the Chung & Ooi benchmark and Kharaz's experiments)."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

NAME = "validate"
HELP = ("the Hertz-Mindlin sphere against Chung & Ooi (2011) Tests 1, 2, 3, 4, 6, 7, 8 and Kharaz et al. (2001): "
        "tables, figures with the published curves, report.md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results/validate"),
                   help="output folder (default: results/validate)")


def run(args: argparse.Namespace) -> int:
    from ..study.validate import summary, write_validation

    start = time.perf_counter()
    paths = write_validation(args.out)
    print(f"validate: {time.perf_counter() - start:.1f} s; wrote {len(paths)} files (tables, figures) to "
          f"{args.out}; the full report: {args.out / 'report.md'}")
    print("\n".join(summary(args.out)))
    return 0
