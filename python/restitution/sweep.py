"""Many impacts: the Cartesian product of axes (or an explicit table of cases), run in Rust."""

from __future__ import annotations

import sys
import time
from typing import Any

import numpy as np
import polars as pl

from . import _core
from ._columns import AXES, build_columns, records_frame, template_vertices, validate_axis
from .scene import INTEGRATORS, Scene

#: Cases per call into the engine when a sweep reports progress (the GIL is released per chunk
#: and Ctrl-C is honoured between chunks).
CHUNK = 16384


def _product(axes: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Cartesian product, first axis slowest (like itertools.product)."""
    arrays = list(axes.values())
    grids = np.meshgrid(*arrays, indexing="ij")
    return {name: g.ravel() for name, g in zip(axes, grids)}


def sweep(
    scene: Scene,
    *,
    cases: pl.DataFrame | None = None,
    threads: int | None = None,
    progress: bool | None = None,
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
    **axes
        Any of ``theta_deg``, ``omega_in``, ``v``, ``mu``, ``gamma``, ``gamma_t``, ``E``,
        ``rho``, ``r``, ``n`` (0: exact disc), ``phi0_deg``, ``dt_factor``, ``kn``, ``cn``,
        ``kt``, ``integrator``: a scalar or a 1-D array. ``theta_deg`` is required.

    Returns
    -------
    polars.DataFrame
        One row per impact: the axes' columns (first axis slowest), then the record's.

    Examples
    --------
    >>> import numpy as np, restitution as rs
    >>> df = rs.sweep(rs.Scene(), theta_deg=[30.0, 60.0], mu=[0.0, 1.0])
    >>> df.select("theta_deg", "mu").rows()
    [(30.0, 0.0), (30.0, 1.0), (60.0, 0.0), (60.0, 1.0)]
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"`scene` must be a restitution.Scene (found {type(scene).__name__})")
    if cases is not None:
        if axes:
            raise ValueError("give either `cases` or axes, not both")
        if not isinstance(cases, pl.DataFrame):
            raise TypeError(f"`cases` must be a polars DataFrame (found {type(cases).__name__})")
        unknown = [c for c in cases.columns if c not in AXES]
        if unknown:
            raise ValueError(f"`cases` has columns that are not axes: {unknown}; allowed: {', '.join(AXES)}")
        if "theta_deg" not in cases.columns:
            raise ValueError("`cases` needs a `theta_deg` column")
        per_case = {}
        for name in cases.columns:
            col = cases[name]
            per_case[name] = validate_axis(name, col.to_list() if name == "integrator" else col.to_numpy(), scene)
        shown = {name: cases[name] for name in cases.columns}
        n_cases = cases.height
    else:
        if "theta_deg" not in axes:
            raise ValueError("`theta_deg` is required (a scalar or a 1-D array in (0, 90])")
        validated = {name: validate_axis(name, values, scene) for name, values in axes.items()}
        per_case = _product(validated)
        n_cases = int(np.prod([len(a) for a in validated.values()]))
        shown = {}
        for name, col in per_case.items():
            shown[name] = pl.Series(name, [INTEGRATORS[c] for c in col]) if name == "integrator" else pl.Series(name, col)
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int) or threads < 1):
        raise ValueError(f"require `threads` an integer >= 1 (found {threads!r})")
    cols = build_columns(scene, per_case, n_cases)
    raw = _run_chunked(scene, cols, n_cases, threads or 0, progress)
    return pl.concat([pl.DataFrame(shown), records_frame(raw)], how="horizontal")


def _run_chunked(scene: Scene, cols: dict[str, np.ndarray], n: int, threads: int, progress: bool | None) -> dict[str, np.ndarray]:
    verts = template_vertices(scene)
    if progress is None:
        progress = n >= 50_000 and sys.stderr.isatty()
    if not progress:
        return dict(_core.run_cases(cols, verts, scene.normal_law, scene.inertia, threads))
    bar = _Progress(n)
    parts = []
    for start in range(0, n, CHUNK):
        chunk = {k: np.ascontiguousarray(v[start : start + CHUNK]) for k, v in cols.items()}
        parts.append(dict(_core.run_cases(chunk, verts, scene.normal_law, scene.inertia, threads)))
        bar.update(len(chunk["theta_deg"]))
    bar.close()
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


class _Progress:
    """tqdm when installed, else a one-line counter on stderr (impacts, impacts/s, ETA)."""

    def __init__(self, total: int) -> None:
        self.total, self.done, self.t0 = total, 0, time.perf_counter()
        try:
            from tqdm import tqdm

            self.bar: Any = tqdm(total=total, unit="impact", unit_scale=True)
        except ImportError:
            self.bar = None

    def update(self, k: int) -> None:
        self.done += k
        if self.bar is not None:
            self.bar.update(k)
            return
        rate = self.done / max(time.perf_counter() - self.t0, 1e-9)
        eta = (self.total - self.done) / rate if rate > 0 else float("inf")
        print(f"\r{self.done}/{self.total} impacts, {rate:,.0f}/s, ETA {eta:,.0f} s", end="", file=sys.stderr)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        else:
            print(file=sys.stderr)


__all__ = ["sweep"]
