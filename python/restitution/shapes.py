"""Particle shapes: an exact disc, a regular n-gon, or any convex polygon."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _core
from ._engine import integer, real, reals


class _Round:
    """What the exact disc and the sphere share: one radius, no corners, no orientation."""

    r: float

    def __post_init__(self) -> None:
        _core.check_shape(0.0, real("r", self.r), 0.0)

    @property
    def n(self) -> int:
        """Shape code in sweeps: 0, no corners (the engine's column ``body`` tells a sphere)."""
        return 0

    @property
    def phi0_deg(self) -> float:
        """Orientation at first touch (irrelevant for a round body)."""
        return 0.0


@dataclass(frozen=True, kw_only=False)
class Disc(_Round):
    """An exact disc (closed-form circular-segment overlap).

    Parameters
    ----------
    r : float
        Radius in metres (> 0).
    """

    r: float = 0.01


@dataclass(frozen=True)
class RegularPolygon:
    """A regular n-gon of circumradius ``r``; vertices at ``phi0_deg + 360 k / n`` degrees.

    Parameters
    ----------
    r : float
        Circumradius in metres (> 0).
    n : int
        Number of corners (>= 3).
    phi0_deg : float
        Orientation at first touch, degrees, counter-clockwise from +x.
    """

    r: float = 0.01
    n: int = 120
    phi0_deg: float = 0.0

    def __post_init__(self) -> None:
        _core.check_shape(float(integer("n", self.n, minimum=3)), real("r", self.r), real("phi0_deg", self.phi0_deg))


@dataclass(frozen=True)
class ConvexPolygon:
    """Any convex polygon, from counter-clockwise vertices in its body frame (metres).

    The vertices are shifted so that the centroid is the origin; ``r`` is then the largest
    vertex distance from it. Non-convex, clockwise, duplicated, collinear or non-finite
    vertices raise ``ValueError``.

    Parameters
    ----------
    vertices : array-like of shape (k, 2)
    phi0_deg : float
        Orientation at first touch, degrees.
    """

    vertices: tuple[tuple[float, float], ...]
    phi0_deg: float = 0.0
    _template: np.ndarray = field(init=False, repr=False, compare=False)
    _r: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        v = reals("vertices", self.vertices)  # numbers by the rule of every numeric parameter
        if v.ndim != 2 or v.shape[1] != 2:
            raise ValueError(f"require `vertices` of shape (k, 2) (found shape {v.shape})")
        _core.check_shape(0.0, 1.0, real("phi0_deg", self.phi0_deg))
        # The engine checks them (at least 3, finite, distinct, counter-clockwise, strictly
        # convex) and returns them about the centroid, scaled to circumradius 1.
        template, r = _core.convex_template(np.ascontiguousarray(v))
        object.__setattr__(self, "vertices", tuple((float(a), float(b)) for a, b in v))
        object.__setattr__(self, "_template", np.ascontiguousarray(template))
        object.__setattr__(self, "_r", float(r))

    @property
    def r(self) -> float:
        """Circumradius about the centroid (m)."""
        return self._r

    @property
    def n(self) -> int:
        """Number of vertices."""
        return len(self.vertices)


@dataclass(frozen=True, kw_only=False)
class Sphere(_Round):
    """A sphere of radius ``r`` moving in its plane of incidence (x, y and the spin about z).

    A 3D body: mass 4/3 pi r^3 rho and moment of inertia 2/5 m r^2, and its records are per
    particle (kg, N, J), not per unit depth. Takes ``normal_law="hertz"`` (or ``"linear"``,
    with ``kn`` in N/m); docs/model.md, section 14.

    Parameters
    ----------
    r : float
        Radius in metres (> 0).
    """

    r: float = 0.0025


Shape = Disc | RegularPolygon | ConvexPolygon | Sphere
