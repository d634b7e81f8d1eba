"""What building a scene costs against one impact (issue 41).

    python benchmarks/scene_bench.py                 # 7 rounds
    python benchmarks/scene_bench.py --rounds 21

A loop over scenes builds one per impact: ``rs.Scene(...)`` checks every field's type and has the
engine check every rule (ranges, pairings, the step bound) once, ``scene.replace(...)`` does the
same for a copy. Each round times, interleaved so that a burst of load on a shared machine lands
on all of them alike, a batch of each call:

- ``Scene()``: the preset disc; ``Scene(Sphere)``: Chung & Ooi's Test 4 alumina (Hertz law);
  ``Scene(120-gon)``: ``Scene.paper()``'s particle;
- ``replace(mu)``: the preset with another friction coefficient;
- ``simulate``: one impact of the preset disc at 45 deg (adaptive, the default).

Prints the median over rounds of each call's time in microseconds and its ratio to one
``simulate`` measured in the same run. Target (issue 41): ``Scene()`` and ``replace`` <= 10 us.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from typing import Callable

import numpy as np

import restitution as rs

BATCH = 2000


def calls() -> dict[str, Callable[[], object]]:
    disc = rs.Scene()
    gon = rs.RegularPolygon(r=0.01, n=120, phi0_deg=0.0)
    ball = rs.Sphere(r=2.5e-3)
    return {
        "Scene()": lambda: rs.Scene(),
        "Scene(Sphere, hertz)": lambda: rs.Scene(shape=ball, normal_law="hertz", E=380e9, nu=0.23, rho=4000.0,
                                                 cor=0.98, mu=0.092, v=3.9),
        "Scene(120-gon, gear5)": lambda: rs.Scene(shape=gon, integrator="gear5"),
        "scene.replace(mu=0.2)": lambda: disc.replace(mu=0.2),
        "simulate(disc, 45 deg)": lambda: rs.simulate(disc, theta_deg=45.0),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    todo = calls()
    times: dict[str, list[float]] = {name: [] for name in todo}
    for _ in range(args.rounds):
        for name, call in todo.items():
            start = time.perf_counter()
            for _ in range(BATCH):
                call()
            times[name].append((time.perf_counter() - start) / BATCH * 1e6)
    median = {name: float(np.median(t)) for name, t in times.items()}
    one_impact = median["simulate(disc, 45 deg)"]
    print(f"# restitution {rs.__version__}, Python {platform.python_version()}, {os.cpu_count()} CPUs, "
          f"median of {args.rounds} rounds of {BATCH} calls")
    print(f"{'call':<24} {'us':>8} {'/ simulate':>11}")
    for name, us in median.items():
        print(f"{name:<24} {us:8.2f} {us / one_impact:11.3f}")


if __name__ == "__main__":
    main()
