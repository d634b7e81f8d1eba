"""``restitution sweep CONFIG --out DIR``: a sweep from a TOML config, streamed to a resumable
Parquet dataset (one file per chunk), on local threads or on a Dask cluster."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "sweep"
HELP = "many impacts from a TOML config into a Parquet dataset (resumable; threads or a Dask cluster)"


def add_arguments(p: argparse.ArgumentParser, *, kind: str = "sweep") -> None:
    """The options of a dataset run from a config (``restitution ensemble`` takes them too)."""
    p.add_argument("config", type=Path, help=f"TOML {kind} config (see examples/{kind}_config.toml)")
    p.add_argument("--out", type=Path, required=True, help="dataset directory (new or empty, or the one to resume)")
    p.add_argument("--resume", action="store_true",
                   help="continue the interrupted sweep in --out (refused if the config changed)")
    p.add_argument("--wait", action="store_true",
                   help="if another process is writing --out, wait for it to finish (default: refuse, naming its pid)")
    p.add_argument("--threads", type=int, default=None, help="engine threads (default: all cores)")
    p.add_argument("--chunk-size", type=int, default=None,
                   help="cases per chunk file (default: the config's [sweep] chunk_size, else 8192)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run chunks on this Dask scheduler (e.g. tcp://host:8786); needs restitution[dask]")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar (default: on a terminal, for 50 000 impacts or more)")


def run(args: argparse.Namespace) -> int:
    from ..runs.config import load_config
    from ..runs.dataset import sweep_to_dataset

    spec, config_chunk = load_config(args.config)
    chunk = args.chunk_size if args.chunk_size is not None else config_chunk
    if chunk is not None and chunk < 1:
        raise ValueError(f"require `--chunk-size` >= 1 (found {chunk})")
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"require `--threads` >= 1 (found {args.threads})")
    try:
        result = sweep_to_dataset(spec, args.out, chunk_size=chunk, threads=args.threads, progress=args.progress,
                                  resume=args.resume, scheduler=args.scheduler, wait=args.wait)
    except ImportError as err:
        raise ValueError(str(err)) from None
    except KeyboardInterrupt as err:
        if str(err):
            print(f"restitution sweep: {err}", file=sys.stderr)
        raise
    rate = f", {result.impacts_per_s:,.0f} impacts/s" if result.cases_written else ""
    print(f"{result.n_cases} impacts in {result.n_chunks} chunks at {result.path}: wrote {result.chunks_written}, "
          f"kept {result.chunks_skipped} ({result.seconds:.2f} s{rate})")
    return 0
