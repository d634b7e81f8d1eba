"""What a pair costs against its body on the plate, end to end through ``rs.simulate`` (issue 40).

    python benchmarks/pair_cost_bench.py                 # 7 rounds
    python benchmarks/pair_cost_bench.py --rounds 15

The paper preset (theta 45 deg, mu 0.5) on the disc, the 12-gon and the study's 120-gon, each
on the plate and against a twin of itself (the pair at twice the plate's speed, so that
identical bodies meet as one body meets the plate), on the default path (adaptive, tol 1e-6)
and with Gear-5, plus a disc on a 12-gon. Each round times a loop of ``rs.simulate`` calls of
every configuration in turn (interleaved, so that a burst of load on a shared machine lands on
all of them alike); the table gives the median over rounds of the time per call and per step
and each pair's ratio to its body on the plate on the same integrator, measured in the same
run. Targets (issue 40, item 5): a 12-gon pair <= 3x the 12-gon on the plate per impact, two
120-gons <= 3x one 120-gon per step, two discs <= 1.5x the disc (stated on the engine's own
time: ``cargo bench -p restitution-core --bench impact -- summary``; this measures what a user's
loop sees, the call's own cost included).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

import restitution as rs

#: Calls per configuration per round: about 20 ms of the slowest configuration.
CALLS = {"disc": 200, "12-gon": 60, "120-gon": 20}


def configurations() -> dict[str, tuple[rs.Scene, int, str]]:
    """Name -> (scene, calls per round, the plate configuration it is compared with)."""
    bodies = {
        "disc": rs.Disc(r=0.01),
        "12-gon": rs.RegularPolygon(r=0.01, n=12, phi0_deg=0.0),
        "120-gon": rs.RegularPolygon(r=0.01, n=120, phi0_deg=0.0),
    }
    out: dict[str, tuple[rs.Scene, int, str]] = {}
    for integrator in ("adaptive", "gear5"):
        for name, body in bodies.items():
            plate = rs.Scene(shape=body, integrator=integrator)
            out[f"{name}, {integrator}"] = (plate, CALLS[name], f"{name}, {integrator}")
            pair = plate.replace(partner=body, v=2 * plate.v)
            out[f"two {name}s, {integrator}"] = (pair, CALLS[name], f"{name}, {integrator}")
        disc_on_12 = rs.Scene(shape=bodies["disc"], partner=bodies["12-gon"], integrator=integrator, v=2 * 0.0357)
        out[f"disc on a 12-gon, {integrator}"] = (disc_on_12, CALLS["12-gon"], f"12-gon, {integrator}")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    todo = configurations()
    steps = {name: rs.simulate(scene, theta_deg=45.0).steps for name, (scene, _, _) in todo.items()}
    times: dict[str, list[float]] = {name: [] for name in todo}
    for _ in range(args.rounds):
        for name, (scene, calls, _) in todo.items():
            start = time.perf_counter()
            for _ in range(calls):
                rs.simulate(scene, theta_deg=45.0)
            times[name].append((time.perf_counter() - start) / calls * 1e6)
    median = {name: float(np.median(t)) for name, t in times.items()}
    print(f"# restitution {rs.__version__}, Python {platform.python_version()}, {os.cpu_count()} CPUs, "
          f"load {os.getloadavg()[0]:.1f}, median of {args.rounds} rounds")
    print(f"{'configuration':<30} {'steps':>6} {'us/call':>9} {'ns/step':>8} {'per call':>9} {'per step':>9}")
    for name, (_, _, base) in todo.items():
        us, n = median[name], steps[name]
        ratio = ""
        if base != name:
            per_call = us / median[base]
            per_step = per_call * steps[base] / n
            ratio = f"{per_call:8.2f}x {per_step:8.2f}x"
        print(f"{name:<30} {n:>6} {us:>9.1f} {us * 1e3 / n:>8.0f} {ratio}")


if __name__ == "__main__":
    main()
