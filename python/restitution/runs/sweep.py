"""Many impacts: the Cartesian product of axes (or an explicit table of cases), run in Rust.

A :class:`SweepSpec` says what to compute; case ``i`` of a product is found by index
arithmetic (first axis slowest), so a chunk of cases is generated on demand and a sweep of
10^6 impacts never holds 10^6-row input grids. Every case runs the same code whatever the chunk
or thread count, so the rows do not depend on either.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import polars as pl

from .. import _engine
from ..errors import RestitutionError
from ..scene import ConvexPolygon, Scene
from ..shapes import Disc, RegularPolygon, Sphere
from ._progress import Progress, want_progress

#: Cases per engine call unless told otherwise. Each call runs on all threads with the GIL
#: released; between calls a sweep reports progress and honours Ctrl-C. Large enough that the
#: per-call overhead (and the idle tail while the last cases of a call finish) is negligible.
DEFAULT_CHUNK = 8192

#: Names accepted as sweep axes: every per-case column of the engine (``n``: the shape, 0 for
#: an exact disc, >= 3 for a regular n-gon; a choice by its names).
AXES: tuple[str, ...] = _engine.CASE_COLUMNS

#: Axes whose values the scene's rules do not tie to other axes: the engine checks them value
#: by value; the others are checked in every combination (the time-step bound ties dt_factor
#: to the stiffness and damping, inertia and overlap to the shape).
_PER_VALUE = ("theta_deg", "omega_in", "v", "phi0_deg")

#: A scene's fields in the config structure besides ``shape`` and ``partner``: every field of
#: :class:`Scene`, so a new field is a key (and part of a dataset's digest) without editing this file.
SCENE_KEYS = tuple(f.name for f in dataclasses.fields(Scene) if f.name not in ("shape", "partner"))

#: Most cases a sweep or an ensemble returns in memory: one row is about 300 bytes, so this is
#: about 15 GB. Beyond it they are refused before any work (10^12 cases would take minutes of
#: checks, then days, then fail for memory): stream them with ``sweep_to_dataset``.
MAX_IN_MEMORY_CASES = 50_000_000

#: Most combinations checked before a sweep starts; beyond it each value is checked alone and
#: the engine still refuses a bad combination when its chunk runs, naming the case.
_CHECK_MAX = 200_000


@dataclass(frozen=True, slots=True)
class Chunk:
    """Cases ``start`` to ``stop`` (exclusive) of a sweep, its ``index``-th chunk."""

    index: int
    start: int
    stop: int


class SweepSpec:
    """What a sweep computes: a scene plus either axes (a Cartesian product) or a cases table.

    Parameters
    ----------
    scene : Scene
        Values of every parameter that is not an axis.
    axes : mapping, optional
        Axis name to a scalar or 1-D array (see :data:`AXES`); the first
        axis varies slowest. ``theta_deg`` is required.
    cases : polars.DataFrame, optional
        One impact per row; its columns must be axis names, ``theta_deg`` among them.
    """

    #: Whether ``theta_deg`` must be an axis (an ensemble may draw it instead).
    _needs_theta = True

    def __init__(self, scene: Scene, *, axes: Mapping[str, Any] | None = None,
                 cases: pl.DataFrame | None = None) -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
        self.scene = scene
        self.cases: pl.DataFrame | None = None
        self.axes: dict[str, np.ndarray] = {}
        if cases is not None:
            if axes:
                raise ValueError("give either `cases` or axes, not both")
            self._init_cases(cases)
        else:
            self._init_axes(dict(axes or {}))

    def _init_axes(self, axes: dict[str, Any]) -> None:
        if "theta_deg" not in axes and self._needs_theta:
            raise ValueError("`theta_deg` is required (a scalar or a 1-D array in (0, 90])")
        self.axes = {name: axis_values(name, values, self.scene) for name, values in axes.items()}
        lens = [len(a) for a in self.axes.values()]
        self.n_cases = int(np.prod(lens, dtype=object))  # exact, no int64 overflow for huge products
        # stride of axis k = product of the lengths after it (first axis slowest)
        self._strides = [int(np.prod(lens[k + 1:], dtype=object)) for k in range(len(lens))]
        self._check_product()

    def _check_product(self) -> None:
        """The engine's rules on the product before it runs: every combination of the axes that
        interact (up to _CHECK_MAX), every value of the others; an error names its case."""
        names = list(self.axes)
        tied = [k for k, name in enumerate(names) if name not in _PER_VALUE]
        sizes = [len(self.axes[names[k]]) for k in tied]
        probes: list[tuple[int, ...]] = []
        if int(np.prod(sizes, dtype=object)) <= _CHECK_MAX:
            for combo in itertools.product(*(range(n) for n in sizes)):
                probe = [0] * len(names)
                for k, j in zip(tied, combo):
                    probe[k] = j
                probes.append(tuple(probe))
        for k, name in enumerate(names):
            if name in _PER_VALUE or int(np.prod(sizes, dtype=object)) > _CHECK_MAX:
                probes.extend(tuple(j if m == k else 0 for m in range(len(names))) for j in range(len(self.axes[name])))
        index = np.array(probes, dtype=np.int64).reshape(len(probes), len(names))
        per_case = {name: self.axes[name][index[:, k]] for k, name in enumerate(names)}
        try:
            _engine.check(_engine.columns(self.scene.engine_values(), per_case, len(probes)),
                          self.scene.template_vertices())
        except RestitutionError as err:
            case = sum(int(i) * st for i, st in zip(index[err.case or 0], self._strides))
            raise err.at_case(case) from None

    def _init_cases(self, cases: pl.DataFrame) -> None:
        if not isinstance(cases, pl.DataFrame):
            raise TypeError(f"`cases` must be a polars DataFrame (found {type(cases).__name__})")
        unknown = [c for c in cases.columns if c not in AXES]
        if unknown:
            raise ValueError(f"`cases` has columns that are not axes: {unknown}; allowed: {', '.join(AXES)}")
        if "theta_deg" not in cases.columns and self._needs_theta:
            raise ValueError("`cases` needs a `theta_deg` column")
        if cases.height == 0:
            raise ValueError("require `cases` with at least one row")
        self.cases = cases
        self._case_cols = {
            name: axis_values(name, cases[name].to_list() if name in _engine.CHOICES else cases[name].to_numpy(),
                              self.scene, cases=True)
            for name in cases.columns
        }
        self.n_cases = cases.height
        self._check_cases()

    def _check_cases(self) -> None:
        if self.n_cases <= _CHECK_MAX:  # beyond, each chunk is checked as it runs
            _engine.check(_engine.columns(self.scene.engine_values(), self._case_cols, self.n_cases),
                          self.scene.template_vertices())

    def to_dict(self, chunk_size: int | None = None, cases_file: str | None = None) -> dict[str, Any]:
        """The spec in the config structure, fully expanded (what a dataset's manifest stores)."""
        return spec_to_dict(self, chunk_size, cases_file)

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Input columns of the result, in order."""
        return tuple(self.cases.columns) if self.cases is not None else tuple(self.axes)

    def axis_values(self, name: str) -> list[Any]:
        """An axis' values as plain Python values (names for integrator, normal_law, inertia)."""
        a = self.axes[name]
        if name in _engine.CHOICES:
            return [_engine.CHOICES[name][int(c)] for c in a]
        if name == "n":
            return [int(c) for c in a]
        return a.tolist()

    def chunks(self, chunk_size: int) -> Iterator[Chunk]:
        """Chunk ``k`` holds cases ``k * chunk_size`` up to the next multiple (a function of the
        case order only, so a resumed sweep finds the same chunks)."""
        size = check_chunk_size(chunk_size)
        for k, start in enumerate(range(0, self.n_cases, size)):
            yield Chunk(k, start, min(start + size, self.n_cases))

    def n_chunks(self, chunk_size: int) -> int:
        return -(-self.n_cases // check_chunk_size(chunk_size))

    def inputs(self, start: int, stop: int) -> tuple[dict[str, np.ndarray], pl.DataFrame]:
        """Cases ``start:stop``: (engine values per axis, the result's input columns)."""
        if not 0 <= start <= stop <= self.n_cases:
            raise ValueError(f"require 0 <= start <= stop <= {self.n_cases} (found {start}, {stop})")
        if self.cases is not None:
            per_case = {name: col[start:stop] for name, col in self._case_cols.items()}
            return per_case, self.cases.slice(start, stop - start)
        i = np.arange(start, stop, dtype=np.int64)
        per_case, shown = {}, {}
        for (name, values), stride in zip(self.axes.items(), self._strides):
            col = values[(i // stride) % len(values)]
            per_case[name] = col
            if name in _engine.CHOICES:
                shown[name] = pl.Series(name, np.asarray(_engine.CHOICES[name], dtype=object)[col.astype(np.int64)]
                                        .tolist(), dtype=pl.String)
            elif name == "n":
                shown[name] = pl.Series(name, col.astype(np.int64))
            else:
                shown[name] = pl.Series(name, col)
        return per_case, pl.DataFrame(shown)

    def run(self, start: int, stop: int, threads: int = 0) -> pl.DataFrame:
        """Runs cases ``start:stop``: one row per impact, input columns then the record's."""
        per_case, shown = self.inputs(start, stop)
        cols = _engine.columns(self.scene.engine_values(), per_case, stop - start)
        try:
            raw = _engine.run(cols, self.scene.template_vertices(), threads)
        except RestitutionError as err:
            # The engine numbers the cases of this call; users need the index in the whole sweep.
            raise err.at_case(start + (err.case or 0)) from None
        return pl.concat([shown, _engine.records_frame(raw)], how="horizontal")


def axis_values(name: str, values: Any, scene: Scene, *, cases: bool = False) -> np.ndarray:
    """One axis' values as the engine's float64 column (a choice's names as their codes). Checks
    what the engine cannot: the axis exists, its values are numbers (or names) in a 1-D list, by
    the rule :class:`Scene` applies to one value (:func:`_engine.real`, :func:`_engine.code`).
    With ``cases``, ``values`` is a cases table's column and an error names its row (``.case``)."""
    if name not in AXES:
        raise ValueError(f"`{name}` is not a sweep axis; allowed axes: {', '.join(AXES)}")
    if name in ("partner_n", "partner_body") and isinstance(scene.partner, ConvexPolygon):
        raise ValueError(f"`{name}` is not a sweep axis for a ConvexPolygon partner (its vertices are fixed)")
    if name in _engine.CHOICES:
        a = _codes(name, values, cases)
    elif name == "n":
        if isinstance(scene.shape, ConvexPolygon):
            raise ValueError("`n` is not a sweep axis for a ConvexPolygon scene (its vertices are fixed)")
        a = _engine.integers(name, values, cases=cases)
    else:
        a = _engine.reals(name, values, cases=cases)
    a = np.atleast_1d(a)
    if a.ndim != 1:
        raise ValueError(f"require `{name}` a scalar or 1-D array (found shape {a.shape})")
    if a.size == 0:
        raise ValueError(f"require `{name}` non-empty")
    return np.ascontiguousarray(a)


def _codes(name: str, values: Any, cases: bool) -> np.ndarray:
    """A choice axis' names as the engine's codes (an error names the row of a cases table)."""
    try:
        names = np.atleast_1d(np.asarray(values, dtype=object))
    except (TypeError, ValueError):  # ragged nests of arrays
        raise TypeError(f"`{name}` must be a name or a 1-D list of names (found {values!r:.80})") from None
    if names.ndim != 1:
        raise ValueError(f"require `{name}` a name or a 1-D list of names (found shape {names.shape})")
    out = np.empty(len(names), dtype=np.float64)
    for i, v in enumerate(names):
        try:
            out[i] = _engine.code(name, v)
        except RestitutionError as err:
            raise err.at_case(i if cases else None) from None
    return out


def spec_to_dict(spec: SweepSpec, chunk_size: int | None = None, cases_file: str | None = None) -> dict[str, Any]:
    """The spec in the config structure (:mod:`restitution.runs.config`), fully expanded (no
    preset; every axis an explicit list): what a dataset's manifest stores and a config reads back."""
    s = spec.scene
    scene: dict[str, Any] = {k: getattr(s, k) if k in _engine.CHOICES else float(getattr(s, k))
                             for k in SCENE_KEYS if getattr(s, k) is not None}
    scene["shape"] = shape_to_dict(s.shape)
    if s.partner is not None:
        scene["partner"] = shape_to_dict(s.partner)
    out: dict[str, Any] = {"scene": scene}
    if spec.cases is None:
        out["axes"] = {name: spec.axis_values(name) for name in spec.axis_names}
    sweep: dict[str, Any] = {}
    if chunk_size is not None:
        sweep["chunk_size"] = chunk_size
    if cases_file is not None:
        sweep["cases"] = cases_file
    if sweep:
        out["sweep"] = sweep
    return out


def shape_to_dict(shape: Any) -> dict[str, Any]:
    """A shape as its config table (``kind`` and its parameters)."""
    if isinstance(shape, Disc):
        return {"kind": "disc", "r": float(shape.r)}
    if isinstance(shape, Sphere):
        return {"kind": "sphere", "r": float(shape.r)}
    if isinstance(shape, RegularPolygon):
        return {"kind": "regular_polygon", "r": float(shape.r), "n": int(shape.n), "phi0_deg": float(shape.phi0_deg)}
    return {"kind": "convex_polygon", "vertices": [list(v) for v in shape.vertices], "phi0_deg": float(shape.phi0_deg)}


def check_in_memory(n_cases: int, parameter: str) -> None:
    """Refuses more than :data:`MAX_IN_MEMORY_CASES` cases returned as one frame, naming ``parameter``."""
    if n_cases > MAX_IN_MEMORY_CASES:
        raise RestitutionError(parameter, f"{n_cases:,} cases", f"at most {MAX_IN_MEMORY_CASES:,} cases in memory "
                               "(about 300 bytes each); stream them to disk with rs.sweep_to_dataset "
                               "(rs.ensemble_to_dataset for an ensemble)")


def check_chunk_size(chunk_size: Any) -> int:
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise RestitutionError("chunk_size", repr(chunk_size), "an integer >= 1")
    return int(chunk_size)


#: Most worker threads a sweep may ask for: far beyond any machine's cores, low enough that a
#: typo (threads=10**6) is an error rather than an attempt to start a million threads.
MAX_THREADS = 4096


def check_threads(threads: Any) -> int:
    """``None`` -> 0 (the engine's default: all cores); else an integer in [1, MAX_THREADS]."""
    if threads is None:
        return 0
    if (isinstance(threads, bool) or not isinstance(threads, (int, np.integer))
            or not 1 <= threads <= MAX_THREADS):
        raise RestitutionError("threads", repr(threads), f"an integer in [1, {MAX_THREADS}]")
    return int(threads)


def sweep(
    scene: Scene,
    *,
    cases: pl.DataFrame | None = None,
    threads: int | None = None,
    progress: bool | None = None,
    chunk_size: int | None = None,
    **axes: Any,
) -> pl.DataFrame:
    """Runs one impact per point of the Cartesian product of ``axes`` (or per row of ``cases``).

    Parameters
    ----------
    scene : Scene
        Values of every parameter that is not an axis.
    cases : polars.DataFrame, optional
        An explicit table, one impact per row; its columns must be axis names.
    threads : int, optional
        Worker threads (default: all cores). Results do not depend on it.
    progress : bool, optional
        Show a progress bar (default: for sweeps of 50 000 impacts or more on a terminal).
    chunk_size : int, optional
        Cases per engine call (default :data:`DEFAULT_CHUNK`). Results do not depend on it.
    **axes
        Any of ``theta_deg``, ``omega_in``, ``v``, ``mu``, ``gamma``, ``gamma_t``, ``E``,
        ``rho``, ``r``, ``n`` (0: exact disc, >= 3: regular n-gon), ``phi0_deg``,
        ``dt_factor``, ``kn``, ``cn``, ``kt``, ``integrator``, ``normal_law``, ``inertia``:
        a scalar or a 1-D array. ``theta_deg`` is required.

    Returns
    -------
    polars.DataFrame
        One row per impact: the axes' columns (first axis slowest), then the record's.

    See Also
    --------
    restitution.sweep_to_dataset : the same, streamed to a resumable Parquet dataset.

    Examples
    --------
    >>> import numpy as np, restitution as rs
    >>> df = rs.sweep(rs.Scene(), theta_deg=[30.0, 60.0], mu=[0.0, 1.0])
    >>> df.select("theta_deg", "mu").rows()
    [(30.0, 0.0), (30.0, 1.0), (60.0, 0.0), (60.0, 1.0)]
    """
    return run_in_memory(SweepSpec(scene, axes=axes, cases=cases), threads=threads, progress=progress,
                         chunk_size=chunk_size)


def run_in_memory(spec: SweepSpec, *, threads: int | None = None, progress: bool | None = None,
                  chunk_size: int | None = None) -> pl.DataFrame:
    """Runs every case of ``spec`` chunk by chunk (progress between chunks) into one frame."""
    n_threads = check_threads(threads)
    size = check_chunk_size(chunk_size if chunk_size is not None else DEFAULT_CHUNK)
    check_in_memory(spec.n_cases, " x ".join(spec.axis_names))
    bar = Progress(spec.n_cases, enabled=want_progress(progress, spec.n_cases))
    parts = []
    try:
        for chunk in spec.chunks(size):
            parts.append(spec.run(chunk.start, chunk.stop, n_threads))
            bar.update(chunk.stop - chunk.start)
    finally:
        bar.close()
    return parts[0] if len(parts) == 1 else pl.concat(parts, rechunk=True)


__all__ = ["DEFAULT_CHUNK", "Chunk", "SweepSpec", "sweep"]
