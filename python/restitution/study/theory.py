"""Rigid-body theory of an oblique impact of a disc (or a sphere) on a flat plate.

The particle has moment of inertia ``I = kappa m r^2`` (``kappa = 1/2`` for a disc, ``2/5`` for a
sphere) and hits the plate with speed ``v`` at ``theta`` degrees from the plate and spin
``omega_in`` (rad/s, counter-clockwise positive; forward rolling is negative). With

    v_T = v cos(theta),  v_N = v sin(theta),  u = v_T + r omega_in  (the contact point's slip),
    A = mu (1 + e_N),    k = kappa / (1 + kappa),

a Coulomb impulse that slides throughout the contact gives (Sondergaard et al.; the study's Eq. 2)

    e_T = 1 - s A tan(theta),                    s = sign(u),
    omega_out = omega_in - s A v_N / (kappa r),

and that happens iff ``A v_N < k |u|``. Otherwise the contact point stops slipping (it "rolls"):

    e_T = 1 / (1 + kappa) - kappa r omega_in / ((1 + kappa) v_T),
    omega_out = -e_T v_T / r.

``e_N`` is an input (the theory does not predict it); pass the measured e_N(theta) to compare
with a simulation. All functions are vectorised (numpy broadcasting), take theta in degrees and
spins in rad/s, and default to the study's preset (r = 0.01 m, v = 0.0357 m/s, disc).

Examples
--------
>>> from restitution import theory
>>> round(float(theory.theta_c(mu=1.0, e_n=0.9)), 2)    # where sliding meets rolling
9.95
>>> float(theory.e_t(80.0, mu=1.0, e_n=0.9))            # rolling: 1 / (1 + 1/2)
0.6666666666666666
>>> round(float(theory.e_t(20.0, mu=0.1, e_n=0.9)), 4)  # sliding: 1 - 0.19 tan 20
0.9308
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._engine import real

#: kappa = I / (m r^2) for a disc and for a solid sphere.
DISC = 0.5
SPHERE = 0.4

#: The study's preset (docs/model.md, section 12): radius (m) and impact speed (m/s).
R_PAPER = 0.01
V_PAPER = 0.0357

ArrayLike = Any


def _kappa(kappa: float | str) -> float:
    if isinstance(kappa, str):
        if kappa not in ("disc", "sphere"):
            raise ValueError(f'require `kappa` "disc", "sphere" or a number in (0, 1] (found {kappa!r})')
        return DISC if kappa == "disc" else SPHERE
    k = float(kappa)
    if not (0.0 < k <= 1.0):
        raise ValueError(f'require `kappa` "disc", "sphere" or a number in (0, 1] (found {kappa!r})')
    return k


def _check(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, r: float, v: float) -> tuple[np.ndarray, ...]:
    th = np.asarray(theta_deg, dtype=float)
    if np.any(~((th > 0.0) & (th <= 90.0))):
        raise ValueError("require `theta_deg` in (0, 90] degrees, measured from the plate")
    m = np.asarray(mu, dtype=float)
    if np.any(~(m >= 0.0)):
        raise ValueError("require `mu` >= 0")
    en = np.asarray(e_n, dtype=float)
    if np.any(~((en >= 0.0) & (en <= 1.0))):
        raise ValueError("require `e_n` in [0, 1]")
    if not (real("r", r) > 0.0 and real("v", v) > 0.0):
        raise ValueError(f"require `r` > 0 and `v` > 0 (found r = {r}, v = {v})")
    return th, m, en


def _components(theta_deg: np.ndarray, omega_in: ArrayLike, r: float, v: float) -> tuple[np.ndarray, ...]:
    th = np.radians(theta_deg)
    # cos is exactly 0 at 90 deg, as in the engine's initial velocity.
    cos = np.where(theta_deg == 90.0, 0.0, np.cos(th))
    v_t = v * cos
    v_n = v * np.sin(th)
    u = v_t + r * np.asarray(omega_in, dtype=float)
    return v_t, v_n, u


def slides(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
           r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """True where the impact slides throughout: ``mu (1 + e_N) v_N < kappa / (1 + kappa) |v_T + r omega_in|``.

    >>> slides([5.0, 30.0], mu=0.5, e_n=0.9).tolist()
    [True, False]
    """
    k = _kappa(kappa)
    th, m, en = _check(theta_deg, mu, e_n, r, v)
    _, v_n, u = _components(th, omega_in, r, v)
    return m * (1.0 + en) * v_n < k / (1.0 + k) * np.abs(u)


def e_t_sliding(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
                r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Sliding-branch e_T = 1 - s mu (1 + e_N) tan(theta), s = sign(v_T + r omega_in) (NaN at 90 deg).

    ``kappa`` does not enter; it is accepted so that all functions share one signature.

    >>> round(float(e_t_sliding(45.0, mu=0.1, e_n=1.0)), 12)
    0.8
    """
    _kappa(kappa)
    th, m, en = _check(theta_deg, mu, e_n, r, v)
    v_t, v_n, u = _components(th, omega_in, r, v)
    s = np.where(u >= 0.0, 1.0, -1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(v_t > 0.0, 1.0 - s * m * (1.0 + en) * v_n / v_t, np.nan)


def e_t_rolling(theta_deg: ArrayLike, omega_in: ArrayLike = 0.0, *, r: float = R_PAPER, v: float = V_PAPER,
                kappa: float | str = DISC) -> np.ndarray:
    """Rolling-branch e_T = 1/(1+kappa) - kappa r omega_in / ((1+kappa) v_T) (NaN at 90 deg).

    >>> round(float(e_t_rolling(60.0, omega_in=-1.0, r=0.01, v=0.02)), 12)   # 2/3 + 0.01/(3 * 0.01)
    1.0
    """
    k = _kappa(kappa)
    th, _, _ = _check(theta_deg, 0.0, 0.0, r, v)
    v_t, _, _ = _components(th, 0.0, r, v)
    w = np.asarray(omega_in, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(v_t > 0.0, (1.0 - k * r * w / np.where(v_t > 0.0, v_t, 1.0)) / (1.0 + k), np.nan)


def e_t(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
        r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Rigid-body e_T: the sliding branch where :func:`slides`, else the rolling one (NaN at 90 deg).

    >>> e_t([5.0, 60.0], mu=1.0, e_n=0.9).round(4).tolist()
    [0.8338, 0.6667]
    """
    sl = slides(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa)
    return np.where(sl, e_t_sliding(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa),
                    e_t_rolling(theta_deg, omega_in, r=r, v=v, kappa=kappa))


def vx_out(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
           r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Tangential velocity after the impact (m/s); finite at 90 deg where e_T is not."""
    k = _kappa(kappa)
    th, m, en = _check(theta_deg, mu, e_n, r, v)
    v_t, v_n, u = _components(th, omega_in, r, v)
    s = np.where(u >= 0.0, 1.0, -1.0)
    sl = m * (1.0 + en) * v_n < k / (1.0 + k) * np.abs(u)
    return np.where(sl, v_t - s * m * (1.0 + en) * v_n, v_t - k * u / (1.0 + k))


def omega_out(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
              r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Spin after the impact (rad/s). The friction impulse P changes v_x by P/m and omega by
    P/(kappa m r); rolling ends with v_x' + r omega' = 0.

    >>> round(float(omega_out(60.0, mu=1.0, e_n=0.9, v=0.03, r=0.01)), 12)  # -(2/3) v cos60 / r
    -1.0
    """
    k = _kappa(kappa)
    w = np.asarray(omega_in, dtype=float)
    vx = vx_out(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa)
    v_t, _, _ = _components(np.asarray(theta_deg, dtype=float), omega_in, r, v)
    # Both branches from the impulse: P = m (vx' - v_T), d(omega) = P / (kappa m r).
    return w + (vx - v_t) / (k * r)


def e_kin(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
          r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Kinematic restitution |v'| / |v| = sqrt((vx'/v)^2 + (e_N sin theta)^2).

    >>> round(float(e_kin(90.0, mu=1.0, e_n=0.9)), 12)
    0.9
    """
    vx = vx_out(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa)
    th = np.radians(np.asarray(theta_deg, dtype=float))
    return np.hypot(vx / v, np.asarray(e_n, dtype=float) * np.sin(th))


def beta(theta_deg: ArrayLike, mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *,
         r: float = R_PAPER, v: float = V_PAPER, kappa: float | str = DISC) -> np.ndarray:
    """Contact-point restitution -u'/u (0 when rolling; NaN where u = 0).

    >>> round(float(beta(5.0, mu=0.1, e_n=1.0)), 4)   # sliding: -1 + 3 * 0.2 tan 5
    -0.9475
    """
    w = omega_out(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa)
    vx = vx_out(theta_deg, mu, e_n, omega_in, r=r, v=v, kappa=kappa)
    _, _, u = _components(np.asarray(theta_deg, dtype=float), omega_in, r, v)
    u_out = vx + r * w
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(u != 0.0, -u_out / np.where(u != 0.0, u, 1.0), np.nan)
    # Rolling ends with u' = 0 up to rounding: report an exact 0 there.
    return np.where(np.abs(u_out) <= 1e-12 * v, np.where(u != 0.0, 0.0, np.nan), b)


def theta_c(mu: ArrayLike, e_n: ArrayLike, omega_in: ArrayLike = 0.0, *, r: float = R_PAPER, v: float = V_PAPER,
            kappa: float | str = DISC) -> np.ndarray:
    """The smallest angle (degrees) at which the impact stops sliding throughout; NaN if it never does.

    Without spin, ``tan theta_c = kappa / ((1 + kappa) mu (1 + e_N))``: 9.95 deg at mu = 1 and
    e_N = 0.90 for a disc. With spin the boundary solves
    ``mu (1 + e_N) sin theta = k |cos theta + r omega_in / v|`` (k = kappa / (1 + kappa)), which can
    have two roots for forward spin (the impact slides backward again near 90 deg when
    ``mu (1 + e_N) < k r |omega_in| / v``); see :func:`regime_boundaries` for all of them.

    >>> round(float(theta_c(mu=1.0, e_n=0.9)), 4)
    9.9506
    >>> float(theta_c(mu=0.0, e_n=0.9))      # frictionless: slides at every angle
    nan
    """
    k = _kappa(kappa)
    m = np.asarray(mu, dtype=float)
    en = np.asarray(e_n, dtype=float)
    w = np.asarray(omega_in, dtype=float)
    _check(45.0, m, en, r, v)
    a = m * (1.0 + en)
    wr = r * w / v
    c = k / (1.0 + k)
    roots = _boundary_roots(a, c, wr)
    return _first(roots)


def _first(roots: np.ndarray) -> np.ndarray:
    filled = np.where(np.isnan(roots), np.inf, roots)
    first = np.min(filled, axis=0)
    return np.where(np.isinf(first), np.nan, first)


def _boundary_roots(a: np.ndarray, c: float, w: np.ndarray) -> np.ndarray:
    """Angles (deg) in (0, 90] where ``a sin t = c |cos t + w|`` and the regime changes from
    sliding (below) to rolling (above); shape (4, *broadcast). Unused slots are NaN.

    Each sign of ``cos t + w`` gives ``a sin t -+ c cos t = +- c w``, i.e. ``R sin(t -+ phi) = +- c w``
    with ``R = hypot(a, c)``, ``phi = atan2(c, a)``; the candidates are checked against the sign
    they assumed and against a change of regime from sliding to rolling.
    """
    a, w = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(w, dtype=float))
    R = np.hypot(a, c)
    phi = np.arctan2(c, a)
    cands = []
    with np.errstate(invalid="ignore", divide="ignore"):
        for sgn in (1.0, -1.0):
            # sgn = +1: cos t + w >= 0,  a sin t - c cos t = c w  ->  sin(t - phi) = c w / R
            # sgn = -1: cos t + w <= 0,  a sin t + c cos t = -c w ->  sin(t + phi) = -c w / R
            q = np.arcsin(np.clip(sgn * c * w / R, -1.0, 1.0))
            valid_q = np.abs(sgn * c * w / R) <= 1.0
            for t in ((phi + q) if sgn > 0 else (q - phi), (phi + np.pi - q) if sgn > 0 else (np.pi - q - phi)):
                ok = valid_q & (t > 0.0) & (t <= np.pi / 2 + 1e-12) & (a > 0.0)
                ok &= sgn * (np.cos(t) + w) >= -1e-12
                cands.append(np.where(ok, np.degrees(np.minimum(t, np.pi / 2)), np.nan))
    roots = np.stack(cands)
    # Keep sliding -> rolling transitions only: g(t) = c|cos t + w| - a sin t goes from > 0 to < 0.
    t = np.radians(roots)
    h = 1e-7
    with np.errstate(invalid="ignore"):
        g_after = c * np.abs(np.cos(t + h) + w) - a * np.sin(t + h)
        g_before = c * np.abs(np.cos(t - h) + w) - a * np.sin(t - h)
    keep = (g_before > 0.0) & (g_after <= 0.0)
    return np.where(keep, roots, np.nan)


def regime_boundaries(mu: float, e_n: float, omega_in: float = 0.0, *, r: float = R_PAPER, v: float = V_PAPER,
                      kappa: float | str = DISC) -> list[tuple[float, str]]:
    """Every angle in (0, 90] where the regime changes, with the regime above it ("rolling"/"sliding").

    Examples
    --------
    >>> [(round(t, 2), s) for t, s in regime_boundaries(0.1, 0.9, omega_in=-0.8727)]
    [(48.06, 'rolling')]
    >>> [(round(t, 2), s) for t, s in regime_boundaries(0.01, 0.9, omega_in=-0.8727)]
    [(72.61, 'rolling'), (79.14, 'sliding')]
    """
    k = _kappa(kappa)
    _check(45.0, mu, e_n, r, v)
    a, c, w = float(mu) * (1.0 + float(e_n)), k / (1.0 + k), r * float(omega_in) / v
    if a == 0.0:
        return []
    out = []
    # g(t) = c|cos t + w| - a sin t changes sign at most 4 times; find them on a fine grid, then bisect.
    t = np.linspace(1e-9, np.pi / 2, 20001)
    g = c * np.abs(np.cos(t) + w) - a * np.sin(t)
    idx = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]
    for i in idx:
        lo, hi = t[i], t[i + 1]
        glo = g[i]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            gm = c * abs(np.cos(mid) + w) - a * np.sin(mid)
            if np.sign(gm) == np.sign(glo):
                lo, glo = mid, gm
            else:
                hi = mid
        out.append((float(np.degrees(0.5 * (lo + hi))), "rolling" if g[i] > 0 else "sliding"))
    return out


def e_kin_min(mu: ArrayLike, e_n: ArrayLike, omega_in: float = 0.0, *, r: float = R_PAPER, v: float = V_PAPER,
              kappa: float | str = DISC, theta_range: tuple[float, float] = (4.0, 89.0)) -> tuple[np.ndarray, np.ndarray]:
    """Minimum of the rigid-body e_kin over theta in ``theta_range`` and its angle, per mu (constant e_N).

    Returns ``(e_kin_min, theta_at_min)``. The minimum is the kink at theta_c when the sliding
    branch still falls there (large mu), else a smooth minimum inside the sliding branch.

    >>> e, t = e_kin_min([1.0], 0.9)
    >>> round(float(t[0]), 2), round(float(e[0]), 4)
    (9.95, 0.6748)
    """
    m = np.atleast_1d(np.asarray(mu, dtype=float))
    en = np.broadcast_to(np.asarray(e_n, dtype=float), m.shape)
    th = np.linspace(theta_range[0], theta_range[1], 8501)
    best_e = np.empty(m.shape)
    best_t = np.empty(m.shape)
    for i, (mi, ei) in enumerate(zip(m, en)):
        grid = th
        for _ in range(3):  # zoom in: grid, then twice around the grid minimum
            ek = e_kin(grid, mi, ei, omega_in, r=r, v=v, kappa=kappa)
            j = int(np.argmin(ek))
            lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, len(grid) - 1)]
            tc = theta_c(mi, ei, omega_in, r=r, v=v, kappa=kappa)
            extra = [float(tc)] if np.isfinite(tc) and lo <= tc <= hi else []
            grid = np.unique(np.concatenate([np.linspace(lo, hi, 2001), extra]))
        ek = e_kin(grid, mi, ei, omega_in, r=r, v=v, kappa=kappa)
        j = int(np.argmin(ek))
        best_e[i], best_t[i] = ek[j], grid[j]
    return best_e, best_t


def e_n_for_theta_c(theta_c_deg: float, mu: float, *, kappa: float | str = DISC) -> float:
    """The e_N for which the spin-free rigid-body theta_c equals ``theta_c_deg`` at friction ``mu``.

    >>> round(float(e_n_for_theta_c(9.95, 1.0)), 4)
    0.9001
    """
    k = _kappa(kappa)
    return k / ((1.0 + k) * mu * np.tan(np.radians(theta_c_deg))) - 1.0


# --------------------------------------------------------------------------------------------
# Beyond the disc's rigid-body theory: the limits ensembles are checked against (model, 16.5-16.6)
# --------------------------------------------------------------------------------------------


def kappa_polygon(n: int) -> float:
    """I / (m r^2) of a regular n-gon of circumradius r: (1 + 2 cos^2(pi / n)) / 6.

    >>> round(kappa_polygon(4), 12), round(kappa_polygon(10**6), 9)   # a square: m a^2 / 6, a = r sqrt 2; a disc
    (0.333333333333, 0.5)
    """
    return (1.0 + 2.0 * math.cos(math.pi / n) ** 2) / 6.0


def polygon_impact(n: int, phi0_deg: ArrayLike, theta_deg: float, omega_in: float = 0.0, *, v: float = V_PAPER,
                   r: float = R_PAPER, e: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Rigid-body impact of a frictionless regular n-gon on the plate: (vx', vy', omega', impulses)
    for each orientation ``phi0_deg`` at first touch (docs/model.md, section 16.5).

    Each contact is a corner at rho = (rho_x, rho_y) from the centre receiving a normal impulse
    P with Newton's restitution ``e`` of the corner's normal velocity u_n = v_y + omega rho_x:
    ``P = -(1 + e) m u_n / (1 + m rho_x^2 / I)``, v_y += P / m, omega += rho_x P / I; v_x is
    unchanged (no friction). The body then flies freely until another corner reaches the plate,
    which takes its impulse in turn, until no corner can reach the plate again (the engine's
    rule: v_y > 0 and either y >= r or v_y > r |omega|). With e = 1 the kinetic energy is conserved.

    A face landing flat (two corners at once) is taken corner after corner, the sequence a
    soft contact approaches only if the first corner's contact ends before the second begins;
    such orientations are a set of measure zero under a uniform draw.

    >>> vx, vy, w, k = polygon_impact(4, 0.0, 90.0, v=1.0, r=1.0)    # a corner right below the centre
    >>> float(vy[0]), abs(round(float(w[0]), 12)), int(k[0])
    (1.0, 0.0, 1)
    """
    phis = np.atleast_1d(np.asarray(phi0_deg, dtype=float))
    out = np.array([_polygon_one(n, float(p), theta_deg, omega_in, v, r, e) for p in phis])
    return out[:, 0], out[:, 1], out[:, 2], out[:, 3].astype(np.int64)


def _polygon_one(n: int, phi0_deg: float, theta_deg: float, omega: float, v: float, r: float,
                 e: float) -> tuple[float, float, float, float]:
    inertia = kappa_polygon(n) * r * r  # per unit mass
    alpha = np.radians(phi0_deg + 360.0 * np.arange(n) / n)
    th = np.radians(theta_deg)
    vx, vy = v * (0.0 if theta_deg == 90.0 else np.cos(th)), -v * np.sin(th)
    y, phi = -r * float(np.min(np.sin(alpha))), 0.0
    corner, impulses = int(np.argmin(np.sin(alpha))), 0
    for _ in range(10_000):
        rho_x = r * np.cos(alpha[corner] + phi)
        u_n = vy + omega * rho_x
        if u_n < 0.0:
            impulse = -(1.0 + e) * u_n / (1.0 + rho_x * rho_x / inertia)
            vy, omega, impulses = vy + impulse, omega + rho_x * impulse / inertia, impulses + 1
        if vy > 0.0 and (y >= r or vy > r * abs(omega)):
            break
        hit = _next_touch(alpha, y, phi, vy, omega, r)
        if hit is None:
            break
        dt, corner = hit
        y, phi = y + vy * dt, phi + omega * dt
    return vx, vy, omega, float(impulses)


def _next_touch(alpha: np.ndarray, y: float, phi: float, vy: float, omega: float,
                r: float) -> tuple[float, int] | None:
    """(time, corner) of the next corner to reach the plate in free flight, or None: corners
    scanned on a grid of at least 2000 steps and 100 per radian turned, the crossing bisected."""
    horizon = (r - y) / vy if vy > 0.0 else (y / -vy if vy < 0.0 else 2.0 * np.pi / abs(omega))
    steps = int(min(max(2000, 100 * abs(omega) * horizon), 400_000))
    t = np.linspace(0.0, horizon * (1.0 + 1e-9), steps + 1)[1:]
    height = y + vy * t[:, None] + r * np.sin(alpha[None, :] + phi + omega * t[:, None])
    below = (height < 0.0).any(axis=1)
    if not below.any():
        return None
    i = int(np.argmax(below))
    corner = int(np.argmin(height[i]))
    lo, hi = (t[i - 1] if i > 0 else 0.0), t[i]
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if y + vy * mid + r * np.sin(alpha[corner] + phi + omega * mid) < 0.0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi), corner


#: 1 - e_N = C eps + O(eps^2) for a viscoelastic force k d^1.5 + (3/2) k A d^0.5 d', with
#: C = (6/5) (5/4)^(3/5) B(3/5, 3/2) (docs/model.md, section 16.6).
VISCOELASTIC_C = 1.2 * 1.25**0.6 * math.gamma(0.6) * math.gamma(1.5) / math.gamma(2.1)


def viscoelastic_epsilon(v_n: ArrayLike, *, gamma: float, E: float, rho: float, r: float) -> np.ndarray:
    """The dimensionless damping of the area law on an exact disc at normal speed ``v_n`` (m/s):
    eps = A (k / m)^(2/5) v_n^(1/5), with the small-overlap force k d^1.5 + (3/2) k A d^0.5 d',
    k = (E / 3) sqrt(2 / r), A = gamma sqrt(m / E), m = rho pi r^2 (docs/model.md, section 16.6).

    >>> round(float(viscoelastic_epsilon(0.0357, gamma=0.33, E=1e7, rho=2500.0, r=0.01)), 4)
    0.0614
    """
    m = rho * math.pi * r * r
    k = E / 3.0 * math.sqrt(2.0 / r)
    return gamma * math.sqrt(m / E) * (k / m) ** 0.4 * np.asarray(v_n, dtype=float) ** 0.2


def e_n_viscoelastic(v_n: ArrayLike, *, gamma: float, E: float, rho: float, r: float) -> np.ndarray:
    """First-order normal restitution of the area law on an exact disc, 1 - C eps, valid for
    small eps and small depth / r (docs/model.md, section 16.6): 1 - e_N grows as v_n^(1/5).

    >>> round(float(e_n_viscoelastic(1e-3, gamma=0.01, E=1e7, rho=2500.0, r=0.01)), 5)
    0.99843
    """
    return 1.0 - VISCOELASTIC_C * viscoelastic_epsilon(v_n, gamma=gamma, E=E, rho=rho, r=r)


__all__ = ["DISC", "SPHERE", "VISCOELASTIC_C", "beta", "e_kin", "e_kin_min", "e_n_for_theta_c", "e_n_viscoelastic",
           "e_t", "e_t_rolling", "e_t_sliding", "kappa_polygon", "omega_out", "polygon_impact", "regime_boundaries",
           "slides", "theta_c", "viscoelastic_epsilon", "vx_out"]
