"""``restitution reproduce``: argument parsing for :func:`restitution.study.reproduce.reproduce`
(the study's Figs. 2-5, the inverse map and a report comparing fits with the study's)."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "reproduce"
HELP = "the study's Figs. 2-5, the inverse map and a report comparing fits with the study (PNG + Parquet + Markdown)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results/reproduce"), help="output folder (default: results/reproduce)")
    p.add_argument("--quick", action="store_true",
                   help="exact disc and coarse grids: a few seconds (the CI smoke test)")
    p.add_argument("--shape", choices=("polygon", "disc"), default=None,
                   help="the study's 120-gon or an exact disc (default: polygon; disc with --quick)")
    p.add_argument("--threads", type=int, default=None, help="worker threads (default: all cores)")


def run(args: argparse.Namespace) -> int:
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"require `--threads` >= 1 (found {args.threads})")
    from ..study.reproduce import reproduce

    res = reproduce(args.out, quick=args.quick, threads=args.threads, shape=args.shape)
    print(f"wrote {len(res['files'])} files to {args.out} in {res['elapsed']:.1f} s ({res['impacts']} impacts)")
    for line in res["summary"]:
        print("  " + line)
    return 0
