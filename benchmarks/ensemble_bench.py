"""Ensembles and collision operators at scale: peak memory of a streamed 10^6-draw ensemble, and
the cost of an operator call per collision in NumPy batches.

Targets (issue 29): 10^6 draws stream at <= 200 MB peak RSS; an operator call costs <= 1 us per
collision in batches of 10^5.

    python benchmarks/ensemble_bench.py                      # both parts
    python benchmarks/ensemble_bench.py --part memory --draws 1000000
    python benchmarks/ensemble_bench.py --part operator --batch 100000 --repeat 7

Memory: each measurement runs in a fresh process and reports its peak RSS (getrusage), the RSS
after the imports (the floor), and the time; the ensemble is 1000 angles x ``draws / 1000``
draws of (omega_in, mu) on the cheap disc of ``benchmarks/sweep_memory.py`` (Verlet, dt_factor
0.1), streamed to a Parquet dataset, then summarised from the dataset (bootstrap included), in
the same process. Operator: the deterministic (interpolated mean) and stochastic (a draw of the
tabulated distribution) calls on random states inside the table, best of ``--repeat`` runs.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time


def _rss_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux


def memory_child(draws: int, chunk_size: int, threads: int) -> None:
    import numpy as np

    import restitution as rs

    floor = _rss_mb()
    scene = rs.Scene(integrator="verlet", dt_factor=0.1)
    vary = {"omega_in": rs.Normal(0.0, 1.0), "mu": rs.Uniform(0.1, 0.9)}
    n = draws // 1000
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        res = rs.ensemble_to_dataset(scene, f"{d}/ens", n, vary=vary, seed=1, chunk_size=chunk_size,
                                     threads=threads or None, progress=False, theta_deg=np.linspace(1.0, 90.0, 1000))
        stream_s, stream_peak = time.perf_counter() - t0, _peak_mb()
        t0 = time.perf_counter()
        summary = rs.read_ensemble(f"{d}/ens").summary(n_boot=200)
        summary_s = time.perf_counter() - t0
    print(json.dumps({"draws": res.n_cases, "floor_mb": floor, "stream_peak_mb": stream_peak, "stream_s": stream_s,
                      "rate": res.n_cases / stream_s, "summary_peak_mb": _peak_mb(), "summary_s": summary_s,
                      "summary_rows": summary.height}))


def memory(args: argparse.Namespace) -> None:
    print(f"{'draws':>9} {'threads':>7} {'floor MB':>9} {'peak MB (stream)':>16} {'peak MB (+summary)':>18} "
          f"{'stream s':>9} {'draws/s':>9} {'summary s':>10}")
    for draws in args.draws:
        out = subprocess.run([sys.executable, __file__, "--child", str(draws), str(args.chunk_size), str(args.threads)],
                             check=True, capture_output=True, text=True).stdout
        r = json.loads(out.strip().splitlines()[-1])
        print(f"{r['draws']:>9} {args.threads or 'all':>7} {r['floor_mb']:>9.0f} {r['stream_peak_mb']:>16.0f} "
              f"{r['summary_peak_mb']:>18.0f} {r['stream_s']:>9.1f} {r['rate']:>9,.0f} {r['summary_s']:>10.1f}",
              flush=True)


def operator(args: argparse.Namespace) -> None:
    import numpy as np

    import restitution as rs

    tables = {
        "disc, deterministic": (rs.CollisionOperator.build(
            rs.Scene(mu=0.3, integrator="adaptive"), theta_deg=np.linspace(5, 90, 18), omega_in=np.linspace(-2, 2, 5),
            v=[0.01, 0.1], tol=2e-3, n_check=64), None),
        "hexagon, 32 draws": (rs.CollisionOperator.build(
            rs.Scene.paper(shape=rs.RegularPolygon(0.01, 6), mu=0.3, integrator="adaptive"),
            theta_deg=np.linspace(5, 90, 10), omega_in=[-2.0, 0.0, 2.0], v=[0.01, 0.1],
            vary={"phi0_deg": rs.Uniform(0.0, 60.0)}, n=32, tol=2e-2, n_check=32), 1),
    }
    rng = np.random.default_rng(0)
    n = args.batch
    v = np.exp(rng.uniform(np.log(0.01), np.log(0.1), n))
    theta = np.radians(rng.uniform(5.0, 90.0, n))
    v_n, v_t = -v * np.sin(theta), v * np.cos(theta) * rng.choice([-1.0, 1.0], n)
    omega = rng.uniform(-2.0, 2.0, n)
    print(f"{'table':>20} {'nodes x draws':>14} {'call':>13} {'batch':>7} {'us per collision (best)':>24} {'median':>7}")
    for name, (op, seed) in tables.items():
        size = f"{int(np.prod(op.table.shape))} x {op.table.n_draws}"
        for kind in ("deterministic", "stochastic"):
            if kind == "stochastic" and seed is None:
                continue
            gen = np.random.default_rng(seed)
            times = []
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                op(v_n, v_t, omega, rng=gen if kind == "stochastic" else None)
                times.append(time.perf_counter() - t0)
            best, med = min(times) / n * 1e6, sorted(times)[len(times) // 2] / n * 1e6
            print(f"{name:>20} {size:>14} {kind:>13} {n:>7} {best:>24.3f} {med:>7.3f}", flush=True)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--part", choices=("memory", "operator", "both"), default="both")
    p.add_argument("--draws", type=int, nargs="+", default=[100_000, 1_000_000])
    p.add_argument("--chunk-size", type=int, default=8192)
    p.add_argument("--threads", type=int, default=0, help="0: all cores")
    p.add_argument("--batch", type=int, default=100_000)
    p.add_argument("--repeat", type=int, default=7)
    p.add_argument("--child", nargs=3, metavar=("DRAWS", "CHUNK", "THREADS"), help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child:
        memory_child(*(int(a) for a in args.child))
        return
    if args.part in ("operator", "both"):
        operator(args)
    if args.part in ("memory", "both"):
        memory(args)


if __name__ == "__main__":
    main()
