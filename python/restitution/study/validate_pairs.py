"""Chung & Ooi's (2011) particle-particle tests for ``restitution validate`` (docs/model.md, 17.6):
Test 1 (two identical spheres head-on: Hertz's closed forms for the pair), Test 7 (two identical
spheres spinning in opposite senses, no slip at the contact: nothing tangential happens) and
Test 8 (a small sphere spinning onto a much larger, heavier one: the sliding branch against
rigid-body theory for the pair, in reduced variables).

Inputs as the benchmark gives them: Test 1 glass (E 48 GPa, nu 0.20, rho 2800) and limestone
(20 GPa, 0.25, 2500), R = 10 mm, +-10 m/s; Tests 7 and 8 aluminium alloy (70 GPa, 0.33, 2700) and
nylon (2.5 GPa, 0.40, 1000), R = 0.1 m, normal speed 0.2 m/s (each body's in Test 7, the
relative one in Test 8), cor 0.5, mu 0.4, Test 8's partner five times as large and a thousand
times as dense. Nothing is fitted.
"""

from __future__ import annotations

import math

import numpy as np
import polars as pl

from ..scene import Scene
from ..shapes import Sphere
from ..simulate import simulate
from ..runs.sweep import sweep

#: (E in Pa, Poisson's ratio, density in kg/m^3) of Tests 1, 7 and 8.
PAIR_MATERIALS = {
    "glass": (48e9, 0.20, 2800.0),
    "limestone": (20e9, 0.25, 2500.0),
    "Al alloy": (70e9, 0.33, 2700.0),
    "nylon": (2.5e9, 0.40, 1000.0),
}
#: Contact time of an elastic Hertz impact in units of delta_max / v: (4/5) B(2/5, 1/2).
HERTZ_TIME = 0.8 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
#: Incident spins of Tests 7 and 8 (rad/s), R = 0.1 m, v_n = 0.2 m/s: omega R / v_n = 0.0875 ... 11.
SPINS = np.array([0.175, 0.2, 0.3, 0.5, 0.7, 0.9, 1.3, 2.0, 3.0, 4.0, 5.0, 7.0, 9.0, 12.0, 22.0])


def pair_scene(material: str, r: float, partner_r: float, **changes: object) -> Scene:
    """Two Hertz-Mindlin spheres of one material (the partner's density may be changed)."""
    e, nu, rho = PAIR_MATERIALS[material]
    return Scene(shape=Sphere(r=r), partner=Sphere(r=partner_r), normal_law="hertz", E=e, nu=nu,
                 rho=rho, **{"integrator": "gear5", **changes})  # type: ignore[arg-type]


def hertz_pair(material: str, r: float, v: float) -> dict[str, float]:
    """Hertz's largest overlap, peak force and contact time of two identical elastic spheres
    of radius ``r`` meeting at relative speed ``v``: E* = E / (2 (1 - nu^2)), R* = r / 2,
    m* = m / 2 (docs/model.md, 17.3)."""
    e, nu, rho = PAIR_MATERIALS[material]
    m_star = 0.5 * 4.0 / 3.0 * math.pi * r**3 * rho
    e_star, r_star = e / (2.0 * (1.0 - nu * nu)), 0.5 * r
    delta = (15.0 * m_star * v * v / (16.0 * e_star * math.sqrt(r_star))) ** 0.4
    return {"max_overlap": delta, "peak_force": 4.0 / 3.0 * e_star * math.sqrt(r_star) * delta**1.5,
            "contact_time": HERTZ_TIME * delta / v}


def test1() -> tuple[pl.DataFrame, dict[str, pl.DataFrame]]:
    """Two identical spheres head-on at +-10 m/s (R = 10 mm): the engine's largest overlap, peak
    force and contact time against Hertz's; and each force-time trace."""
    rows, traces = [], {}
    r, v = 0.01, 20.0
    for material in ("glass", "limestone"):
        rec = simulate(pair_scene(material, r, r, cor=1.0, mu=0.35, v=v), 90.0, trace=True)
        assert rec.trace is not None
        engine = {"max_overlap": rec.max_depth, "peak_force": float(rec.trace["f_n"].max()),
                  "contact_time": rec.contact_time}
        hertz = hertz_pair(material, r, v)
        for q, value in engine.items():
            rows.append({"material": material, "quantity": q, "engine": value, "hertz": hertz[q],
                         "deviation": value / hertz[q] - 1.0})
        traces[material] = rec.trace.select("t", "f_n", "depth")
    return pl.DataFrame(rows), traces


def test7() -> pl.DataFrame:
    """Two identical spheres (R = 0.1 m) head-on at +-0.2 m/s, spinning at +-omega: the contact
    point does not slip (g_t + r omega1 + r omega2 = 0), so the spins stay and no tangential
    velocity appears. The residuals, per material and spin."""
    frames = []
    for material in ("Al alloy", "nylon"):
        scene = pair_scene(material, 0.1, 0.1, cor=0.5, mu=0.4, v=0.4)
        for w in SPINS:
            rec = simulate(scene, 90.0, omega_in=float(w), partner_omega_in=-float(w))
            frames.append({"material": material, "omega_in": float(w),
                           "spin_change": rec.omega_out - w, "partner_spin_change": rec.partner_omega_out + w,
                           "tangential_after": rec.vx_out, "e_n": rec.e_n})
    return pl.DataFrame(frames)


def test8_scene(material: str) -> Scene:
    """Test 8's pair: R = 0.1 m on R = 0.5 m a thousand times as dense, cor 0.5, mu 0.4, 0.2 m/s."""
    _, _, rho = PAIR_MATERIALS[material]
    return pair_scene(material, 0.1, 0.5, partner_rho=1000.0 * rho, cor=0.5, mu=0.4, v=0.2)


def tangential_mass(scene: Scene) -> tuple[float, float]:
    """(m*, m_t) of a sphere pair: 1/m* = 1/m1 + 1/m2, 1/m_t = 1/m* + r1^2/I1 + r2^2/I2 with
    I = (2/5) m r^2, so r^2/I = 5/(2 m)."""
    assert scene.partner is not None
    m1 = 4.0 / 3.0 * math.pi * scene.r**3 * scene.rho
    rho2 = scene.partner_rho if scene.partner_rho is not None else scene.rho
    m2 = 4.0 / 3.0 * math.pi * scene.partner.r**3 * rho2
    m_star = 1.0 / (1.0 / m1 + 1.0 / m2)
    return m_star, 1.0 / (1.0 / m_star + 2.5 / m1 + 2.5 / m2)


def rigid_recoil(psi: np.ndarray, e_n: float, mu: float, m_star: float, m_t: float) -> np.ndarray:
    """Rigid-body theory of the pair in reduced variables: a normal impulse m* (1 + e) v_n and, while
    the contact point slides, mu times it along the slip; the slip velocity v_c falls by
    mu (1 + e) v_n m*/m_t. With psi = v_c / v_n before, the recoil v_c' / v_n' after is
    (psi - mu (1 + e) m*/m_t) / e while sliding throughout, and 0 once the slip stops."""
    drop = mu * (1.0 + e_n) * m_star / m_t
    return np.where(psi > drop, (psi - drop) / e_n, 0.0)


def test8() -> pl.DataFrame:
    """Test 8: the small sphere spins (omega R / v_n from 0.09 to 11) onto the large, heavy one
    head-on; the contact point's recoil v_c' / v_n' against psi = v_c / v_n, with rigid-body
    theory (the engine's e_N)."""
    frames = []
    for material in ("Al alloy", "nylon"):
        scene = test8_scene(material)
        df = sweep(scene, theta_deg=90.0, omega_in=SPINS, progress=False)
        m_star, m_t = tangential_mass(scene)
        psi = df["omega_in"].to_numpy() * scene.r / scene.v
        # The contact point's slip after: beta = -v_c' / v_c, the normal velocity after e_N v_n.
        recoil = -df["beta"].to_numpy() * psi / df["e_n"].to_numpy()
        theory = rigid_recoil(psi, float(df["e_n"].mean()), scene.mu, m_star, m_t)
        frames.append(pl.DataFrame({"material": material, "psi": psi, "recoil": recoil, "recoil_theory": theory,
                                    "e_n": df["e_n"], "sliding": psi > scene.mu * (1 + df["e_n"].mean()) * m_star / m_t}))
    return pl.concat(frames)


def report_lines(t1: pl.DataFrame, t7: pl.DataFrame, t8: pl.DataFrame) -> list[str]:
    """Tests 1, 7 and 8 in words and numbers (markdown lines)."""
    sliding = t8.filter(pl.col("sliding"))
    gap = (sliding["recoil"] - sliding["recoil_theory"]).abs()
    return [
        "## Test 1: two identical spheres head-on, against Hertz's closed forms for the pair", "",
        "| material | quantity | deviation |", "|---|---|---|",
        *[f"| {m} | {q} | {d:.2e} |" for m, q, d in t1.select("material", "quantity", "deviation").iter_rows()], "",
        "## Test 7: opposite spins at zero contact slip", "",
        f"largest |spin change| {t7['spin_change'].abs().max():.2e} rad/s (partner "
        f"{t7['partner_spin_change'].abs().max():.2e}), largest tangential velocity after "
        f"{t7['tangential_after'].abs().max():.2e} m/s, over omega = {SPINS[0]:g} ... {SPINS[-1]:g} rad/s.", "",
        "## Test 8: a small sphere spinning onto a large, heavy one", "",
        f"On the sliding branch ({sliding.height} of {t8.height} impacts) the recoil v_c'/v_n' follows rigid-body "
        f"theory for the pair to {gap.max():.2e} (largest absolute deviation); below it the compliant contact "
        "recoils where the rigid one stops (Maw's micro-slip).", "",
    ]


def figures(t1_traces: dict[str, pl.DataFrame], t8: pl.DataFrame, path_t1, path_t8) -> None:  # noqa: ANN001
    """Test 1's force against overlap, and Test 8's recoil against psi with rigid-body theory."""
    from .figures import THEORY_STYLE, _plt

    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for material, tr in t1_traces.items():
        ax.plot(tr["depth"] * 1e6, tr["f_n"] / 1e3, label=material)
    ax.set(xlabel=r"overlap $\delta$ ($\mu$m)", ylabel="normal force (kN)",
           title="Test 1: two identical spheres head-on (+-10 m/s)")
    ax.legend()
    fig.savefig(path_t1, bbox_inches="tight")
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for material in ("Al alloy", "nylon"):
        df = t8.filter(pl.col("material") == material).sort("psi")
        ax.plot(df["psi"], df["recoil"], "o-", label=f"{material} (engine)")
        ax.plot(df["psi"], df["recoil_theory"], **THEORY_STYLE)
    ax.set(xlabel=r"$\psi = v_c / v_n$ before", ylabel=r"$v_c' / v_n'$ after",
           title="Test 8: small sphere on a large, heavy one (dashed: rigid-body theory)")
    ax.legend()
    fig.savefig(path_t8, bbox_inches="tight")
    plt.close(fig)
