"""Building a collision table: the engine at the nodes, refinement to a tolerance, validation.

Refinement (docs/model.md, section 16.2). On a tensor grid, the interpolation error of an
interval of axis k is measured where it is largest for a smooth function, at its midpoint: the
engine there against the mean of the interval's two ends (what multilinear interpolation gives
at a midpoint), the largest over the nodes of the other axes and the three outputs. Intervals
whose error exceeds ``tol`` are split at their midpoint (whose values are then already known),
every axis in the same round, until none exceeds it, or an interval reaches its axis' smallest
width (it is then marked *rough*: a kink or jump of the outcome, such as the sliding-rolling
transition, that refinement cannot resolve), or the grid would exceed ``max_nodes``.

Validation. The interpolated mean is then compared with the engine at ``n_check`` points drawn
uniformly over the domain (theta, spin, log v), which are not nodes: per output the largest,
95th-percentile and rms absolute error, over all points and over those in smooth cells; with
drawn parameters also the sampling error of the tabulated means (against an independent set of
draws) and the Wasserstein-1 distance between the stochastic operator's distribution and the
engine's draws at each check point.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import polars as pl

from .. import _engine
from ..runs.ensemble import EnsembleSpec
from ..runs.sweep import SweepSpec, run_in_memory
from ..scene import Scene
from .table import AXES, OUTPUTS, Table

#: Smallest interval refinement makes, per axis (theta in degrees, spin, log v).
MIN_WIDTH = {"theta_deg": 0.05, "spin": 1e-3, "v": 1e-3}
#: Halving a smooth interval divides its midpoint error by 4, one with a kink by about 2: an
#: interval whose error fell by less than this factor's inverse is marked rough.
SMOOTH_RATIO = 0.35
#: Stream of the validation points (apart from every drawn parameter's).
_CHECK_KEY = 0xC4EC


class Evaluator:
    """The engine's outputs at table coordinates, each node computed once (cached).

    With ``vary``, each point runs the ``n`` draws of an ensemble (the same draws at every
    point: the tabulated samples line up from node to node); without, one impact."""

    def __init__(self, scene: Scene, vary: Mapping[str, Any] | None, n: int, seed: int, sampling: str,
                 threads: int | None, progress: bool | None) -> None:
        self.scene, self.vary, self.n, self.seed, self.sampling = scene, dict(vary or {}), n, seed, sampling
        self.threads, self.progress = threads, progress
        self._cache: dict[tuple[float, float, float], np.ndarray] = {}
        self.impacts = 0
        self.timed_out = 0

    def values(self, theta: np.ndarray, spin: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Outputs at the points, shape (m, n, 3)."""
        keys = list(zip(theta.tolist(), spin.tolist(), v.tolist()))
        missing = list(dict.fromkeys(k for k in keys if k not in self._cache))
        if missing:
            for key, value in zip(missing, self._run(np.array(missing))):
                self._cache[key] = value
        return np.stack([self._cache[k] for k in keys]) if keys else np.empty((0, self.n, 3))

    def _run(self, pts: np.ndarray) -> np.ndarray:
        theta, spin, v = pts[:, 0], pts[:, 1], pts[:, 2]
        cases = pl.DataFrame({"theta_deg": theta, "omega_in": spin * v / self.scene.r, "v": v})
        spec: SweepSpec = (EnsembleSpec(self.scene, n=self.n, vary=self.vary, seed=self.seed, cases=cases,
                                        sampling=self.sampling) if self.vary else SweepSpec(self.scene, cases=cases))
        df = run_in_memory(spec, threads=self.threads, progress=self.progress)
        self.impacts += df.height
        self.timed_out += int(df["timed_out"].sum())
        vv = np.repeat(v, self.n)
        out = np.column_stack([df["vy_out"].to_numpy() / vv, df["vx_out"].to_numpy() / vv,
                               df["omega_out"].to_numpy() * self.scene.r / vv])
        return out.reshape(len(pts), self.n, len(OUTPUTS))

    def table(self, grid: Mapping[str, np.ndarray]) -> Table:
        """The table on ``grid`` (nodes computed as needed)."""
        mesh = np.meshgrid(*(grid[a] for a in AXES), indexing="ij")
        values = self.values(*(m.ravel() for m in mesh))
        shape = tuple(len(grid[a]) for a in AXES)
        return Table(grid["theta_deg"], grid["spin"], grid["v"], values.reshape(*shape, self.n, len(OUTPUTS)),
                     self.scene.r)


def _midpoints(axis: str, nodes: np.ndarray) -> np.ndarray:
    if axis == "v":  # v is interpolated in log v
        return np.sqrt(nodes[:-1] * nodes[1:])
    return 0.5 * (nodes[:-1] + nodes[1:])


def _widths(axis: str, nodes: np.ndarray) -> np.ndarray:
    return np.diff(np.log(nodes)) if axis == "v" else np.diff(nodes)


def edge_errors(ev: Evaluator, grid: dict[str, np.ndarray], axis: str) -> np.ndarray:
    """Midpoint error of every edge along ``axis`` (each interval of the axis at each node of
    the others), the largest over the outputs: the engine's mean at the midpoint against the
    mean of the edge's two ends. Shape: the grid's, one less along ``axis``."""
    k = AXES.index(axis)
    nodes = grid[axis]
    at_mid = {a: (_midpoints(axis, nodes) if a == axis else grid[a]) for a in AXES}
    mid = ev.table(at_mid).mean
    ends = ev.table(grid).mean
    lower = np.take(ends, np.arange(len(nodes) - 1), axis=k)
    upper = np.take(ends, np.arange(1, len(nodes)), axis=k)
    return np.abs(mid - 0.5 * (lower + upper)).max(axis=3)


Edge = tuple[float, float, tuple[float, ...]]
"""An edge: (lower node, upper node, the other axes' coordinates)."""


def _edges(grid: Mapping[str, np.ndarray], axis: str, err: np.ndarray) -> list[tuple[Edge, float]]:
    k = AXES.index(axis)
    nodes = grid[axis]
    out = []
    for ind, e in zip(np.ndindex(err.shape), err.ravel().tolist()):
        others = tuple(float(grid[a][ind[m]]) for m, a in enumerate(AXES) if m != k)
        out.append(((float(nodes[ind[k]]), float(nodes[ind[k] + 1]), others), e))
    return out


def refine(ev: Evaluator, grid: dict[str, np.ndarray], *, tol: float, max_rounds: int,
           max_nodes: int) -> tuple[dict[str, np.ndarray], np.ndarray, dict[str, Any]]:
    """Splits intervals until their edges' midpoint errors are within ``tol`` (module doc).

    Returns (grid, rough cells, what happened)."""
    rough: dict[str, set[Edge]] = {a: set() for a in AXES}
    stopped, rounds, pending = "converged", 0, 0
    for rounds in range(max_rounds + 1):
        splits: dict[str, np.ndarray] = {}
        for axis in AXES:
            if len(grid[axis]) >= 2:
                splits[axis], rough[axis] = _splits(ev, axis, _edges(grid, axis, edge_errors(ev, grid, axis)), tol)
        pending = sum(len(x) for x in splits.values())
        if not pending:
            break
        new_size = int(np.prod([len(grid[a]) + len(splits.get(a, ())) for a in AXES]))
        if rounds == max_rounds or new_size > max_nodes:
            stopped = "max_rounds" if rounds == max_rounds else "max_nodes"
            break
        grid = {a: np.union1d(grid[a], splits.get(a, np.empty(0))) for a in AXES}
    info = {"rounds": rounds, "stopped": stopped, "nodes": int(np.prod([len(grid[a]) for a in AXES])),
            "unresolved_intervals": pending if stopped != "converged" else 0}
    return grid, rough_cells(grid, rough), info


def verdict(stopped: str, error: pl.DataFrame, tol: float) -> str:
    """Why refinement stopped, as the stated error shows it: ``"converged"`` only where every
    output's largest error at the check points is within ``tol``. Refinement that found nothing
    more to split with a larger error is ``"rough"`` when the excess lies in rough cells only,
    else ``"unresolved"`` (the midpoint test was satisfied on too coarse a grid: give more
    starting nodes). ``"max_rounds"`` and ``"max_nodes"`` stay as they are."""
    if stopped != "converged" or error["max_abs"].to_numpy().max() <= tol:
        return stopped
    smooth = error["max_abs_smooth"].drop_nulls().to_numpy()
    return "rough" if smooth.size == 0 or smooth.max() <= tol else "unresolved"


def _splits(ev: Evaluator, axis: str, edges: list[tuple[Edge, float]], tol: float) -> tuple[np.ndarray, set[Edge]]:
    """(midpoints of the intervals to split, the rough edges) from the edges over ``tol``.

    An edge over ``tol`` is *rough* when its halves' midpoint errors (the engine at its
    quarter points, which are the next round's midpoints anyway) are not at most
    :data:`SMOOTH_RATIO` of its own: a smooth function's fall fourfold when the interval is
    halved, a kink's by at most about two, a jump's not at all. Or when it is at its axis'
    smallest width. A rough edge is no reason to split; its cells are left out of the smooth
    error."""
    failing = [(edge, e) for edge, e in edges if e > tol]
    if not failing:
        return np.empty(0), set()
    k = AXES.index(axis)
    lo = np.array([edge[0] for edge, _ in failing])
    hi = np.array([edge[1] for edge, _ in failing])
    mid = _midpoints(axis, np.array([lo, hi]).T.ravel())[::2]
    q1, q3 = (_midpoints(axis, np.array([a, b]).T.ravel())[::2] for a, b in ((lo, mid), (mid, hi)))
    others = np.array([edge[2] for edge, _ in failing]).reshape(len(failing), 2)
    f = {}
    for name, x in (("lo", lo), ("q1", q1), ("mid", mid), ("q3", q3), ("hi", hi)):
        cols = np.insert(others, k, x, axis=1)
        f[name] = ev.values(cols[:, 0], cols[:, 1], cols[:, 2]).mean(axis=1)
    halves = np.maximum(np.abs(f["q1"] - 0.5 * (f["lo"] + f["mid"])), np.abs(f["q3"] - 0.5 * (f["mid"] + f["hi"])))
    ratio = halves.max(axis=1) / np.array([e for _, e in failing])
    width = np.log(hi / lo) if axis == "v" else hi - lo
    is_rough = (ratio > SMOOTH_RATIO) | (width <= 2.0 * MIN_WIDTH[axis])
    rough = {edge for (edge, _), r in zip(failing, is_rough) if r}
    return np.unique(mid[~is_rough]), rough


def rough_cells(grid: Mapping[str, np.ndarray], rough: Mapping[str, set[Edge]]) -> np.ndarray:
    """Cells (one per interval of each axis; one along an axis of a single node) touching a
    rough edge of the final grid."""
    shape = tuple(max(len(grid[a]) - 1, 1) for a in AXES)
    out = np.zeros(shape, dtype=bool)
    for k, axis in enumerate(AXES):
        nodes = grid[axis]
        for lo, hi, others in rough[axis]:
            i = int(np.searchsorted(nodes, lo))
            if i + 1 >= len(nodes) or nodes[i] != lo or nodes[i + 1] != hi:
                continue  # split since (at another node of the other axes): not an edge any more
            index: list[Any] = []
            for m, a in enumerate(AXES):
                if m == k:
                    index.append([i])
                    continue
                j = int(np.searchsorted(grid[a], others[m if m < k else m - 1]))
                index.append([c for c in (j - 1, j) if 0 <= c < shape[m]] if len(grid[a]) > 1 else [0])
            out[np.ix_(*index)] = True
    return out


def check_points(grid: Mapping[str, np.ndarray], n_check: int, seed: int) -> np.ndarray:
    """``n_check`` points drawn uniformly over the grid's domain (theta, spin, log v), (m, 3)."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(_CHECK_KEY,)))
    cols = []
    for axis in AXES:
        lo, hi = grid[axis][0], grid[axis][-1]
        if axis == "v":
            cols.append(np.exp(rng.uniform(np.log(lo), np.log(hi), n_check)) if hi > lo else np.full(n_check, lo))
        else:
            cols.append(rng.uniform(lo, hi, n_check) if hi > lo else np.full(n_check, lo))
    return np.column_stack(cols)


def in_rough_cell(table: Table, rough: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Whether each point lies in a rough cell."""
    index = tuple(np.minimum(i, n - 1) for (i, _), n in zip(table.locate(pts[:, 0], pts[:, 1], pts[:, 2]),
                                                           rough.shape))
    return rough[index]


def validate(ev: Evaluator, table: Table, rough: np.ndarray, pts: np.ndarray) -> pl.DataFrame:
    """The table's error at ``pts`` against the engine, per output (see the module doc)."""
    direct = ev.values(pts[:, 0], pts[:, 1], pts[:, 2])
    err = np.abs(table.mean_at(pts[:, 0], pts[:, 1], pts[:, 2]) - direct.mean(axis=1))
    smooth = ~in_rough_cell(table, rough, pts)
    n = table.n_draws
    se = _sampling_error(ev, pts, direct) if n > 1 else np.full(3, np.nan)
    w1 = np.array([[wasserstein1(*_component(table.mixture(*p), k), direct[j, :, k]) for k in range(3)]
                   for j, p in enumerate(pts)]) if n > 1 else np.full((len(pts), 3), np.nan)
    rows = []
    for k, out in enumerate(OUTPUTS):
        e = err[:, k]
        rows.append({"output": out, "n_points": len(pts), "max_abs": e.max(), "p95_abs": np.quantile(e, 0.95),
                     "rms": float(np.sqrt(np.mean(e**2))), "n_smooth": int(smooth.sum()),
                     "max_abs_smooth": float(e[smooth].max()) if smooth.any() else None,
                     "sampling_se": _finite(se[k]), "w1_median": _finite(np.median(w1[:, k])),
                     "w1_max": _finite(w1[:, k].max())})
    return pl.DataFrame(rows, schema={"output": pl.String, "n_points": pl.Int64, "max_abs": pl.Float64,
                                      "p95_abs": pl.Float64, "rms": pl.Float64, "n_smooth": pl.Int64,
                                      "max_abs_smooth": pl.Float64, "sampling_se": pl.Float64,
                                      "w1_median": pl.Float64, "w1_max": pl.Float64})


def _sampling_error(ev: Evaluator, pts: np.ndarray, direct: np.ndarray) -> np.ndarray:
    """How far a mean over the table's n draws lies from the distribution's mean, per output:
    the rms over the points of the difference between the means of the table's draws and of an
    independent set (the draws of seed + 1, made the same way), over sqrt 2. The table's draws
    are the same at every node, so this error is one coherent bias over the whole table, and it
    compounds over many impacts."""
    other = Evaluator(ev.scene, ev.vary, ev.n, (ev.seed + 1) % 2**63, ev.sampling, ev.threads, ev.progress)
    fresh = other.values(pts[:, 0], pts[:, 1], pts[:, 2])
    ev.impacts += other.impacts
    diff = direct.mean(axis=1) - fresh.mean(axis=1)
    return np.sqrt(np.mean(diff**2, axis=0) / 2.0)


def _component(mix: tuple[np.ndarray, np.ndarray], k: int) -> tuple[np.ndarray, np.ndarray]:
    return mix[0][:, k], mix[1]


def _finite(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def wasserstein1(a: np.ndarray, wa: np.ndarray, b: np.ndarray) -> float:
    """The Wasserstein-1 distance between a weighted sample (a, wa) and an unweighted one (b):
    the integral of |F_a - F_b| over x.

    Examples
    --------
    >>> wasserstein1(np.array([0.0, 1.0]), np.array([0.5, 0.5]), np.array([0.5, 1.5]))
    0.5
    """
    wb = np.full(len(b), 1.0 / len(b))
    x = np.concatenate([a, b])
    w = np.concatenate([wa / wa.sum(), -wb])
    order = np.argsort(x, kind="stable")
    diff = np.cumsum(w[order])[:-1]  # F_a - F_b between consecutive values
    return float(np.sum(np.abs(diff) * np.diff(x[order])))


def initial_grid(theta_deg: Any, spin: Any, v: Any) -> dict[str, np.ndarray]:
    """The starting nodes: sorted, distinct, checked per axis."""
    grid = {}
    for axis, values in zip(AXES, (theta_deg, spin, v)):
        a = np.unique(np.atleast_1d(_engine.reals(axis, values)))
        if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
            raise ValueError(f"require `{axis}` finite numbers (found {values!r:.80})")
        grid[axis] = a
    return grid


__all__ = ["Evaluator", "check_points", "edge_errors", "initial_grid", "refine", "rough_cells", "validate",
           "wasserstein1"]
