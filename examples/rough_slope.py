"""A particle bouncing down a rough slope, impact after impact: the full engine at every impact
against the collision operator (deterministic and stochastic) and the reduced models fitted to
it (Walton's, constant coefficients). Prints one summary line and writes rough_slope.png.

The slope (a rockfall code's usual model): a plane inclined at ALPHA; between impacts the
particle flies under gravity and lands back on the mean plane; at each impact the surface it
meets is tilted by a random angle psi ~ N(0, SIGMA_PSI) (the slope's roughness), clipped so
that the local impact angle stays in [THETA_MIN, 90] deg. Every run sees the same tilts.

- Exact disc: the engine's outcome is deterministic, so the trajectories can be compared impact
  by impact; the operator is also checked at every impact against the engine's own incoming state.
- Hexagon: its orientation at impact is what a point-particle code does not resolve, drawn
  uniformly at every impact of the engine runs; the stochastic operator draws from the tabulated
  distribution, the deterministic one takes its mean. Compared: the particles' speeds, as a
  distribution over particles, impact after impact.

Run: python examples/rough_slope.py [--quick] [--out DIR]
"""

import argparse
import math
import time
from pathlib import Path

import numpy as np
import polars as pl

import restitution as rs

ALPHA = math.radians(2.5)        # mean slope: gravity feeds about what the impacts take
SIGMA_PSI = math.radians(8.0)    # roughness: sd of the local tilt
THETA_MIN = 3.0                  # smallest local impact angle (deg)
G = 9.81
R = 0.01
V_RANGE = (0.05, 4.0)            # speeds the tables cover (m/s)

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--quick", action="store_true", help="fewer particles, impacts and coarser tables (seconds)")
ap.add_argument("--out", type=Path, default=Path("results"))
args = ap.parse_args()
PARTICLES, IMPACTS = (24, 40) if args.quick else (96, 80)
BASE = rs.Scene(E=1e9, gamma=0.33, mu=0.3, v=1.0, integrator="adaptive", tol=1e-7)
DISC = BASE.replace(shape=rs.Disc(R))
HEXAGON = BASE.replace(shape=rs.RegularPolygon(R, 6))
TILTS = np.random.default_rng(2024).normal(0.0, SIGMA_PSI, (IMPACTS, PARTICLES))


def engine_collide(scene, vary_phi):
    """The engine at every impact (one sweep per round of impacts, all particles at once)."""
    rng = np.random.default_rng(7)

    def collide(v_n, v_t, omega):
        s = np.where(v_t < 0.0, -1.0, 1.0)  # the engine takes v_t >= 0: mirror the rest
        cases = {"theta_deg": np.degrees(np.arctan2(-v_n, np.abs(v_t))), "v": np.hypot(v_n, v_t), "omega_in": s * omega}
        if vary_phi:
            cases["phi0_deg"] = rng.uniform(0.0, 60.0, v_n.size)
        df = rs.sweep(scene, cases=pl.DataFrame(cases))
        return df["vy_out"].to_numpy(), s * df["vx_out"].to_numpy(), s * df["omega_out"].to_numpy()

    return collide


def run(collide):
    """Bounces every particle IMPACTS times; returns (downslope distance, speed) per impact and the
    seconds spent in ``collide``."""
    vx, vy, om = np.full(PARTICLES, 1.0), np.full(PARTICLES, -0.5), np.zeros(PARTICLES)
    x = np.zeros(PARTICLES)
    xs, speeds, spent = [], [], 0.0
    for k in range(IMPACTS):
        theta_mean = np.degrees(np.arctan2(-vy, np.abs(vx)))
        psi = np.clip(TILTS[k], np.radians(THETA_MIN - theta_mean), np.radians(90.0 - theta_mean))
        psi = np.where(vx < 0.0, -psi, psi)  # a facet tilts against the motion as often as with it
        c, s = np.cos(psi), np.sin(psi)
        v_t, v_n = vx * c + vy * s, -vx * s + vy * c  # into the facet's frame
        t0 = time.perf_counter()
        v_n, v_t, om = collide(v_n, v_t, om)
        spent += time.perf_counter() - t0
        vx, vy = v_t * c - v_n * s, v_t * s + v_n * c
        # A rebound into the mean plane (off a facet tilted away) meets the next facet at once:
        # a hop of 1 mm/s normal speed, then a new impact with a fresh tilt.
        vy = np.maximum(vy, 1e-3)
        flight = 2.0 * vy / (G * math.cos(ALPHA))
        x = x + vx * flight + 0.5 * G * math.sin(ALPHA) * flight**2
        vx, vy = vx + G * math.sin(ALPHA) * flight, -vy
        xs.append(x.copy())
        speeds.append(np.hypot(vx, vy))
    return np.array(xs), np.array(speeds), spent


def per_impact_error(op, scene):
    """The operator against the engine at the incoming states of an engine run (disc)."""
    states = []

    def recording(v_n, v_t, omega):
        states.append((v_n.copy(), v_t.copy(), omega.copy()))
        return engine_collide(scene, False)(v_n, v_t, omega)

    run(recording)
    v_n, v_t, omega = (np.concatenate(a) for a in zip(*states))
    ours, theirs = op(v_n, v_t, omega), engine_collide(scene, False)(v_n, v_t, omega)
    speed = np.hypot(v_n, v_t)
    return np.abs(ours[0] - theirs[0]) / speed, np.abs(ours[1] - theirs[1]) / speed


def build(scene, vary):
    """The scene's operator over the slope's states (draws per node only for the hexagon)."""
    draws = None if vary is None else (16 if args.quick else 48)
    return rs.CollisionOperator.build(scene, theta_deg=np.linspace(THETA_MIN, 90.0, 8), v=np.geomspace(*V_RANGE, 4),
                                      omega_in=np.linspace(-1.5, 1.5, 5) * scene.v / R, vary=vary, n=draws,
                                      tol=2e-2 if args.quick else 3e-3, max_nodes=1500 if args.quick else 20000,
                                      n_check=64 if args.quick else 256, seed=1)


t0 = time.perf_counter()
disc_op = build(DISC, None)
hex_op = build(HEXAGON, {"phi0_deg": rs.Uniform(0.0, 60.0)})
build_s = time.perf_counter() - t0
walton, constant = hex_op.fit_walton(), hex_op.fit_constant()
print(f"tables built in {build_s:.1f} s: {disc_op}\n{hex_op}")
print(f"hexagon, Walton: {walton.summary()}; constant: {constant.summary()}")

disc = {"engine": run(engine_collide(DISC, False)), "operator": run(lambda *s: disc_op(*s))}
rng = np.random.default_rng(11)
hexagon = {"engine": run(engine_collide(HEXAGON, True)), "stochastic": run(lambda *s: hex_op(*s, rng=rng)),
           "deterministic": run(lambda *s: hex_op(*s)), "Walton": run(lambda *s: walton(*s)),
           "constant": run(lambda *s: constant(*s))}
err_n, err_t = per_impact_error(disc_op, DISC)
stated = dict(zip(disc_op.error["output"], disc_op.error["max_abs"]))

args.out.mkdir(parents=True, exist_ok=True)
from restitution.study.figures import OKABE_ITO, _plt  # noqa: E402 - matplotlib only for the figure

plt = _plt()
fig, ax = plt.subplots(2, 2, figsize=(11, 8))
k = np.arange(1, IMPACTS + 1)
for p in range(4):
    ax[0, 0].plot(k, disc["engine"][0][:, p], color=OKABE_ITO[(1, 2, 3, 6)[p]], lw=1.2, label="engine" if p == 0 else None)
    ax[0, 0].plot(k, disc["operator"][0][:, p], color=OKABE_ITO[(1, 2, 3, 6)[p]], ls="--", lw=1.2,
                  label="operator" if p == 0 else None)
ax[0, 0].set(xlabel="impact", ylabel="distance down the slope (m)", title="exact disc: four particles")
ax[0, 0].legend()
bins = np.geomspace(1e-9, 1.0, 50)
ax[0, 1].hist(err_n, bins=bins, alpha=0.6, label="v_n' / |v|")
ax[0, 1].hist(err_t, bins=bins, alpha=0.6, label="v_t' / |v|")
for name, colour in (("vn_ratio", "C0"), ("vt_ratio", "C1")):
    ax[0, 1].axvline(stated[name], color=colour, ls=":", lw=1.5)
ax[0, 1].set(xscale="log", xlabel="|operator - engine| at the engine's incoming states",
             title="disc: error per impact (dotted: stated)")
ax[0, 1].legend()
for (name, (_, speed, _)), colour in zip(hexagon.items(), [OKABE_ITO[i] for i in (0, 1, 2, 3, 6)]):
    q = np.quantile(speed, [0.25, 0.5, 0.75], axis=1)
    ax[1, 0].plot(k, q[1], color=colour, label=name)
    ax[1, 0].fill_between(k, q[0], q[2], color=colour, alpha=0.15, lw=0)
ax[1, 0].set(xlabel="impact", ylabel="speed after landing (m/s)", title="hexagon: median and 25-75 % of particles")
ax[1, 0].legend()
names = ["disc engine", "disc operator", *[f"hexagon {n}" for n in hexagon]]
cost = [disc["engine"][2], disc["operator"][2], *[h[2] for h in hexagon.values()]]
ax[1, 1].barh(names, np.array(cost) / (PARTICLES * IMPACTS) * 1e6, color=OKABE_ITO[5])
ax[1, 1].set(xscale="log", xlabel="us per impact (collisions only)", title="cost")
fig.tight_layout()
fig.savefig(args.out / "rough_slope.png")

final = {n: h[0][-1] for n, h in hexagon.items()}  # distance travelled after the last impact
se = {n: s.std(ddof=1) / math.sqrt(s.size) for n, s in final.items()}
speedup = hexagon["engine"][2] / hexagon["stochastic"][2]
disc_x = abs(disc["operator"][0][-1] - disc["engine"][0][-1]).mean() / disc["engine"][0][-1].mean()
print(f"rough slope ({PARTICLES} particles x {IMPACTS} impacts): disc per-impact error max v_n {err_n.max():.1e} "
      f"v_t {err_t.max():.1e} (stated {stated['vn_ratio']:.1e}, {stated['vt_ratio']:.1e}), distance gap {disc_x:.1%}; "
      "hexagon mean distance " + ", ".join(f"{n} {final[n].mean():.3f}+-{se[n]:.3f}" for n in hexagon)
      + f" m; operator {speedup:.0f}x faster than the engine; wrote {args.out / 'rough_slope.png'}")
