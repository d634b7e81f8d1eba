"""Sweep throughput: 86 angles (4..89 deg) x 11 mu (0, 0.1 ... 1) on the paper preset, for the
exact disc and the study's 120-gon, at several thread counts, in one run.

    python benchmarks/sweep_bench.py                       # threads 1 and 2, best of 3
    python benchmarks/sweep_bench.py --threads 1 2 4 16 --repeat 5

Prints impacts/s per shape and thread count (best of the repeats, so a noisy repeat on a busy
machine does not count) and the speed-up over one thread, measured in the same run. Target
(issue 3): >= 1.8x on 2 threads. Speed-ups need that many idle cores: on a loaded machine they
measure the load as much as the code.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

import restitution as rs

THETA = np.arange(4.0, 90.0)  # 86 angles
MU = np.round(np.linspace(0.0, 1.0, 11), 10)  # 11 values


def shapes() -> dict[str, rs.Scene]:
    return {
        "disc": rs.Scene.paper(shape=rs.Disc(r=0.01)),
        "120-gon": rs.Scene.paper(),
    }


def best_time(scene: rs.Scene, threads: int, repeat: int) -> tuple[float, int]:
    """Best wall time of `repeat` sweeps, and the total steps of one sweep."""
    best, steps = float("inf"), 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        df = rs.sweep(scene, theta_deg=THETA, mu=MU, threads=threads, progress=False)
        best = min(best, time.perf_counter() - t0)
        steps = int(df["steps"].sum())
    return best, steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2], help="thread counts (default: 1 2)")
    parser.add_argument("--repeat", type=int, default=3, help="repeats per configuration; the best counts (default: 3)")
    args = parser.parse_args()
    if args.repeat < 1 or any(t < 1 for t in args.threads):
        parser.error("--repeat and --threads must be >= 1")
    threads = sorted(set(args.threads))
    n = len(THETA) * len(MU)
    print(f"{n} impacts per sweep ({len(THETA)} angles x {len(MU)} mu), paper preset, best of {args.repeat}")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} logical CPUs")
    print(f"{'shape':<8} {'threads':>7} {'time s':>8} {'impacts/s':>10} {'ns/step':>8} {'speed-up':>8}")
    for name, scene in shapes().items():
        rs.sweep(scene, theta_deg=THETA[:4], mu=MU[:2], threads=1, progress=False)  # warm-up
        base = 1.0
        for t in threads:
            secs, steps = best_time(scene, t, args.repeat)
            if t == threads[0]:
                base = secs
            # ns per step of one thread's work: wall time x threads / steps.
            ns_step = secs * t / steps * 1e9
            ratio = f"{base / secs:.2f}x" if t != threads[0] else "1.00x"
            print(f"{name:<8} {t:>7} {secs:>8.3f} {n / secs:>10.0f} {ns_step:>8.1f} {ratio:>8}")
    print(f"speed-up is relative to {threads[0]} thread(s), measured in this run")


if __name__ == "__main__":
    main()
