"""Ensembles as sweeps: ``n`` drawn impacts at every point of the swept axes.

An :class:`EnsembleSpec` is a :class:`~restitution.runs.sweep.SweepSpec` whose cases are
(point, draw) pairs: the points are the Cartesian product of the axes (or the rows of a cases
table), and at each point ``n`` impacts draw the parameters of ``vary`` from their
distributions. Case ``i`` is point ``i // n``, draw ``j = i % n``; draw ``j``'s values depend
only on ``(seed, name, j)`` (:mod:`restitution.runs.distributions`), so

- the rows do not depend on the chunk size, the thread count or the machine (Dask);
- every point sees the same ``n`` draws (common random numbers): a difference between two
  angles is the physics', not two samples' noise, and the draws of an operator's table line up
  from node to node.

Everything a sweep does follows: chunks, progress and Ctrl-C, Parquet datasets with manifest,
digest and resume (the manifest holds ``n``, ``seed`` and the distributions), Dask.

Refused draws. The engine refuses some parameter values (a depth beyond r / 2 when a drawn
speed is too high, a negative drawn mu ...). With ``on_refused="raise"`` (the default) every
case is checked before any impact runs (about 0.4 us per case, streamed), and a refusal raises
:class:`~restitution.RestitutionError` naming the parameter, the first refused case and how
many are refused: truncate the distribution (``rs.Normal(0.5, 0.2, lo=0.0)``) to what the model
describes. With ``on_refused="skip"`` the refused cases keep their row with null record
columns and the engine's reason in the ``refused`` column; statistics are then those of the
accepted draws (the distribution conditioned on the model accepting it), and the summary says
how many were refused.
"""

from __future__ import annotations

import numbers
import sys
import time
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import polars as pl

from .. import _engine
from ..errors import RestitutionError
from ..scene import ConvexPolygon, Scene
from . import config as _config
from ._progress import Progress, want_progress
from .distributions import Choice, Distribution, check_seed, from_dict
from .sweep import AXES, SweepSpec, axis_values

#: What to do with draws the engine refuses (see the module doc).
ON_REFUSED = ("raise", "skip")
#: How the n draws are made: independently, or stratified (a Latin hypercube: each parameter's
#: n draws fall one in each of n equal-probability strata; :func:`distributions.stratified`).
SAMPLING = ("random", "stratified")
#: Cases probed per engine call in the up-front check (a chunk's worth: memory stays a chunk's).
_CHECK_BLOCK = 8192
#: An up-front check estimated (from its first block) to take longer than this says so first.
LONG_CHECK_S = 10.0


def _duration(seconds: float) -> str:
    """A duration in the unit that reads best (s, min, h, days, years)."""
    for unit, size in (("years", 365.25 * 86400), ("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:,.1f} {unit}"
    return f"{seconds:,.0f} s"


class _Points(SweepSpec):
    """The swept points of an ensemble: axes or a cases table, ``theta_deg`` optional (it may be
    drawn), checked with their draws by the ensemble rather than alone."""

    _needs_theta = False

    def _check_product(self) -> None:
        pass

    def _check_cases(self) -> None:
        pass


class EnsembleSpec(SweepSpec):
    """What an ensemble computes: ``n`` draws of ``vary`` at each point of ``axes`` (or ``cases``).

    Parameters
    ----------
    scene : Scene
        Values of every parameter that is neither an axis nor drawn.
    n : int
        Draws per point (>= 1).
    vary : mapping
        Parameter name (any sweep axis) to a distribution (``rs.Uniform``, ``rs.Normal``,
        ``rs.LogNormal``, ``rs.Choice``, or its dict form).
    seed : int
        The draws' seed, in [0, 2^63).
    axes, cases :
        The points, as for :class:`~restitution.runs.sweep.SweepSpec`; ``theta_deg`` must be an
        axis, a column or drawn.
    on_refused : {"raise", "skip"}
        See the module doc.
    sampling : {"random", "stratified"}
        Independent draws, or stratified ones (each parameter's n draws one per stratum of
        probability 1 / n; the mean over them converges much faster, the bootstrap intervals of
        :meth:`Ensemble.summary` are then conservative).
    max_cases : int, optional
        Refuse (naming ``n``) more cases than this, before any work (the in-memory ensemble's
        :data:`~restitution.runs.sweep.MAX_IN_MEMORY_CASES`).
    progress : bool, optional
        A progress line for the up-front check of every case (``on_refused="raise"``); by
        default shown on a terminal when the first block's rate says it takes over
        :data:`LONG_CHECK_S`, after a line with the estimate.
    """

    def __init__(self, scene: Scene, *, n: int, vary: Mapping[str, Any], seed: int,
                 axes: Mapping[str, Any] | None = None, cases: pl.DataFrame | None = None,
                 on_refused: str = "raise", sampling: str = "random", max_cases: int | None = None,
                 progress: bool | None = None) -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
            raise RestitutionError("n", repr(n), "an integer >= 1 (draws per point)")
        if on_refused not in ON_REFUSED:
            raise RestitutionError("on_refused", repr(on_refused), 'one of "raise", "skip"')
        if sampling not in SAMPLING:
            raise RestitutionError("sampling", repr(sampling), 'one of "random", "stratified"')
        self.sampling: str = sampling
        self.scene = scene
        self.n_draws: int = int(n)
        self.seed: int = check_seed(seed)
        self.on_refused: str = on_refused
        self.vary: dict[str, Distribution] = _check_vary(vary, scene)
        swept = set(cases.columns) if isinstance(cases, pl.DataFrame) else set(axes or {})
        both = sorted(swept & set(self.vary))
        if both:
            raise ValueError(f"`{both[0]}` is both swept and drawn: give it as an axis or in `vary`, not both")
        if "theta_deg" not in swept and "theta_deg" not in self.vary:
            raise ValueError("`theta_deg` is required: an axis (a scalar or 1-D array in (0, 90]) or drawn in `vary`")
        self.points: SweepSpec = _Points(scene, axes=axes, cases=cases)
        self.cases = self.points.cases
        self.axes = self.points.axes
        self.n_points: int = self.points.n_cases
        self.n_cases = self.n_points * self.n_draws
        if max_cases is not None and self.n_cases > max_cases:
            raise RestitutionError("n", self.n_draws, f"such that points x n is at most {max_cases:,} cases in "
                                   f"memory (here {self.n_points:,} points x n = {self.n_cases:,}); stream them "
                                   "to disk with rs.ensemble_to_dataset, or draw fewer")
        want_progress(progress, 0)  # refused now if it is not True, False or None
        if on_refused == "raise":
            self._check_all(progress)

    @property
    def point_names(self) -> tuple[str, ...]:
        """The swept axes (or the cases table's columns): one distribution per value."""
        return self.points.axis_names

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Input columns of the result: the swept axes, ``draw``, the drawn parameters."""
        return self.point_names + ("draw",) + tuple(self.vary)

    def to_dict(self, chunk_size: int | None = None, cases_file: str | None = None) -> dict[str, Any]:
        """The config structure, fully expanded, with an ``ensemble`` table (n, seed, on_refused)
        and a ``vary`` table (each distribution's dict form): what the manifest stores."""
        body = self.points.to_dict(chunk_size, cases_file)
        body["ensemble"] = {"n": self.n_draws, "seed": self.seed, "on_refused": self.on_refused,
                            "sampling": self.sampling}
        body["vary"] = {name: d.to_dict() for name, d in self.vary.items()}
        return body

    def engine_inputs(self, start: int, stop: int) -> dict[str, np.ndarray]:
        """Cases ``start:stop``: the engine values of the swept and drawn columns."""
        return self._inputs(start, stop, shown=False)[0]

    def inputs(self, start: int, stop: int) -> tuple[dict[str, np.ndarray], pl.DataFrame]:
        """Cases ``start:stop``: (engine values per column, the result's input columns)."""
        per_case, shown = self._inputs(start, stop, shown=True)
        assert shown is not None
        return per_case, shown

    def _inputs(self, start: int, stop: int, shown: bool) -> tuple[dict[str, np.ndarray], pl.DataFrame | None]:
        if not 0 <= start <= stop <= self.n_cases:
            raise ValueError(f"require 0 <= start <= stop <= {self.n_cases} (found {start}, {stop})")
        i = np.arange(start, stop, dtype=np.int64)
        point, draw = i // self.n_draws, i % self.n_draws
        per_case: dict[str, np.ndarray] = {}
        frames = []
        if self.point_names and stop > start:
            p0 = int(point[0])
            at_points, points_shown = self.points.inputs(p0, int(point[-1]) + 1)
            per_case = {name: col[point - p0] for name, col in at_points.items()}
            frames.append(points_shown[point - p0])
        for name, dist in self.vary.items():
            per_case[name] = _engine_column(name, dist, self._draw(dist, name, draw), self.scene)
        if not shown:
            return per_case, None
        frames.append(pl.DataFrame([pl.Series("draw", draw)] + [_shown(name, per_case[name]) for name in self.vary]))
        return per_case, pl.concat(frames, how="horizontal")

    def run(self, start: int, stop: int, threads: int = 0) -> pl.DataFrame:
        """Runs cases ``start:stop``: input columns, the record's, then ``refused`` (null, or why
        the engine refused the case when ``on_refused="skip"``)."""
        per_case, shown = self.inputs(start, stop)
        m = stop - start
        cols = _engine.columns(self.scene.engine_values(), per_case, m)
        vertices = self.scene.template_vertices()
        reasons: dict[int, str] = {}
        if self.on_refused == "skip":
            reasons = dict(refused_cases(cols, vertices, threads=threads))
        if reasons:
            keep = np.setdiff1d(np.arange(m), np.fromiter(reasons, dtype=np.int64))
            raw = _engine.run({k: v[keep] for k, v in cols.items()}, vertices, threads) if keep.size else None
            records = _scatter_records(raw, keep, m)
        else:
            try:
                records = _engine.records_frame(_engine.run(cols, vertices, threads))
            except RestitutionError as err:  # a refusal the up-front check did not see
                raise self._advise(err.at_case(start + (err.case or 0)), None) from None
        refused = pl.Series("refused", [reasons.get(k) for k in range(m)], dtype=pl.String)
        return pl.concat([shown, records, refused.to_frame()], how="horizontal")

    def _check_all(self, progress: bool | None) -> None:
        """Every (point, draw) case against the engine's rules, before anything runs (streamed,
        a block at a time; Ctrl-C stops it between blocks or inside one). When the first block's
        rate says it takes long, a line says how long, then a progress line counts the cases."""
        vertices, base = self.scene.template_vertices(), self.scene.engine_values()
        first: RestitutionError | None = None
        count = 0
        bar: Progress | None = None
        t0 = time.perf_counter()
        try:
            for start in range(0, self.n_cases, _CHECK_BLOCK):
                stop = min(start + _CHECK_BLOCK, self.n_cases)
                per_case = self.engine_inputs(start, stop)
                bad = refused_cases(_engine.columns(base, per_case, stop - start), vertices, keep_errors=True)
                if bad and first is None:
                    first = bad[0][2].at_case(start + bad[0][0])
                count += len(bad)
                if bar is None:  # after the first block, whose rate estimates the whole check
                    bar = self._check_progress(stop, time.perf_counter() - t0, progress)
                bar.update(stop - start)
        finally:
            if bar is not None:
                bar.close()
        if first is not None:
            raise self._advise(first, count)

    def _check_progress(self, done: int, seconds: float, progress: bool | None) -> Progress:
        """The check's progress line (disabled when short, or not asked for), from its first block."""
        estimate = seconds * self.n_cases / max(done, 1)
        show = want_progress(progress, self.n_cases) if progress is not None else (
            estimate > LONG_CHECK_S and sys.stderr.isatty())
        if show and estimate > LONG_CHECK_S:
            print(f"checking {self.n_cases:,} cases before running any (on_refused=\"raise\"): about "
                  f"{_duration(estimate)} at this rate; Ctrl-C stops it", file=sys.stderr)
        return Progress(self.n_cases, done=0, enabled=show)

    def _advise(self, err: RestitutionError, count: int | None) -> RestitutionError:
        """The engine's refusal, with the draw it came from and what to do about it."""
        case = err.case or 0
        point, draw = divmod(case, self.n_draws)
        drawn = ", ".join(f"{k} = {v}" for k, v in self._drawn_values(case).items())
        how_many = f"{count} of {self.n_cases} cases are refused; " if count is not None else ""
        advice = (f"{err.expected} [point {point}, draw {draw}: {drawn}; {how_many}truncate the distribution "
                  f"(e.g. rs.Normal(mean, sd, lo=..., hi=...)) or pass on_refused=\"skip\"]")
        return RestitutionError(err.parameter, err.value, advice, case)

    def _drawn_values(self, case: int) -> dict[str, Any]:
        draw = np.array([case % self.n_draws])
        return {name: self._draw(d, name, draw)[0] for name, d in self.vary.items()}

    def _draw(self, dist: Distribution, name: str, draw: np.ndarray) -> np.ndarray:
        strata = self.n_draws if self.sampling == "stratified" else None
        return dist.draw_at(self.seed, name, draw, strata=strata)


def _check_vary(vary: Mapping[str, Any], scene: Scene) -> dict[str, Distribution]:
    """The drawn parameters: known axes, each with a distribution its values can take."""
    if not isinstance(vary, Mapping) or not vary:
        raise ValueError("require `vary`: a non-empty mapping of parameter name to distribution "
                         "(rs.Uniform, rs.Normal, rs.LogNormal, rs.Choice)")
    out: dict[str, Distribution] = {}
    for name, dist in vary.items():
        if name not in AXES:
            raise ValueError(f"`vary` key `{name}` is not a sweep axis; allowed: {', '.join(AXES)}")
        if not isinstance(dist, (Distribution, dict)):
            raise TypeError(f"`vary['{name}']` must be a distribution (rs.Uniform, rs.Normal, rs.LogNormal, "
                            f"rs.Choice) (found {type(dist).__name__})")
        dist = from_dict(dist, f"vary.{name}")
        discrete = name in _engine.CHOICES or name == "n"
        if discrete and not isinstance(dist, Choice):
            raise ValueError(f"`vary['{name}']` takes rs.Choice([...]) of its values (found {type(dist).__name__})")
        if isinstance(dist, Choice):
            axis_values(name, list(dist.values), scene)  # names exist, n are integers, numbers are numbers
        if name == "n" and isinstance(scene.shape, ConvexPolygon):
            raise ValueError("`n` cannot be drawn for a ConvexPolygon scene (its vertices are fixed)")
        out[name] = dist
    return out


def _engine_column(name: str, dist: Distribution, values: np.ndarray, scene: Scene) -> np.ndarray:
    """Drawn values as the engine's float64 column (a choice's names as their codes)."""
    if isinstance(dist, Choice):
        return axis_values(name, values.tolist(), scene)
    return np.ascontiguousarray(values, dtype=np.float64)


def _shown(name: str, column: np.ndarray) -> pl.Series:
    """A drawn engine column as the result shows it (names for choices, integers for ``n``)."""
    if name in _engine.CHOICES:
        return pl.Series(name, np.asarray(_engine.CHOICES[name], dtype=object)[column.astype(np.int64)].tolist(),
                         dtype=pl.String)
    if name == "n":
        return pl.Series(name, column.astype(np.int64))
    return pl.Series(name, column)


def refused_cases(cols: Mapping[str, np.ndarray], vertices: Any, *, threads: int = 0,
                  keep_errors: bool = False) -> list[Any]:
    """The rows of ``cols`` the engine refuses, in row order: ``(row, reason)`` pairs, or
    ``(row, reason, error)`` with ``keep_errors``.

    Some refusals need the impact's start (the depth estimate, the contact's step count), so
    each row is probed by running it with a budget of one step (a few us per case). The engine
    names one refused row per call; the rows before and after it are probed again, so every
    refused row is found whichever one the engine names first.
    """
    n = len(next(iter(cols.values())))
    probe = {**cols, "max_steps": np.ones(n)}
    found: list[Any] = []
    todo = [(0, n)]
    while todo:
        lo, hi = todo.pop()
        if lo >= hi:
            continue
        try:
            _engine.run({k: v[lo:hi] for k, v in probe.items()}, vertices, threads)
        except RestitutionError as err:
            row = lo + (err.case or 0)
            reason = str(err.at_case(None))
            found.append((row, reason, err) if keep_errors else (row, reason))
            todo += [(lo, row), (row + 1, hi)]
    return sorted(found, key=lambda f: f[0])


def _scatter_records(raw: Mapping[str, np.ndarray] | None, keep: np.ndarray, m: int) -> pl.DataFrame:
    """Record columns of the accepted rows ``keep`` placed in ``m`` rows, null elsewhere."""
    if raw is None:  # every row refused: the record's schema (an engine call on no rows), nulls only
        raw = _engine.run(_engine.columns(Scene().engine_values(), {}, 0), None, 1)
    frame = _engine.records_frame(raw)
    out = []
    for s in frame.get_columns():
        full = pl.Series(s.name, [None] * m, dtype=s.dtype)
        out.append(full.scatter(keep, s) if keep.size else full)
    return pl.DataFrame(out)


def spec_from_dict(data: Mapping[str, Any], *, source: str = "config",
                   base_dir: Path | None = None) -> tuple[EnsembleSpec, int | None]:
    """An ensemble config to (spec, chunk_size or None): a sweep config (``[scene]``, ``[axes]``
    or ``sweep.cases``, ``[sweep]``) plus ``[ensemble]`` (``n``, ``seed``, ``on_refused``) and
    ``[vary]`` (name = ``{ dist = "uniform", lo = 0, hi = 60 }``, ...); see
    ``examples/ensemble_config.toml``. Errors name the key."""
    fail = _config.failer(source)
    _config._check_keys(data, _config.TOP_KEYS + ("ensemble", "vary"), "", fail)
    scene, axes, cases, chunk = _config.parts(data, fail, base_dir, axes_required=False)
    ens = _config._table(data, "ensemble", fail)
    _config._check_keys(ens, ("n", "seed", "on_refused", "sampling"), "ensemble", fail)
    for key in ("n", "seed"):
        if key not in ens:
            raise fail(f"ensemble.{key}", "required (draws per point; the draws' seed)")
    vary_t = _config._table(data, "vary", fail)
    try:
        vary = {name: from_dict(d, f"vary.{name}") for name, d in vary_t.items()}
    except (ValueError, TypeError) as err:
        raise fail("", str(err)) from None
    try:
        spec = EnsembleSpec(scene, n=ens["n"], seed=ens["seed"], vary=vary, on_refused=ens.get("on_refused", "raise"),
                            sampling=ens.get("sampling", "random"), axes=None if cases is not None else axes,
                            cases=cases)
    except (ValueError, TypeError) as err:
        name = err.parameter if isinstance(err, RestitutionError) else None
        where = (f"ensemble.{name}" if name in ("n", "seed", "on_refused", "sampling") else f"vary.{name}" if name in vary_t
                 else "sweep.cases" if cases is not None else _config._named_key("axes", err, axes))
        raise fail(where, str(err)) from None
    return spec, chunk


def load_config(path: str | Path) -> tuple[EnsembleSpec, int | None]:
    """Reads a TOML ensemble config: (the spec, its ``[sweep] chunk_size`` or None)."""
    path = Path(path)
    try:
        data = _config.tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as err:
        raise _config.ConfigError(f"{path}: cannot read the config ({err.strerror})") from None
    except _config.tomllib.TOMLDecodeError as err:
        raise _config.ConfigError(f"{path}: invalid TOML: {' '.join(str(err).split())}") from None
    return spec_from_dict(data, source=str(path), base_dir=path.parent)


__all__ = ["EnsembleSpec", "ON_REFUSED", "SAMPLING", "load_config", "refused_cases", "spec_from_dict"]
