"""A collision operator for event-driven and rockfall codes, tabulated from the engine.

``op = rs.CollisionOperator.build(scene, theta_deg=..., omega_in=..., v=..., vary=...)``
tabulates the outcome of an impact over the pre-collision state (docs/model.md, section 16.2),
refining the grid until the interpolation error is within ``tol`` where the outcome is smooth,
and states its own error against the engine at points it was not built on (``op.error``).
``op(v_n, v_t, omega)`` maps NumPy arrays of pre-collision states to post-collision ones; with
``rng`` it draws from the tabulated distribution of what the scene leaves open. ``op.save`` /
``CollisionOperator.load`` write and read one Parquet file whose layout docs/model.md, section
16.3 documents for readers in any language. ``op.fit_walton()`` and ``op.fit_constant()`` fit
the reduced models and report what they cost (:mod:`restitution.collision.reduced`).

Examples
--------
>>> import numpy as np, restitution as rs
>>> scene = rs.Scene(mu=0.3, integrator="adaptive", tol=1e-8)
>>> op = rs.CollisionOperator.build(scene, theta_deg=np.linspace(10, 90, 9), omega_in=[-1.0, 0.0, 1.0],
...                                 tol=1e-2, n_check=16)
>>> v_n, v_t, omega = op(np.array([-0.02, -0.03]), np.array([0.02, -0.01]), np.array([0.0, 0.5]))
>>> bool(np.all(v_n > 0)), v_t.shape
(True, (2,))
>>> float(op.error.filter(op.error["output"] == "vn_ratio")["max_abs"][0]) < 1e-2
True
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import polars as pl

from .. import _engine
from .._core import __version__ as ENGINE_VERSION
from ..errors import RestitutionError, RestitutionFileError
from ..runs import config as _config
from ..runs.distributions import Distribution, Uniform, check_seed, from_dict
from ..runs._progress import want_progress
from ..runs.ensemble import SAMPLING, _Points
from ..runs.sweep import check_threads
from ..scene import Scene
from ..shapes import ConvexPolygon, RegularPolygon
from . import build as _build
from .table import AXES, OUTPUTS, Table, outputs_to_state, state_to_table

FORMAT = "restitution-operator/1"
META_KEY = "restitution.operator"
UNITS = {"theta_deg": "deg (from the plate; 90 head-on)", "spin": "1 (omega r / |v|, mirror-reduced)",
         "v": "m/s (|v|, interpolated in log v)", "vn_ratio": "1 (v_n' / |v|)", "vt_ratio": "1 (v_t' / |v|)",
         "spin_out": "1 (omega' r / |v|)", "r": "m"}


class CollisionOperator:
    """An impact's outcome tabulated over the pre-collision state, callable on NumPy arrays.

    Made by :meth:`build` or :meth:`load`. Attributes: ``table`` (the grid and the draws),
    ``scene``, ``vary`` and ``seed`` (what was tabulated), ``tol``, ``error`` (the stated
    interpolation error, per output), ``rough`` (a boolean per grid cell: True where
    refinement met a kink or jump it could not resolve), ``info`` (rounds, nodes, impacts,
    timed-out records, why refinement stopped).
    """

    def __init__(self, table: Table, *, scene: Scene, vary: Mapping[str, Distribution], seed: int, tol: float,
                 error: pl.DataFrame, rough: np.ndarray, info: Mapping[str, Any]) -> None:
        self.table, self.scene, self.vary, self.seed, self.tol = table, scene, dict(vary), seed, tol
        self.error, self.rough, self.info = error, np.asarray(rough, dtype=bool), dict(info)

    @classmethod
    def build(cls, scene: Scene, *, theta_deg: Any, omega_in: Any = 0.0, v: Any = None,
              vary: Mapping[str, Any] | None = None, n: int | None = None, seed: int = 0,
              sampling: str = "stratified", tol: float = 1e-3,
              max_rounds: int = 6, max_nodes: int = 20000, n_check: int = 256, threads: int | None = None,
              progress: bool | None = None) -> CollisionOperator:
        """Tabulates ``scene``'s impacts and refines the grid to ``tol``.

        Parameters
        ----------
        scene : Scene
            Everything but the pre-collision state (and the drawn parameters).
        theta_deg : array-like
            Starting nodes of the impact angle (deg, in (0, 90]); the table covers their range.
        omega_in : array-like
            Starting nodes of the spin, in rad/s at the scene's speed ``scene.v``: the table's
            axis is their ratio omega r / |v|, so at a speed v it covers omega_in v / scene.v.
        v : array-like, optional
            Starting nodes of the impact speed (m/s; interpolated in log v). Default: the
            scene's speed alone (then the outputs' ratios are taken as speed-independent).
        vary : mapping, optional
            Drawn parameters (as for :func:`restitution.ensemble`; not theta_deg, omega_in or v):
            each node holds ``n`` draws, the same draws at every node.
        n : int, optional
            Draws per node (default 64 with ``vary``, else 1).
        seed : int
            Seeds the draws and the validation points.
        sampling : {"stratified", "random"}
            How the n draws are made (:func:`restitution.ensemble`): stratified by default, since
            the same draws serve every node and their sampling error is one bias over the whole
            table (``error["sampling_se"]``), which a collision code compounds impact after impact.
        tol : float
            Target absolute error of the interpolated mean outputs (v_n' / |v|, v_t' / |v|, omega' r / |v|).
        max_rounds, max_nodes : int
            Refinement stops after this many rounds (>= 0) or before the grid exceeds this many
            nodes (>= 1). ``info["stopped"]`` says why it stopped: ``"converged"`` (every
            output's stated error within ``tol``), ``"rough"`` (nothing left to split, the error
            above ``tol`` only in rough cells), ``"unresolved"`` (nothing left to split, yet the
            error above ``tol`` in smooth cells: give more starting nodes), ``"max_rounds"`` or
            ``"max_nodes"``.
        n_check : int
            Validation points (not nodes) at which the stated error is measured.
        threads, progress :
            As for :func:`restitution.sweep`.
        """
        vary_d, n_draws = _check_build(scene, vary, n, tol, n_check)
        _check_settings(max_rounds=max_rounds, max_nodes=max_nodes, threads=threads, progress=progress)
        seed = check_seed(seed)
        spin = _engine.reals("omega_in", omega_in) * scene.r / scene.v
        grid = _build.initial_grid(theta_deg, spin, scene.v if v is None else v)
        if sampling not in SAMPLING:
            raise RestitutionError("sampling", repr(sampling), 'one of "stratified", "random"')
        ev = _build.Evaluator(scene, vary_d, n_draws, seed, sampling, threads, progress)
        grid, rough, info = _build.refine(ev, grid, tol=tol, max_rounds=max_rounds, max_nodes=max_nodes)
        table = ev.table(grid)
        error = _build.validate(ev, table, rough, _build.check_points(grid, n_check, seed))
        info.update(stopped=_build.verdict(info["stopped"], error, tol), impacts=ev.impacts, timed_out=ev.timed_out, n_check=n_check, sampling=sampling)
        return cls(table, scene=scene, vary=vary_d, seed=seed, tol=tol, error=error, rough=rough, info=info)

    def __call__(self, v_n: Any, v_t: Any, omega: Any, rng: Any = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Post-collision (v_n', v_t', omega') of pre-collision states (NumPy arrays, SI units).

        The plate's convention: its normal is +y, so ``v_n`` < 0 approaches it (refused
        otherwise, naming the index); ``v_t`` along the plate; ``omega`` counter-clockwise
        (rad/s). Without ``rng`` the interpolated mean of the tabulated outcome; with a
        ``numpy.random.Generator`` (or a seed) a draw from its tabulated distribution. States
        outside the table's domain are clamped to its edges (:attr:`domain`).
        """
        theta, spin, speed, sign = state_to_table(v_n, v_t, omega, self.table.r)
        if rng is None:
            out = self.table.mean_at(theta, spin, speed)
        else:
            out = self.table.sample_at(theta, spin, speed, np.random.default_rng(rng))
        return outputs_to_state(out, speed, sign, self.table.r)

    @property
    def domain(self) -> dict[str, tuple[float, float]]:
        """The tabulated range of each axis: theta_deg (deg), spin (omega r / |v|), v (m/s)."""
        return {a: (float(getattr(self.table, a)[0]), float(getattr(self.table, a)[-1])) for a in AXES}

    def __repr__(self) -> str:
        shape = " x ".join(str(s) for s in self.table.shape)
        worst = ", ".join(f"{r['output']} {r['max_abs']:.1e}" for r in self.error.iter_rows(named=True))
        return (f"CollisionOperator({shape} nodes x {self.table.n_draws} draws over {self.domain}; "
                f"largest error at {self.info.get('n_check')} check points: {worst})")

    def fit_walton(self) -> Any:
        """Walton's model (e, mu, beta_0) fitted to the table, with its error against it."""
        from .reduced import fit_walton

        return fit_walton(self)

    def fit_constant(self) -> Any:
        """Constant (e_N, e_T) fitted to the table, with its error against it."""
        from .reduced import fit_constant

        return fit_constant(self)

    def save(self, path: str | Path) -> Path:
        """Writes the table to one Parquet file (layout: docs/model.md, section 16.3)."""
        path = Path(path)
        meta = self._metadata()
        frame = _frame(self.table)
        frame.write_parquet(path, metadata={META_KEY: json.dumps(meta)})
        return path

    @classmethod
    def load(cls, path: str | Path) -> CollisionOperator:
        """Reads a table written by :meth:`save`, checking its format and digest.

        Raises :class:`~restitution.errors.RestitutionFileError` (a ``RestitutionError``)
        naming ``path`` for a file that is unreadable, truncated, foreign or edited."""
        path = Path(path)
        fix = "save the operator again (op.save) or rebuild it (CollisionOperator.build)"
        try:
            meta = json.loads(pl.read_parquet_metadata(path)[META_KEY])
            if not isinstance(meta, dict) or meta.get("format") != FORMAT:
                found = meta.get("format") if isinstance(meta, dict) else meta
                raise RestitutionFileError("path", str(path), f"its format is {found!r:.80}, this package reads "
                                           f"{FORMAT!r}; {fix}")
            frame = pl.read_parquet(path)
            values = frame.select(OUTPUTS).to_numpy().reshape(*tuple(meta["shape"]), len(OUTPUTS))
            if _digest(meta, values) != meta["sha256"]:
                raise RestitutionFileError("path", str(path), f"the table does not match its sha256 digest "
                                           f"(damaged or edited); {fix}")
            return cls._from(meta, values, str(path))
        except RestitutionFileError:
            raise
        except KeyError as err:
            problem = (f"it is not a collision operator (no `{META_KEY}` metadata)" if err.args == (META_KEY,)
                       else f"its metadata lacks {err}")
            raise RestitutionFileError("path", str(path), f"{problem}; {fix}") from None
        except (OSError, ValueError, TypeError, IndexError, pl.exceptions.PolarsError) as err:
            problem = " ".join(str(err).split())[:160]
            raise RestitutionFileError("path", str(path), f"not a collision operator this package can read, "
                                       f"unreadable, truncated or foreign ({type(err).__name__}: {problem}); "
                                       f"{fix}") from None

    @classmethod
    def _from(cls, meta: dict[str, Any], values: np.ndarray, source: str) -> CollisionOperator:
        """The operator of a file's checked metadata and values."""
        grid = {a: np.asarray(meta["grid"][a], dtype=np.float64) for a in AXES}
        table = Table(grid["theta_deg"], grid["spin"], grid["v"], values, meta["r"])
        scene = _config._scene({**meta["scene"], "preset": "default"}, _config.failer(source))
        return cls(table, scene=scene, vary={k: from_dict(d) for k, d in meta["vary"].items()}, seed=meta["seed"],
                   tol=meta["tol"], error=pl.DataFrame(meta["error"], infer_schema_length=None),
                   rough=_unflatten(meta["rough_cells"], table), info=meta["info"])

    def _metadata(self) -> dict[str, Any]:
        t = self.table
        body = {"format": FORMAT, "restitution_version": ENGINE_VERSION, "axes": list(AXES), "outputs": list(OUTPUTS),
                "shape": [*t.shape, t.n_draws], "grid": {a: getattr(t, a).tolist() for a in AXES}, "r": t.r,
                "units": UNITS, "scene": _Points(self.scene, axes={}).to_dict()["scene"],
                "vary": {k: d.to_dict() for k, d in self.vary.items()}, "seed": self.seed, "n_draws": t.n_draws,
                "tol": self.tol, "rough_cells": np.flatnonzero(self.rough).tolist(),
                "error": self.error.to_dicts(), "info": self.info}
        return {**body, "sha256": _digest(body, t.values)}


def _unflatten(cells: list[int], t: Table) -> np.ndarray:
    shape = tuple(max(n - 1, 1) for n in t.shape)
    out = np.zeros(int(np.prod(shape)), dtype=bool)
    out[np.asarray(cells, dtype=np.int64)] = True
    return out.reshape(shape)


def _frame(t: Table) -> pl.DataFrame:
    """The table's rows: i_theta slowest, then i_spin, i_v, draw fastest (C order)."""
    shape = (*t.shape, t.n_draws)
    idx = np.indices(shape).reshape(4, -1)
    cols: dict[str, Any] = {name: pl.Series(name, idx[k].astype(np.int32))
                            for k, name in enumerate(("i_theta", "i_spin", "i_v", "draw"))}
    for k, a in enumerate(AXES):
        cols[a] = getattr(t, a)[idx[k]]
    flat = t.values.reshape(-1, len(OUTPUTS))
    for k, out in enumerate(OUTPUTS):
        cols[out] = flat[:, k]
    return pl.DataFrame(cols)


def _digest(meta: Mapping[str, Any], values: np.ndarray) -> str:
    """SHA-256 of the metadata (without its digest; JSON, sorted keys) and the outputs (float64,
    little-endian, in row order)."""
    h = hashlib.sha256()
    h.update(json.dumps({k: v for k, v in meta.items() if k != "sha256"}, sort_keys=True).encode())
    h.update(np.ascontiguousarray(values, dtype="<f8").tobytes())
    return h.hexdigest()


def _check_build(scene: Scene, vary: Mapping[str, Any] | None, n: int | None, tol: float,
                 n_check: int) -> tuple[dict[str, Distribution], int]:
    """The drawn parameters and draws per node; refuses what the operator cannot honour."""
    if not isinstance(scene, Scene):
        raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
    if not (math.isfinite(_engine.real("tol", tol)) and tol > 0):
        raise RestitutionError("tol", tol, "finite and > 0 (absolute error of v_n' / |v|, v_t' / |v|, omega' r / |v|)")
    _engine.integer("n_check", n_check, 2)
    vary_d = {k: from_dict(d, f"vary.{k}") for k, d in (vary or {}).items()}
    for name in ("theta_deg", "omega_in", "v"):
        if name in vary_d:
            raise ValueError(f"`{name}` is an axis of the table (the pre-collision state); it cannot be drawn")
    n_draws = (64 if vary_d else 1) if n is None else n
    if isinstance(n_draws, bool) or not isinstance(n_draws, int) or n_draws < 1 or (n_draws > 1 and not vary_d):
        raise RestitutionError("n", repr(n), "an integer >= 1 (draws per node), and 1 unless `vary` draws something")
    _check_mirror(scene, vary_d)
    return vary_d, n_draws


def _check_settings(*, max_rounds: Any, max_nodes: Any, threads: Any, progress: Any) -> None:
    """The refinement's limits and the run's settings, refused by name before anything runs."""
    _engine.integer("max_rounds", max_rounds, 0)
    _engine.integer("max_nodes", max_nodes, 1)
    check_threads(threads)
    want_progress(progress, 0)


def _check_mirror(scene: Scene, vary: Mapping[str, Distribution]) -> None:
    """The table holds v_t >= 0 and mirrors the rest, (v_t, omega) -> (-v_t, -omega): exact for
    round bodies, and in distribution for regular polygons whose orientation is drawn uniformly
    over whole periods. Anything else would need the mirrored scene tabulated too."""
    shape = scene.shape
    if isinstance(shape, ConvexPolygon):
        raise ValueError("a ConvexPolygon scene has no mirror symmetry, which the operator uses for v_t < 0; "
                         "tabulate a regular polygon or a disc")
    ns = [shape.n] if isinstance(shape, RegularPolygon) else []
    if "n" in vary:
        ns = [int(k) for k in getattr(vary["n"], "values", ()) if int(k) >= 3]
    if not ns:
        return
    phi = vary.get("phi0_deg")
    periods = [(phi.hi - phi.lo) / (360.0 / k) for k in ns] if isinstance(phi, Uniform) else []
    if not periods or any(abs(p - round(p)) > 1e-9 or round(p) < 1 for p in periods):
        raise ValueError("a polygon's operator needs `phi0_deg` drawn uniformly over whole periods "
                         f"(vary={{'phi0_deg': rs.Uniform(0, 360 / n)}}) so that mirrored impacts (v_t < 0) "
                         "have the same distribution; an orientation fixed at impact is not mirror-symmetric")


__all__ = ["CollisionOperator", "FORMAT", "META_KEY"]
