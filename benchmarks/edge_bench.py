"""The edge: what a Python call costs beyond the engine's own time (issue 27).

    python benchmarks/edge_bench.py                 # 5 rounds
    python benchmarks/edge_bench.py --rounds 20

Every call is timed from Python (``time.perf_counter`` around it) and the engine's own time of
that same call is read from the binding (``restitution._core.last_call_diagnostics()``:
``engine_s``, measured in Rust from the engine's entry to its return); the difference is the
edge: the scene's row, the checks, the crossing into Rust, the Ctrl-C plumbing and the record
back. The calls:

- ``rs.simulate`` over the study's 86 angles (4..89 deg), mu 0.5, on the preset disc
  (``Scene()``) and on the study's 120-gon (``Scene.paper()``);
- one-case ``rs.sweep`` calls over the same angles on the disc, on all threads and on one;
- small sweeps: 11 mu (0 ... 1) at each angle on the disc, all threads.

Each round runs each configuration's loop over the 86 angles in turn (a user's loop of
calls, not calls of several kinds interleaved: a parallel sweep's idle workers and its frames
would slow the next call of another kind), so a burst of load on a shared machine lands on all
of them alike. Prints per configuration the median engine time and the median,
99th percentile and largest edge, in microseconds. Targets (issue 27): a median edge of
``rs.simulate`` <= 30 us, of a sweep call <= 1 ms.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from typing import Callable

import numpy as np

import restitution as rs
from restitution import _core

THETA = np.arange(4.0, 90.0)  # the study's 86 angles
MU = np.round(np.linspace(0.0, 1.0, 11), 10)


def configurations() -> dict[str, Callable[[float], object]]:
    """Each configuration as a call of one angle."""
    disc, polygon = rs.Scene(), rs.Scene.paper()
    return {
        "simulate, disc": lambda t: rs.simulate(disc, theta_deg=t),
        "simulate, 120-gon": lambda t: rs.simulate(polygon, theta_deg=t),
        "sweep 1 case, disc": lambda t: rs.sweep(disc, theta_deg=t, progress=False),
        "sweep 1 case, disc, threads=1": lambda t: rs.sweep(disc, theta_deg=t, threads=1, progress=False),
        "sweep 11 mu, disc": lambda t: rs.sweep(disc, theta_deg=t, mu=MU, progress=False),
    }


def edge_of(call: Callable[[float], object], theta: float) -> tuple[float, float]:
    """(engine seconds, seconds beyond the engine) of one call."""
    start = time.perf_counter()
    call(theta)
    wall = time.perf_counter() - start
    engine = float(_core.last_call_diagnostics()["engine_s"])
    return engine, wall - engine


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5, help="passes over the 86 angles (default: 5)")
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds must be >= 1")
    configs = configurations()
    for call in configs.values():  # warm-up: imports, first allocations
        for theta in THETA[:5]:
            call(float(theta))
    engine: dict[str, list[float]] = {name: [] for name in configs}
    edge: dict[str, list[float]] = {name: [] for name in configs}
    for _ in range(args.rounds):
        for name, call in configs.items():
            for theta in THETA:
                e, x = edge_of(call, float(theta))
                engine[name].append(e)
                edge[name].append(x)
    print(f"{len(THETA)} angles x {args.rounds} rounds per configuration, mu 0.5 unless varied")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} logical CPUs, "
          f"load average {os.getloadavg()[0]:.1f}" if hasattr(os, "getloadavg") else "")
    print(f"{'call':<31} {'engine us':>10} {'edge median':>12} {'p99':>9} {'max':>9}   (us)")
    for name in configs:
        e, x = 1e6 * np.array(engine[name]), 1e6 * np.array(edge[name])
        print(f"{name:<31} {np.median(e):>10.1f} {np.median(x):>12.1f} "
              f"{np.percentile(x, 99):>9.1f} {x.max():>9.1f}")


if __name__ == "__main__":
    main()
