"""Pairs at the extremes, bounded (issue 40, item 4): random and corner pair scenes each through
the public ``rs.simulate`` on the default path, timed one by one on one core.

Scenes: discs, regular 3- to 1024-gons and random convex polygons; partner sizes 1e-2 to 1e2
times the particle's (r = 0.01 m), density ratios 1e-3 to 1e3, theta 0.05 to 90 deg, spins
|omega| r / v <= 2 (and the corner scenes' faster ones), mu 0 to 2, the area law elastic or
damped; plus the corner scenes of issue 40 (a 7-gon on a small pentagon at 0.07 deg, a spinning
triangle on a disc, 1024-gon pairs, 120-gons with a small fast partner). Prints the slowest
scenes, how many took over 1.5 s, how many ended on their step budget (`timed_out`), the
refusals, and the largest elastic energy gain.

    python benchmarks/pair_extremes_bench.py --n 300 --seed 1
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

import restitution as rs

R = 0.01
V = 0.0357
SIDES = (0, 3, 4, 5, 7, 12, 120, 1024, -1)  # 0: disc, -1: a random convex polygon


def body(rng: np.random.Generator, n: int, r: float):
    phi = float(rng.uniform(0.0, 360.0))
    if n == 0:
        return rs.Disc(r=r)
    if n < 0:
        ang = np.sort(rng.uniform(0.0, 2.0 * math.pi, int(rng.integers(4, 10))))
        verts = [(r * math.cos(a), r * (0.6 + 0.4 * rng.random()) * math.sin(a)) for a in ang]
        try:
            return rs.ConvexPolygon(vertices=verts, phi0_deg=phi)
        except (ValueError, TypeError):
            return rs.RegularPolygon(r=r, n=5, phi0_deg=phi)
    return rs.RegularPolygon(r=r, n=n, phi0_deg=phi)


def corner_scenes(rng: np.random.Generator) -> list[dict]:
    def scene(a, b, theta, w1=0.0, w2=0.0, ratio=1.0, mu=0.0):
        return {"shape": a, "partner": b, "theta": theta, "w": (w1, w2), "ratio": ratio, "mu": mu,
                "gamma": 0.0}
    poly = lambda n, r, phi=13.0: rs.RegularPolygon(r=r, n=n, phi0_deg=phi)
    return [
        scene(poly(7, R), poly(5, 0.3 * R, 71.0), 0.07),
        scene(poly(3, R), rs.Disc(r=R), 30.0, w1=3.0),
        scene(poly(1024, R), poly(1024, R, 71.0), 45.0),
        scene(poly(1024, R), poly(7, R), 10.0, w1=300.0),
        scene(poly(120, R), poly(3, 0.01 * R), 60.0, w2=-50.0),
        scene(poly(120, R), poly(4, 0.05 * R), 80.0, w1=-1.0, w2=20.0, ratio=1e-3),
        scene(poly(5, R), rs.Disc(r=100 * R), 90.0, ratio=1e3),
        scene(poly(4, R), poly(200, 3 * R), 1.0, w1=5.0, w2=-5.0, mu=2.0),
    ]


def random_scene(rng: np.random.Generator) -> dict:
    a = body(rng, int(rng.choice(SIDES)), R)
    b = body(rng, int(rng.choice(SIDES)), R * float(10 ** rng.uniform(-2, 2)))
    if isinstance(a, rs.Disc) and isinstance(b, rs.Disc):
        b = rs.RegularPolygon(r=b.r, n=5)
    return {"shape": a, "partner": b, "theta": float(10 ** rng.uniform(math.log10(0.05), math.log10(90))),
            "w": (float(rng.uniform(-2, 2)), float(rng.uniform(-2, 2))),
            "ratio": float(10 ** rng.uniform(-3, 3)), "mu": float(rng.choice([0.0, 0.5, 2.0])),
            "gamma": float(rng.choice([0.0, 0.33]))}


def radius(shape) -> float:
    if isinstance(shape, (rs.Disc, rs.RegularPolygon)):
        return shape.r
    return max(math.hypot(x, y) for x, y in shape.vertices)


def run(p: dict):
    scene = rs.Scene(shape=p["shape"], partner=p["partner"], partner_rho=2500.0 * p["ratio"],
                     mu=p["mu"], gamma=p["gamma"], gamma_t=0.0 if p["gamma"] == 0.0 else 0.5, v=V)
    w1 = p["w"][0] * V / radius(p["shape"])
    w2 = p["w"][1] * V / radius(p["partner"])
    t0 = time.perf_counter()
    rec = rs.simulate(scene, p["theta"], w1, w2)
    return rec, time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    scenes = corner_scenes(rng) + [random_scene(rng) for _ in range(args.n)]
    times, refused, timed_out, worst_gain = [], 0, 0, -math.inf
    for k, p in enumerate(scenes):
        try:
            rec, sec = run(p)
        except ValueError:
            refused += 1
            continue
        times.append((sec, k, p))
        timed_out += bool(rec.timed_out)
        if p["gamma"] == 0.0 and not rec.timed_out:
            worst_gain = max(worst_gain, rec.energy_out / rec.energy_in - 1.0)
    times.sort(key=lambda t: -t[0])
    print(f"{len(scenes)} pair scenes ({len(corner_scenes(rng))} corner), {refused} refused up front, "
          f"rs from {rs.__file__}")
    print(f"over 1.5 s: {sum(t > 1.5 for t, _, _ in times)}; timed_out: {timed_out}; "
          f"largest elastic energy gain {worst_gain:.2e}")
    for sec, k, p in times[:5]:
        print(f"  {sec:.2f} s  scene {k}: {type(p['shape']).__name__}/{type(p['partner']).__name__} "
              f"theta {p['theta']:.3g} ratio {p['ratio']:.3g} mu {p['mu']}")


if __name__ == "__main__":
    main()
