"""``restitution pairs``: argument parsing for :mod:`restitution.study.pair_map` (the
negative-e_N map of two discs against Müller, Krengel & Pöschel's criterion)."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

NAME = "pairs"
HELP = ("two discs colliding: e_n (first-touch normal) and e_n_sep against theta, where e_n turns negative, "
        "against Müller, Krengel & Pöschel's criterion (table, figure, report.md)")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results/pairs"),
                   help="output folder (default: results/pairs)")


def run(args: argparse.Namespace) -> int:
    from ..study.pair_map import write_map

    start = time.perf_counter()
    paths = write_map(args.out)
    print((args.out / "report.md").read_text())
    print(f"pairs: {time.perf_counter() - start:.1f} s; wrote {', '.join(str(p) for p in paths)}")
    return 0
