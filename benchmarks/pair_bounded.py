"""Bounded pairs (issue 40): random and corner pair scenes through the public ``rs.simulate``,
each timed in CPU seconds of the calling thread (``time.process_time``: on a loaded machine wall
time says little), on the default path unless ``--integrator`` says otherwise.

Both bodies discs or regular 3- to 1024-gons at random orientations, the partner 1e-2 ... 1e2
times the particle's size (r = 0.01 m) and 1e-3 ... 1e3 its density, theta 0.05 ... 90 deg,
v 0.01 ... 10 m/s, spins up to 1e4 deg/s each, mu 0, 0.5 or 2, gamma 0 or 0.3; magnitudes
log-uniform, one scene in ten a corner of the box. A scene still running after ``--limit``
seconds of wall time is stopped by a SIGALRM handler (the engine polls its token: this also
exercises the interruption). Prints how many took over 1.5 s and the slowest.

    python benchmarks/pair_bounded.py --n 120 --seed 1
"""

from __future__ import annotations

import argparse
import math
import signal
import time

import numpy as np

import restitution as rs

SHAPES = (0, 3, 5, 7, 12, 120, 1024)


class Slow(Exception):
    """Raised by the SIGALRM handler: the scene ran past --limit seconds of wall time."""


def lu(rng, lo, hi):
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


def draw(rng):
    corner = rng.random() < 0.1
    pick = (lambda lo, hi: float(rng.choice([lo, hi]))) if corner else (lambda lo, hi: lu(rng, lo, hi))
    return dict(n1=int(rng.choice(SHAPES)), n2=int(rng.choice(SHAPES)), phi1=float(rng.uniform(0, 360)),
                phi2=float(rng.uniform(0, 360)), size=pick(1e-2, 1e2), rho=pick(1e-3, 1e3),
                theta=pick(0.05, 90.0), mu=float(rng.choice([0.0, 0.5, 2.0])), gamma=float(rng.choice([0.0, 0.3])),
                om1=float(rng.choice([-1, 1])) * pick(1e-3, 1e4), om2=float(rng.choice([-1, 1])) * pick(1e-3, 1e4),
                v=pick(0.01, 10.0))


def shape(n, r, phi):
    return rs.Disc(r=r) if n == 0 else rs.RegularPolygon(r=r, n=n, phi0_deg=phi)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--limit", type=float, default=20.0)
    ap.add_argument("--integrator", default=None)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    def alarm(*_: object) -> None:
        raise Slow()
    signal.signal(signal.SIGALRM, alarm)
    rows = []
    for i in range(a.n):
        p = draw(rng)
        kw = {} if a.integrator is None else {"integrator": a.integrator}
        try:
            s = rs.Scene(shape=shape(p["n1"], 0.01, p["phi1"]), partner=shape(p["n2"], 0.01 * p["size"], p["phi2"]),
                         partner_rho=2500 * p["rho"], mu=p["mu"], gamma=p["gamma"], v=p["v"], **kw)
        except ValueError:
            continue
        c0, w0 = time.process_time(), time.perf_counter()
        signal.setitimer(signal.ITIMER_REAL, a.limit)
        try:
            r = rs.simulate(s, theta_deg=p["theta"], omega_in=math.radians(p["om1"]), partner_omega_in=math.radians(p["om2"]))
            out = f"stop={r.stop} steps={r.steps}/{r.step_budget} res={r.energy_residual:.1e}"
        except ValueError as e:
            out = "refused " + str(e)[:60]
        except Slow:
            out = "WALL LIMIT"
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        cpu = time.process_time() - c0
        rows.append((cpu, i, p, out))
    rows.sort(key=lambda x: -x[0])
    print(f"{len(rows)} scenes; over 1.5 s CPU: {sum(r[0] > 1.5 for r in rows)}")
    for cpu, i, p, out in rows[:12]:
        print(f"{cpu:7.3f}s #{i} n={p['n1']}/{p['n2']} size={p['size']:.2g} rho={p['rho']:.2g} th={p['theta']:.3g} om={p['om1']:.3g}/{p['om2']:.3g} v={p['v']:.3g} mu={p['mu']} {out}")


if __name__ == "__main__":
    main()
