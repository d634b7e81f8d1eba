"""One impact: ``simulate(scene, theta_deg, omega_in)`` returns a typed :class:`Record`."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import polars as pl

from . import _engine
from .scene import Scene


@dataclass(frozen=True)
class Record:
    """What one impact returns (the record of docs/model.md; its columns are the engine's
    ``RECORD_COLUMNS``, in order). Velocities in m/s, spins in rad/s, energies in J/m."""

    theta_deg: float
    """Impact angle from the plate (degrees; input)."""
    omega_in: float
    """Spin before impact (rad/s, counter-clockwise positive; input)."""
    partner_omega_in: float
    """The partner's spin before impact (rad/s; input; 0 for the plate)."""
    e_n: float
    """Normal restitution -vy'/vy (a pair: -(g' . n_0) / (g . n_0), g the relative velocity, n_0 the
    normal at first touch: negative where the pair turns by more than the impact angle)."""
    e_t: float | None
    """Tangential restitution vx'/vx of the centre of mass; None at theta = 90."""
    e_kin: float
    """Kinematic restitution |v'|/|v|."""
    omega_out: float
    """Spin after the impact (rad/s)."""
    beta: float | None
    """Contact-point restitution -v_cp'/v_cp, v_cp = vx + r omega; None when v_cp = 0."""
    rebound_angle_deg: float
    """atan2(vy', vx') in degrees."""
    vx_out: float
    vy_out: float
    contact_time: float
    """Time with overlap (s), all contacts, the clipped tail included."""
    steps: int
    """Integration steps from first touch to the end."""
    contacts: int
    """Number of contacts (a spinning polygon may hit again)."""
    max_depth: float
    """Largest depth of the lowest point (m)."""
    max_area: float
    """Largest overlap area (m^2)."""
    slip_events: int
    """Stick-to-slip transitions (a dt-dependent micro-slip diagnostic)."""
    energy_in: float
    energy_out: float
    work_normal: float
    """Work of the normal force on the body, elastic and damping parts (<= 0 where the law has a
    potential)."""
    work_friction: float
    """Work of the tangential force on the body (<= 0)."""
    energy_residual: float
    """(energy_out - energy_in - work_normal - work_friction) / energy_in."""
    separated: bool
    """The particle left the plate and no part of it can reach the plate again."""
    timed_out: bool
    """The impact ended on a budget before separating (``stop`` says which)."""
    step_budget: int
    """The step budget it ran under: ``Scene.max_steps`` or the default (``steps <= step_budget``)."""
    stop: str
    """Why it ended: "separated", "step_budget", "contact_time_budget" or "non_finite"."""
    err_est: float | None
    """Estimated largest absolute error among e_N, e_T, e_kin and omega_out r / v: always for
    ``integrator="adaptive"`` / ``"reference"``, for gear5 / verlet with ``Scene(error_estimate=True)``;
    None otherwise (null in frames)."""
    e_n_sep: float
    """Normal restitution with the normal at separation, -(g' . n_s) / (g . n_0) (a pair; on the
    plate, whose normal never turns, ``e_n``)."""
    normal_rotation_deg: float
    """Angle from the normal at first touch to the normal at separation (degrees,
    counter-clockwise positive; 0 on the plate)."""
    partner_omega_out: float
    """The partner's spin after the impact (rad/s; 0 for the plate)."""
    partner_vx_out: float
    """The partner's velocity after the impact, in the frame where it was at rest before (m/s;
    0 for the plate)."""
    partner_vy_out: float
    momentum_residual: float | None
    """|linear momentum after - before| over the largest momentum in the balance (docs/model.md
    17.4): round-off for a pair (integrated in its centre-of-mass frame); None for the plate."""
    angular_momentum_residual: float | None
    """(angular momentum about the pair's centre of mass after - before) over its largest term,
    at least m* v (r1 + r2): round-off for a pair (restored by a rigid turn, docs/model.md 17.2);
    None for the plate."""
    work_damping: float
    """The part of ``work_normal`` done by the normal dashpot (<= 0); ``work_normal - work_damping``
    is the elastic force's: <= 0 where the law has a potential, of either sign for the area law
    between bodies with corners (docs/model.md 7.7)."""
    trace: pl.DataFrame | None = None
    """Per-step history when ``simulate(..., trace=True)``: t, x, y, phi, vx, vy, omega, f_n, f_t,
    area, depth, xi, partner_phi, partner_omega, stick (0 none, 1 stick, 2 slip). For a pair x, y,
    vx, vy are the particle's relative to the partner, f_n and f_t act along and across the line of
    centres, depth is the overlap of the centres' distance."""

    def as_dict(self) -> dict[str, object]:
        """The record without its trace."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "trace"}


def simulate(scene: Scene, theta_deg: float, omega_in: float = 0.0, partner_omega_in: float = 0.0, *,
             trace: bool = False) -> Record:
    """Simulates one impact of ``scene``'s particle at ``theta_deg`` from the plate (or its partner)
    with spin ``omega_in``.

    Parameters
    ----------
    scene : Scene
    theta_deg : float
        Impact angle from the plate in degrees, in (0, 90] (90 is head-on).
    omega_in : float
        Spin before impact in rad/s (counter-clockwise positive; forward rolling is negative).
    partner_omega_in : float
        The partner's spin before impact in rad/s (``Scene(partner=...)``; 0 for the plate).
    trace : bool
        Also return the per-step history as ``record.trace`` (a polars DataFrame).

    Examples
    --------
    >>> import restitution as rs
    >>> rec = rs.simulate(rs.Scene(mu=0.0, gamma=0.0), theta_deg=30.0)
    >>> round(rec.e_n, 6), rec.e_t
    (1.0, 1.0)

    Two identical discs head-on at +-v are one disc on the plate at v:

    >>> pair = rs.Scene(partner=rs.Disc(0.01))
    >>> a, b = rs.simulate(rs.Scene(), 90.0), rs.simulate(pair.replace(v=2 * pair.v), 90.0)
    >>> abs(a.e_n - b.e_n) < 3 * rs.Scene().tol  # each to its tolerance; Gear-5's to round-off
    True
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
    theta = _engine.real("theta_deg", theta_deg)
    omega = _engine.real("omega_in", omega_in)
    partner_omega = _engine.real("partner_omega_in", partner_omega_in)
    trace = _engine.boolean("trace", trace)
    row = _engine.with_values(scene._engine_row(), theta_deg=theta, omega_in=omega, partner_omega_in=partner_omega)
    try:
        if trace:
            values, trace_frame = _engine.trace_one(row, scene.template_vertices())
        else:
            values, trace_frame = _engine.run_one(row, scene.template_vertices()), None
    except _engine.RestitutionError as err:
        raise err.at_case(None) from None  # one impact: no case to name
    return _record((theta, omega, partner_omega), values, trace_frame)


def _record(inputs: tuple[float, float, float], values: tuple[Any, ...], trace: pl.DataFrame | None) -> Record:
    """The Record of an impact's inputs, its record's ``values`` (in ``RECORD_COLUMNS`` order) and
    its trace, built without the frozen dataclass's ``__init__``: that sets each of the 27 fields
    through ``object.__setattr__``, 7.7 us, most of the cost of a ``simulate`` call beyond its
    impact. The same object otherwise (frozen, equal, hashable, printable);
    ``tests/test_simulate.py`` checks that its fields are the inputs, the record columns and the trace."""
    rec = object.__new__(Record)
    theta_deg, omega_in, partner_omega_in = inputs
    rec.__dict__.update(zip(_engine.RECORD_COLUMNS, values), theta_deg=theta_deg, omega_in=omega_in,
                        partner_omega_in=partner_omega_in, trace=trace)
    return rec
