"""Many impacts: the Cartesian product of axes (or an explicit table of cases), run in Rust.

A :class:`SweepSpec` says what to compute; case ``i`` of a product is found by index
arithmetic (first axis slowest), so a chunk of cases is generated on demand and a sweep of
10^6 impacts never holds 10^6-row input grids. Every case runs the same code whatever the chunk
or thread count, so the rows do not depend on either.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import polars as pl

from .. import _core
from .._columns import (AXES, CHOICE_AXES, build_columns, check_combinations, records_frame, template_vertices,
                       validate_axis)
from ._progress import Progress, want_progress
from ..scene import INERTIAS, INTEGRATORS, NORMAL_LAWS, Scene

#: Cases per engine call unless told otherwise. Each call runs on all threads with the GIL
#: released; between calls a sweep reports progress and honours Ctrl-C. Large enough that the
#: per-call overhead (and the idle tail while the last cases of a call finish) is negligible.
DEFAULT_CHUNK = 8192

#: Axes that the engine takes per call rather than per case: a chunk runs once per value group.
_PER_CALL = ("normal_law", "inertia")


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
        Axis name to a scalar or 1-D array (see :data:`restitution._columns.AXES`); the first
        axis varies slowest. ``theta_deg`` is required.
    cases : polars.DataFrame, optional
        One impact per row; its columns must be axis names, ``theta_deg`` among them.
    """

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
        if "theta_deg" not in axes:
            raise ValueError("`theta_deg` is required (a scalar or a 1-D array in (0, 90])")
        self.axes = {name: validate_axis(name, values, self.scene) for name, values in axes.items()}
        check_combinations(self.scene, self.axes, rows=False)
        lens = [len(a) for a in self.axes.values()]
        self.n_cases = int(np.prod(lens, dtype=object))  # exact, no int64 overflow for huge products
        # stride of axis k = product of the lengths after it (first axis slowest)
        self._strides = [int(np.prod(lens[k + 1:], dtype=object)) for k in range(len(lens))]

    def _init_cases(self, cases: pl.DataFrame) -> None:
        if not isinstance(cases, pl.DataFrame):
            raise TypeError(f"`cases` must be a polars DataFrame (found {type(cases).__name__})")
        unknown = [c for c in cases.columns if c not in AXES]
        if unknown:
            raise ValueError(f"`cases` has columns that are not axes: {unknown}; allowed: {', '.join(AXES)}")
        if "theta_deg" not in cases.columns:
            raise ValueError("`cases` needs a `theta_deg` column")
        if cases.height == 0:
            raise ValueError("require `cases` with at least one row")
        self.cases = cases
        self._case_cols = {
            name: validate_axis(name, cases[name].to_list() if name in CHOICE_AXES else cases[name].to_numpy(),
                                self.scene)
            for name in cases.columns
        }
        check_combinations(self.scene, self._case_cols, rows=True)
        self.n_cases = cases.height

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Input columns of the result, in order."""
        return tuple(self.cases.columns) if self.cases is not None else tuple(self.axes)

    def axis_values(self, name: str) -> list[Any]:
        """An axis' values as plain Python values (names for integrator, normal_law, inertia)."""
        a = self.axes[name]
        if name in CHOICE_AXES:
            return [_choice_table(name)[int(c)] for c in a]
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
            if name in CHOICE_AXES:
                shown[name] = pl.Series(name, np.asarray(_choice_table(name), dtype=object)[col].tolist(),
                                        dtype=pl.String)
            else:
                shown[name] = pl.Series(name, col)
        return per_case, pl.DataFrame(shown)

    def run(self, start: int, stop: int, threads: int = 0) -> pl.DataFrame:
        """Runs cases ``start:stop``: one row per impact, input columns then the record's."""
        per_case, shown = self.inputs(start, stop)
        raw = run_per_case(self.scene, per_case, stop - start, threads, offset=start)
        return pl.concat([shown, records_frame(raw)], how="horizontal")


def _choice_table(name: str) -> tuple[str, ...]:
    return INTEGRATORS if name == "integrator" else CHOICE_AXES[name]


def check_chunk_size(chunk_size: Any) -> int:
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"require `chunk_size` an integer >= 1 (found {chunk_size!r})")
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
        raise ValueError(f"require `threads` an integer in [1, {MAX_THREADS}] (found {threads!r})")
    return int(threads)


_CASE_PREFIX = re.compile(r"^case (\d+): ")


def run_per_case(scene: Scene, per_case: Mapping[str, np.ndarray], n: int, threads: int,
                 offset: int = 0) -> dict[str, np.ndarray]:
    """Runs ``n`` cases (values per case in ``per_case``, the scene's elsewhere) in the engine.

    ``normal_law`` and ``inertia`` are per call in the engine: with either as an axis, each
    value group runs as one call and the records are put back in case order.
    """
    verts = template_vertices(scene)
    if not any(k in per_case for k in _PER_CALL):
        return _engine(scene, per_case, n, threads, verts, scene.normal_law, scene.inertia, offset, None)
    law = per_case.get("normal_law", np.full(n, NORMAL_LAWS.index(scene.normal_law)))
    inertia = per_case.get("inertia", np.full(n, INERTIAS.index(scene.inertia)))
    key = np.asarray(law) * len(INERTIAS) + np.asarray(inertia)
    out: dict[str, np.ndarray] = {}
    for k in np.unique(key):
        idx = np.flatnonzero(key == k)
        sub = {name: v[idx] for name, v in per_case.items() if name not in _PER_CALL}
        raw = _engine(scene, sub, len(idx), threads, verts, NORMAL_LAWS[k // len(INERTIAS)],
                      INERTIAS[k % len(INERTIAS)], offset, idx)
        for name, a in raw.items():
            if name not in out:
                out[name] = np.empty(n, dtype=a.dtype)
            out[name][idx] = a
    return out


def _engine(scene: Scene, per_case: Mapping[str, np.ndarray], n: int, threads: int, verts: np.ndarray | None,
            normal_law: str, inertia: str, offset: int, idx: np.ndarray | None) -> dict[str, np.ndarray]:
    cols = build_columns(scene, per_case, n)
    try:
        return dict(_core.run_cases(cols, verts, normal_law, inertia, threads, overlap=scene.overlap))
    except ValueError as err:
        # The engine numbers cases within this call; users need the index in the whole sweep.
        m = _CASE_PREFIX.match(str(err))
        if m is None:
            raise
        i = int(m.group(1))
        global_i = offset + (int(idx[i]) if idx is not None else i)
        raise ValueError(f"case {global_i}: {str(err)[m.end():]}") from None


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
    spec = SweepSpec(scene, axes=axes, cases=cases)
    n_threads = check_threads(threads)
    size = check_chunk_size(chunk_size if chunk_size is not None else DEFAULT_CHUNK)
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
