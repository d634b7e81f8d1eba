"""``restitution ensemble CONFIG --out DIR``: an ensemble from a TOML config (a sweep config
plus ``[ensemble]`` and ``[vary]``), streamed to a resumable Parquet dataset, on local threads or
a Dask cluster; when complete, its summary (``summary.parquet``) next to the chunks."""

from __future__ import annotations

import argparse
import sys

from .sweep import add_arguments as _sweep_arguments

NAME = "ensemble"
HELP = "drawn impacts from a TOML config into a Parquet dataset, with their statistics (resumable; threads or Dask)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    _sweep_arguments(p, kind="ensemble")  # the same options as `restitution sweep`
    p.add_argument("--n-boot", type=int, default=1000,
                   help="bootstrap resamples per point and quantity for summary.parquet (0: none)")


def run(args: argparse.Namespace) -> int:
    from ..runs.ensemble import load_config
    from ..study.ensemble import ensemble_to_dataset, read_ensemble

    spec, config_chunk = load_config(args.config)
    chunk = args.chunk_size if args.chunk_size is not None else config_chunk
    if chunk is not None and chunk < 1:
        raise ValueError(f"require `--chunk-size` >= 1 (found {chunk})")
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"require `--threads` >= 1 (found {args.threads})")
    if args.n_boot < 0:
        raise ValueError(f"require `--n-boot` >= 0 (found {args.n_boot})")
    try:
        result = ensemble_to_dataset(spec, args.out, chunk_size=chunk, threads=args.threads, progress=args.progress,
                                     resume=args.resume, scheduler=args.scheduler, wait=args.wait)
    except ImportError as err:
        raise ValueError(str(err)) from None
    except KeyboardInterrupt as err:
        if str(err):
            print(f"restitution ensemble: {err}", file=sys.stderr)
        raise
    summary = read_ensemble(args.out).summary(n_boot=args.n_boot)
    summary.write_parquet(args.out / "summary.parquet")
    rate = f", {result.impacts_per_s:,.0f} impacts/s" if result.cases_written else ""
    print(f"{result.n_cases} impacts ({spec.n_draws} draws x {spec.n_points} points) in {result.n_chunks} chunks "
          f"at {result.path}: wrote {result.chunks_written}, kept {result.chunks_skipped} ({result.seconds:.2f} s{rate}); "
          f"summary: {args.out / 'summary.parquet'}")
    return 0
