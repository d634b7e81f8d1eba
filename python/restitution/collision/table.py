"""The tabulated outcome of an impact and its interpolation (numpy only, vectorised).

A table holds, at every node of a tensor grid over the pre-collision state

    theta_deg   impact angle from the plate (deg), in (0, 90]
    spin        omega r / |v|: the rim speed over the impact speed (1), the mirror-reduced sign
    v           impact speed |v| (m/s), interpolated in log v

and for each of ``n_draws`` draws of what the scene leaves open, three dimensionless outputs,
the velocities after the impact over the speed before it:

    vn_ratio    v_n' / |v|         normal velocity after (e_N sin theta)
    vt_ratio    v_t' / |v|         tangential velocity after (e_T cos theta)
    spin_out    omega' r / |v|     spin after, as a rim speed

All three stay of order one at every angle (e_N itself grows without bound at grazing angles
for a polygon, whose rotation feeds the rebound), so one absolute tolerance serves them all.

The deterministic operator interpolates the draws' mean multilinearly; the stochastic one picks
a neighbouring node with the multilinear weights as probabilities (one independent choice per
axis: lower node with probability 1 - t, upper with t) and one of its draws uniformly: a draw
from the mixture of the neighbours' tabulated distributions, whose mean is exactly the
deterministic value. Outside the grid each coordinate is clamped to its edge.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import RestitutionError

#: The table's axes and outputs, in storage order (docs/model.md, section 16.3).
AXES = ("theta_deg", "spin", "v")
OUTPUTS = ("vn_ratio", "vt_ratio", "spin_out")


@dataclass(frozen=True)
class Table:
    """Outcomes on a tensor grid: ``values[i_theta, i_spin, i_v, draw, output]``."""

    theta_deg: np.ndarray
    spin: np.ndarray
    v: np.ndarray
    values: np.ndarray
    r: float
    """The particle's circumradius (m): spins in the table are omega r / |v|."""
    mean: np.ndarray = field(init=False, repr=False)
    _flat: np.ndarray = field(init=False, repr=False)
    _strides: tuple[int, int, int] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        axes = [np.ascontiguousarray(getattr(self, a), dtype=np.float64) for a in AXES]
        shape = tuple(len(a) for a in axes)
        if self.values.shape[:3] != shape or self.values.ndim != 5 or self.values.shape[4] != len(OUTPUTS):
            raise ValueError(f"values of shape {self.values.shape} do not fit the grid {shape} x draws x 3")
        for name, a in zip(AXES, axes):
            if a.size == 0 or np.any(np.diff(a) <= 0):
                raise ValueError(f"require the `{name}` nodes strictly increasing (found {a})")
            object.__setattr__(self, name, a)
        values = np.ascontiguousarray(self.values, dtype=np.float64)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "mean", values.mean(axis=3))
        object.__setattr__(self, "_flat", values.reshape(-1, values.shape[3], len(OUTPUTS)))
        object.__setattr__(self, "_strides", (shape[1] * shape[2], shape[2], 1))

    @property
    def n_draws(self) -> int:
        return int(self.values.shape[3])

    @property
    def shape(self) -> tuple[int, int, int]:
        return tuple(self.values.shape[:3])  # type: ignore[return-value]

    def locate(self, theta_deg: np.ndarray, spin: np.ndarray, v: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """Per axis: (index of the lower node, fraction t in [0, 1] towards the upper one)."""
        return [_locate(self.theta_deg, theta_deg), _locate(self.spin, spin),
                _locate(np.log(self.v), np.log(v))]

    def mean_at(self, theta_deg: Any, spin: Any, v: Any) -> np.ndarray:
        """The interpolated mean outputs at the points, shape (m, 3)."""
        loc = self.locate(*_points(theta_deg, spin, v))
        mean = self.mean.reshape(-1, len(OUTPUTS))
        out = np.zeros((loc[0][0].size, len(OUTPUTS)))
        for index, weight in self._corners(loc):
            out += weight[:, None] * mean[index]
        return out

    def sample_at(self, theta_deg: Any, spin: Any, v: Any, rng: np.random.Generator) -> np.ndarray:
        """One draw per point from the mixture of the neighbouring nodes' draws, shape (m, 3)."""
        loc = self.locate(*_points(theta_deg, spin, v))
        m = loc[0][0].size
        index = np.zeros(m, dtype=np.int64)
        for (i, t), stride, size in zip(loc, self._strides, self.shape):
            upper = (rng.random(m) < t) & (i + 1 < size)
            index += (i + upper) * stride
        draw = rng.integers(0, self.n_draws, size=m)
        return self._flat[index, draw]

    def mixture(self, theta_deg: float, spin: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        """The stochastic operator's distribution at one point: (draws (k, 3), weights (k,))."""
        loc = self.locate(*_points(theta_deg, spin, v))
        values, weights = [], []
        for index, weight in self._corners(loc):
            if weight[0] > 0.0:
                values.append(self._flat[index[0]])
                weights.append(np.full(self.n_draws, weight[0] / self.n_draws))
        return np.concatenate(values), np.concatenate(weights)

    def _corners(self, loc: list[tuple[np.ndarray, np.ndarray]]) -> Any:
        """(flat node index, multilinear weight) of each of the 2^3 corners around the points."""
        for corner in range(8):
            index = np.zeros_like(loc[0][0])
            weight = np.ones(loc[0][0].shape)
            for k, ((i, t), stride, size) in enumerate(zip(loc, self._strides, self.shape)):
                up = (corner >> k) & 1
                if size == 1:
                    if up:
                        break
                    index = index + i * stride
                    continue
                index = index + (i + up) * stride
                weight = weight * (t if up else 1.0 - t)
            else:
                yield index, weight


def _locate(nodes: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    if nodes.size == 1:
        return np.zeros(x.shape, dtype=np.int64), np.zeros(x.shape)
    i = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
    lo, hi = nodes[i], nodes[i + 1]
    return i, np.clip((x - lo) / (hi - lo), 0.0, 1.0)


def _points(theta_deg: Any, spin: Any, v: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    th, sp, vv = np.broadcast_arrays(*(np.atleast_1d(np.asarray(a, dtype=np.float64)) for a in (theta_deg, spin, v)))
    return th.ravel(), sp.ravel(), vv.ravel()


def state_to_table(v_n: Any, v_t: Any, omega: Any, r: float) -> tuple[np.ndarray, ...]:
    """Pre-collision states (SI, the plate's convention: normal +y, v_n < 0 approaching, spin
    counter-clockwise) to table coordinates: (theta_deg, spin, speed, sign), where sign = -1
    mirrors a state moving in -x onto the table's v_t >= 0 half ((v_t, omega) -> (-v_t, -omega))."""
    vn, vt, om = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (v_n, v_t, omega)))
    for name, a in (("v_n", vn), ("v_t", vt), ("omega", om)):
        bad = ~np.isfinite(a)
        if bad.any():
            k = int(np.flatnonzero(bad.ravel())[0])
            raise RestitutionError(name, a.ravel()[k], f"finite (at index {k})")
    if np.any(vn >= 0.0):
        k = int(np.flatnonzero((vn >= 0.0).ravel())[0])
        raise RestitutionError("v_n", vn.ravel()[k], f"< 0: approaching the plate, whose normal is +y (at index {k})")
    sign = np.where(vt < 0.0, -1.0, 1.0)
    speed = np.hypot(vn, vt)
    theta = np.degrees(np.arctan2(-vn, np.abs(vt)))
    return theta, sign * om * r / speed, speed, sign


def outputs_to_state(out: np.ndarray, speed: np.ndarray, sign: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Table outputs (m, 3) back to (v_n', v_t', omega') in SI, the mirror undone."""
    shape = speed.shape
    vn_ratio, vt_ratio, spin_out = (out[:, k].reshape(shape) for k in range(3))
    return speed * vn_ratio, sign * speed * vt_ratio, sign * speed * spin_out / r


__all__ = ["AXES", "OUTPUTS", "Table", "outputs_to_state", "state_to_table"]
