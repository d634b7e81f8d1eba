"""The reference integrator against an independent high-accuracy computation (issue 18).

The polygon model is written here again from the equations of docs/model.md (overlap by clipping the
polygon to y <= 0, F_el = E A / L at the overlap centroid, F_d = gamma sqrt(m E) (dA/dt) / L at
the chord midpoint with dA/dt = -l (v_y + omega (x_mid - x_cm)), both clipped to zero when their
sum is negative), without calling the engine, and integrated with scipy's DOP853 at tight
tolerances, every corner crossing and clip switch located as a terminal event and the
integration restarted there. Frictionless (mu = 0), so the contact law is the normal force only.
"""

import math

import numpy as np
import pytest
import restitution as rs

scipy_integrate = pytest.importorskip("scipy.integrate")

R, V, RHO, E = 0.01, 0.0357, 2500.0, 1e7


def _polygon(n: int) -> np.ndarray:
    k = np.arange(n)
    return R * np.column_stack([np.cos(2 * np.pi * k / n), np.sin(2 * np.pi * k / n)])


def _mass_inertia(body: np.ndarray) -> tuple[float, float]:
    # Triangle fan about the centroid (the origin): area and polar second moment.
    a, b = body, np.roll(body, -1, axis=0)
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    area = 0.5 * cross.sum()
    polar = (cross * ((a * a).sum(1) + (a * b).sum(1) + (b * b).sum(1))).sum() / 12.0
    return RHO * area, RHO * polar


def _world(body: np.ndarray, s: np.ndarray) -> np.ndarray:
    c, sn = math.cos(s[2]), math.sin(s[2])
    return np.column_stack([s[0] + c * body[:, 0] - sn * body[:, 1], s[1] + sn * body[:, 0] + c * body[:, 1]])


def _overlap(p: np.ndarray) -> tuple[float, float, float, float]:
    """Area, centroid x, chord length and chord midpoint x of the polygon's part below y = 0."""
    out, crossings = [], []
    n = len(p)
    for i in range(n):
        a, b = p[i], p[(i + 1) % n]
        if a[1] <= 0.0:
            out.append(a)
        if (a[1] <= 0.0) != (b[1] <= 0.0):
            t = a[1] / (a[1] - b[1])
            x = a[0] + t * (b[0] - a[0])
            out.append(np.array([x, 0.0]))
            crossings.append(x)
    if len(out) < 3 or len(crossings) != 2:
        return 0.0, 0.0, 0.0, 0.0
    q = np.array(out)
    a, b = q, np.roll(q, -1, axis=0)
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    area = 0.5 * cross.sum()
    if area <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    cx = ((a[:, 0] + b[:, 0]) * cross).sum() / (6.0 * area)
    return area, cx, abs(crossings[1] - crossings[0]), 0.5 * (crossings[0] + crossings[1])


class Model:
    def __init__(self, n: int, gamma: float):
        self.body = _polygon(n)
        self.m, self.inertia = _mass_inertia(self.body)
        self.length = 4.0 * R
        self.damping = gamma * math.sqrt(self.m * E) / self.length

    def normal(self, s: np.ndarray) -> tuple[float, float, float, float]:
        """Unclipped F_el, F_d and their arms (x from the centre of mass)."""
        area, cx, chord, x_mid = _overlap(_world(self.body, s))
        f_el = E * area / self.length
        f_d = self.damping * (-chord * (s[4] + s[5] * (x_mid - s[0])))
        return f_el, f_d, cx - s[0], x_mid - s[0]

    def rhs(self, clip_on: bool):
        def f(_t, s):
            f_el, f_d, a_el, a_d = self.normal(s)
            if not clip_on or f_el + f_d < 0.0:
                f_el = f_d = 0.0
            return [s[3], s[4], s[5], 0.0, (f_el + f_d) / self.m, (a_el * f_el + a_d * f_d) / self.inertia]

        return f


def _events(model: Model, s: np.ndarray, clip_on: bool):
    heights = _world(model.body, s)[:, 1]
    near = np.flatnonzero(heights < 0.05 * R)
    evs = []
    for k in near:
        def corner(_t, y, k=k):
            return _world(model.body, y)[k, 1]

        corner.terminal = True
        evs.append(corner)

    def clip(_t, y):
        # Without an overlap there is nothing to clip (and F_el + F_d is exactly zero).
        f_el, f_d, _, _ = model.normal(y)
        return f_el + f_d if f_el > 0.0 else -1.0

    clip.terminal = True
    clip.direction = -1.0 if clip_on else 1.0
    evs.append(clip)
    return evs


def independent_impact(n: int, phi0_deg: float, theta_deg: float, omega_in: float, gamma: float) -> np.ndarray:
    """Final (vx, vy, omega) of the impact, every switch located."""
    model = Model(n, gamma)
    phi0 = math.radians(phi0_deg)
    s = np.array([0.0, 0.0, phi0, V * math.cos(math.radians(theta_deg)), -V * math.sin(math.radians(theta_deg)),
                  omega_in])
    s[1] = -_world(model.body, s)[:, 1].min()
    t_ref = math.sqrt(model.m / E)
    t, clip_on = 0.0, True
    for _ in range(400):
        sol = scipy_integrate.solve_ivp(model.rhs(clip_on), (t, t + 50 * t_ref), s, method="DOP853", rtol=1e-13,
                                        atol=1e-20, events=_events(model, s, clip_on), max_step=0.05 * t_ref)
        s, t = sol.y[:, -1].copy(), sol.t[-1]
        heights = _world(model.body, s)[:, 1]
        fired = [i for i, te in enumerate(sol.t_events) if len(te)]
        if fired and fired[-1] == len(sol.t_events) - 1 and (sol.t_events[-1][0] == t):
            clip_on = not clip_on
        elif not clip_on:
            f_el, f_d, _, _ = model.normal(s)
            clip_on = f_el + f_d > 0.0 and heights.min() < 0.0
        if heights.min() > 1e-3 * R and s[4] > 0.0:
            # Clear of the plate and rising (no force in flight): the final velocities.
            return s[3:6]
        # Step off the event by a hair so that it does not fire again at once.
        t_nudge = 1e-12 * t_ref
        s = s + t_nudge * np.array(model.rhs(clip_on)(t, s))
        t += t_nudge
    raise AssertionError("no separation")


@pytest.mark.parametrize("dt_factor", [0.2, 1.0])
def test_reference_matches_an_independent_computation_in_the_clipped_tail(dt_factor: float) -> None:
    # The case: the plate pulled in the clipped tail when the largest step was
    # >= 2 gamma (up to 4e-6 in e_N).
    omega_in = math.radians(-50.0)
    vx, vy, om = independent_impact(120, 0.0, 10.0, omega_in, 0.10)
    scene = rs.Scene(shape=rs.RegularPolygon(r=R, n=120, phi0_deg=0.0), gamma=0.10, gamma_t=0.0, mu=0.0,
                     integrator="reference", dt_factor=dt_factor)
    rec = rs.simulate(scene, theta_deg=10.0, omega_in=omega_in)
    v_n = V * math.sin(math.radians(10.0))
    assert rec.e_n == pytest.approx(vy / v_n, abs=1e-8)
    assert rec.omega_out * R / V == pytest.approx(om * R / V, abs=1e-8)
    assert rec.vx_out == pytest.approx(vx, abs=1e-12)
