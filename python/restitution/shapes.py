"""Particle shapes: an exact disc, a regular n-gon, or any convex polygon."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._validation import check_finite, check_int, check_positive


@dataclass(frozen=True, kw_only=False)
class Disc:
    """An exact disc (closed-form circular-segment overlap).

    Parameters
    ----------
    r : float
        Radius in metres (> 0).
    """

    r: float = 0.01

    def __post_init__(self) -> None:
        check_positive("r", self.r)

    @property
    def n(self) -> int:
        """Shape code in sweeps: 0 means an exact disc."""
        return 0

    @property
    def phi0_deg(self) -> float:
        """Orientation at first touch (irrelevant for a disc)."""
        return 0.0


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
        check_positive("r", self.r)
        check_int("n", self.n, minimum=3)
        check_finite("phi0_deg", self.phi0_deg)


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
        try:
            v = np.asarray(self.vertices, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise TypeError(f"`vertices` must be an array of shape (k, 2) of numbers ({e})") from None
        if v.ndim != 2 or v.shape[1] != 2 or v.shape[0] < 3:
            raise ValueError(f"require `vertices` of shape (k, 2) with k >= 3 (found shape {v.shape})")
        if not np.all(np.isfinite(v)):
            raise ValueError("require `vertices` finite (found NaN or inf)")
        check_finite("phi0_deg", self.phi0_deg)
        object.__setattr__(self, "vertices", tuple((float(a), float(b)) for a, b in v))
        c = _centroid(v)
        rel = v - c
        r = float(np.max(np.hypot(rel[:, 0], rel[:, 1])))
        object.__setattr__(self, "_template", np.ascontiguousarray(rel / r))
        object.__setattr__(self, "_r", r)
        _check_convex(v)

    @property
    def r(self) -> float:
        """Circumradius about the centroid (m)."""
        return self._r

    @property
    def n(self) -> int:
        """Number of vertices."""
        return len(self.vertices)


Shape = Disc | RegularPolygon | ConvexPolygon


def _centroid(v: np.ndarray) -> np.ndarray:
    # Shoelace sums about the vertex mean: about a far-away origin their terms cancel badly.
    o = v.mean(axis=0)
    x, y = v[:, 0] - o[0], v[:, 1] - o[1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    w = x * yn - xn * y
    a = w.sum() / 2.0
    if a == 0.0:
        return o
    return o + np.array([((x + xn) * w).sum(), ((y + yn) * w).sum()]) / (6.0 * a)


def _check_convex(v: np.ndarray) -> None:
    k = len(v)
    scale = float(np.max(np.hypot(v[:, 0], v[:, 1]))) or 1.0
    for i in range(k):
        for j in range(i + 1, k):
            if np.hypot(*(v[i] - v[j])) <= 1e-12 * scale:
                raise ValueError(f"require `vertices` distinct (found vertices {i} and {j} coinciding)")
    x, y = v[:, 0], v[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    if area <= 0.0:
        raise ValueError("require `vertices` in counter-clockwise order (found clockwise or zero area)")
    e0 = np.roll(v, -1, axis=0) - v
    e1 = np.roll(e0, -1, axis=0)
    cross = e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0]
    norms = np.hypot(e0[:, 0], e0[:, 1]) * np.hypot(e1[:, 0], e1[:, 1])
    if np.any(cross <= 1e-12 * norms):
        bad = int(np.argmax(cross <= 1e-12 * norms))
        raise ValueError(
            "require `vertices` to form a strictly convex polygon "
            f"(found a right turn or collinear vertices at vertex {(bad + 1) % k})"
        )
    turning = float(np.sum(np.arctan2(cross, np.sum(e0 * e1, axis=1))))
    if abs(turning - 2 * np.pi) > 1e-6:
        raise ValueError(f"require `vertices` to form a simple convex polygon (found total turning {turning:.4f} rad)")
