"""Extremes benchmark (issue 14): random and corner scenes over the whole parameter box, each through
the public ``rs.simulate``, timed one by one on one core.

Ranges: theta 0.01-90 deg, mu 0 or 1e-6-1e3, gamma 0 or 1e-6-10, E 1e3-1e12 Pa, v 1e-6-1e3 m/s,
|omega_in| 1e-3-1e4 deg/s, exact disc and regular 3-, 4-, 120-, 4096-gons at random orientation
(r = 0.01 m, rho = 2500, Gear-5 at dt_factor 0.01). Magnitudes are log-uniform; one scene in ten is a
corner of the box (every parameter at an end of its range).

Prints the slowest impacts, the refusals grouped by the parameter they name, the counts of finite,
non-finite and energy-gaining records, the timed-out ones, and the fraction over 1 s.

    python benchmarks/extremes_bench.py --n 10000 --seed 1
    python benchmarks/extremes_bench.py --quick          # 200 scenes
    python benchmarks/extremes_bench.py --integrator adaptive   # every scene on the adaptive path
"""

from __future__ import annotations

import argparse
import math
import re
import time
from collections import Counter

import numpy as np

import restitution as rs

SHAPES = (0, 3, 4, 120, 4096)  # 0: exact disc


def log_uniform(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


def draw(rng: np.random.Generator) -> dict:
    """One scene's parameters: random in the box, or (one in ten) a corner of it."""
    corner = rng.random() < 0.1
    pick = (lambda lo, hi: float(rng.choice([lo, hi]))) if corner else (lambda lo, hi: log_uniform(rng, lo, hi))
    return {
        "n": int(rng.choice(SHAPES)),
        "phi0_deg": float(rng.uniform(0.0, 360.0)),
        "theta_deg": pick(0.01, 90.0),
        "mu": 0.0 if rng.random() < 0.25 else pick(1e-6, 1e3),
        "gamma": 0.0 if rng.random() < 0.25 else pick(1e-6, 10.0),
        "E": pick(1e3, 1e12),
        "v": pick(1e-6, 1e3),
        "omega_deg_s": float(rng.choice([-1.0, 1.0])) * pick(1e-3, 1e4),
    }


def run_one(p: dict, integrator: str | None = None) -> tuple[str, object, float]:
    """('ok', record, seconds) or ('refused', message, seconds); ``integrator`` None: Scene()'s."""
    shape = rs.Disc(r=0.01) if p["n"] == 0 else rs.RegularPolygon(r=0.01, n=p["n"], phi0_deg=p["phi0_deg"])
    t0 = time.perf_counter()
    try:
        chosen = {} if integrator is None else {"integrator": integrator}
        scene = rs.Scene(shape=shape, mu=p["mu"], gamma=p["gamma"], E=p["E"], v=p["v"], **chosen)
        rec = rs.simulate(scene, theta_deg=p["theta_deg"], omega_in=math.radians(p["omega_deg_s"]))
    except ValueError as err:
        return "refused", str(err), time.perf_counter() - t0
    return "ok", rec, time.perf_counter() - t0


def finite(rec: rs.Record) -> bool:
    values = [rec.e_n, rec.e_kin, rec.omega_out, rec.vx_out, rec.vy_out, rec.energy_out, rec.energy_residual,
              rec.contact_time, rec.max_depth]
    return all(math.isfinite(x) for x in values)


def gains(p: dict, rec: rs.Record) -> bool:
    """Energy gained beyond the integration error that docs/model.md accepts: 1e-6 of the input where damping
    or friction act, 1e-2 for a conservative impact (whose O(dt^k) error may go either way)."""
    dissipative = p["gamma"] > 0.0 or p["mu"] > 0.0
    return rec.energy_out > rec.energy_in * (1.0 + (1e-6 if dissipative else 1e-2))


def summary(message: str) -> str:
    """A refusal's message reduced to the parameter it names and its first words."""
    name = re.search(r"`([^`]+)`", message)
    words = re.sub(r"\(found [^)]*\)|[-+]?\d[\d.e+-]*", "#", message).split()
    return f"{name.group(1) if name else '?'}: {' '.join(words[2:9])}"


def describe(p: dict) -> str:
    shape = "disc" if p["n"] == 0 else f"{p['n']}-gon phi0 {p['phi0_deg']:.1f}"
    return (f"{shape}, theta {p['theta_deg']:.3g}, mu {p['mu']:.3g}, gamma {p['gamma']:.3g}, E {p['E']:.3g}, "
            f"v {p['v']:.3g}, omega {p['omega_deg_s']:.3g} deg/s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--n", type=int, default=10_000, help="number of scenes (default 10^4)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--quick", action="store_true", help="200 scenes")
    parser.add_argument("--slowest", type=int, default=15, help="how many of the slowest to print")
    parser.add_argument("--integrator", default=None,
                        help="run every scene with this integrator (default: Scene()'s, Gear-5)")
    args = parser.parse_args()
    n = 200 if args.quick else args.n
    rng = np.random.default_rng(args.seed)
    results = []
    start = time.perf_counter()
    for i in range(n):
        p = draw(rng)
        kind, out, secs = run_one(p, args.integrator)
        results.append((secs, kind, out, p))
        if (i + 1) % max(1, n // 10) == 0:
            print(f"  {i + 1}/{n} scenes, {time.perf_counter() - start:.1f} s", flush=True)
    records = [(s, out, p) for s, kind, out, p in results if kind == "ok"]
    refused = Counter(summary(out) for _, kind, out, _ in results if kind == "refused")
    print(f"\n{n} scenes (seed {args.seed}) in {time.perf_counter() - start:.1f} s")
    print(f"refused: {sum(refused.values())}")
    for msg, count in refused.most_common():
        print(f"  {count:6d}  {msg}")
    print(f"records: {len(records)}: finite {sum(finite(r) for _, r, _ in records)}, "
          f"non-finite {sum(not finite(r) for _, r, _ in records)}, "
          f"energy-gaining {sum(gains(p, r) for _, r, p in records)}")
    for _, r, p in records:
        if gains(p, r):
            print(f"  gains {r.energy_out / r.energy_in - 1:+.2e}: {describe(p)} ({r.steps} steps, stop {r.stop})")
    stops = Counter(getattr(r, "stop", "timed_out" if r.timed_out else "separated") for _, r, _ in records)
    print(f"  ended: {dict(stops)}")
    over = sum(s > 1.0 for s, *_ in results)
    print(f"over 1 s: {over} of {n} ({over / n:.2%}); slowest {max(s for s, *_ in results):.3f} s")
    print(f"\nslowest {args.slowest}:")
    for secs, kind, out, p in sorted(results, key=lambda x: -x[0])[: args.slowest]:
        what = (f"{out.steps} steps, {out.contacts} contacts, timed_out {out.timed_out}" if kind == "ok"
                else f"refused: {out[:60]}")
        print(f"  {secs:7.3f} s  {describe(p)}: {what}")


if __name__ == "__main__":
    main()
