"""Peak memory and throughput of large sweeps: streamed to a Parquet dataset vs held in memory.

Each measurement runs in a fresh process and reports its peak RSS (getrusage ru_maxrss), the
RSS right after the imports (the floor), wall time and impacts/s. A streamed sweep should keep
the same peak whatever its size (bounded by the chunk size); the in-memory one grows with it.

    python benchmarks/sweep_memory.py                       # 1e5, 2e5, 1e6 impacts
    python benchmarks/sweep_memory.py --sizes 100000 --modes streamed --threads 1 2

The scene is deliberately cheap (exact disc, Verlet, dt_factor 0.1: ~50 steps per contact) so
that 10^6 impacts take about a minute on 2 cores; memory does not depend on the cost per impact.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from typing import Any


def _rss_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def child(n: int, mode: str, threads: int, chunk_size: int) -> None:
    import numpy as np

    import restitution as rs

    floor = _rss_mb()
    scene = rs.Scene(integrator="verlet", dt_factor=0.1)
    inner = 1000
    axes: dict[str, Any] = {"theta_deg": np.linspace(1.0, 90.0, n // inner), "omega_in": np.linspace(-1.0, 1.0, inner)}
    t0 = time.perf_counter()
    if mode == "streamed":
        with tempfile.TemporaryDirectory() as d:
            res = rs.sweep_to_dataset(scene, f"{d}/ds", chunk_size=chunk_size, threads=threads or None,
                                        progress=False, **axes)
            rows = res.n_cases
    else:
        rows = rs.sweep(scene, chunk_size=chunk_size, threads=threads or None,
                                        progress=False, **axes).height
    seconds = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux
    print(json.dumps({"n": rows, "mode": mode, "threads": threads, "floor_mb": floor, "peak_mb": peak,
                      "seconds": seconds, "rate": rows / seconds}))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[100_000, 200_000, 1_000_000])
    p.add_argument("--modes", nargs="+", choices=("streamed", "memory"), default=["streamed", "memory"])
    p.add_argument("--threads", type=int, nargs="+", default=[0], help="0: all cores")
    p.add_argument("--chunk-size", type=int, default=8192)
    p.add_argument("--child", nargs=4, metavar=("N", "MODE", "THREADS", "CHUNK"), help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child:
        n, mode, threads, chunk = args.child
        child(int(n), mode, int(threads), int(chunk))
        return
    print(f"{'impacts':>9} {'mode':>9} {'threads':>7} {'floor MB':>9} {'peak MB':>8} {'peak-floor':>10} "
          f"{'seconds':>8} {'impacts/s':>10}")
    for mode in args.modes:
        for threads in args.threads:
            for n in args.sizes:
                out = subprocess.run([sys.executable, __file__, "--child", str(n), mode, str(threads),
                                      str(args.chunk_size)], check=True, capture_output=True, text=True).stdout
                r = json.loads(out.strip().splitlines()[-1])
                print(f"{r['n']:>9} {mode:>9} {threads or 'all':>7} {r['floor_mb']:>9.0f} {r['peak_mb']:>8.0f} "
                      f"{r['peak_mb'] - r['floor_mb']:>10.0f} {r['seconds']:>8.1f} {r['rate']:>10,.0f}", flush=True)


if __name__ == "__main__":
    main()
