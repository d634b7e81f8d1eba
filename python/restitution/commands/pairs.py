"""``restitution pairs``: argument parsing for :mod:`restitution.study.pair_map` (the
negative-e_N map of two discs against Müller, Krengel & Pöschel's criterion)."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

NAME = "pairs"
HELP = ("two discs colliding: e_n (first-touch normal) and e_n_sep against theta, where e_n turns negative, "
        "against Müller, Krengel & Pöschel's criterion; and two polygons at random orientations "
        "(tables, figures, report.md)")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results/pairs"),
                   help="output folder (default: results/pairs)")
    p.add_argument("--draws", type=int, default=48,
                   help="orientation draws per angle of the polygons' map (default: 48; 0 skips it)")


def run(args: argparse.Namespace) -> int:
    from ..study.pair_map import summary, write_map
    from ..study.polygon_pair_map import write_polygon_map

    start = time.perf_counter()
    paths = write_map(args.out)
    if args.draws > 0:
        more, text = write_polygon_map(args.out, draws=args.draws)
        paths += more
        with (args.out / "report.md").open("a") as f:
            f.write(text)
    print(f"pairs: {time.perf_counter() - start:.1f} s; wrote {len(paths)} files (tables, figures) to {args.out}; "
          f"the full report: {args.out / 'report.md'}")
    print("\n".join(summary(args.out)))
    return 0
