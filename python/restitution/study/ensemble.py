"""Ensembles: distributions of the outcome over what a scene leaves open.

``rs.ensemble(scene, n, vary={...}, seed=..., **axes)`` draws ``n`` impacts at every point of
the swept axes, each drawing the parameters of ``vary`` (a polygon's orientation, a spread of
mu for roughness, spin noise, speed ...) from their distributions, and returns an
:class:`Ensemble`: the samples (drawn parameters and every record column) and their
statistics per point (:meth:`Ensemble.summary`, docs/model.md section 16).

How the draws are made, why every point sees the same draws, and what happens to draws the
engine refuses: :mod:`restitution.runs.ensemble`. An ensemble is a sweep: it streams to a
Parquet dataset with resume (:func:`ensemble_to_dataset`, ``restitution ensemble CONFIG``) and
runs on Dask.

Examples
--------
>>> import restitution as rs
>>> ens = rs.ensemble(rs.Scene.paper(shape=rs.RegularPolygon(0.01, 4), integrator="adaptive", mu=0.0, gamma=0.0),
...                   64, vary={"phi0_deg": rs.Uniform(0.0, 90.0)}, seed=1, theta_deg=[30.0, 60.0])
>>> ens.samples.select("theta_deg", "draw", "phi0_deg").shape
(128, 3)
>>> s = ens.summary(["e_n"], n_boot=200)
>>> s.select("theta_deg", "quantity", "n").rows()
[(30.0, 'e_n', 64), (60.0, 'e_n', 64)]
>>> bool((s["q05_lo"] <= s["q05"]).all() and (s["q05"] <= s["q95"]).all())
True
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterator, Mapping, Sequence

import numpy as np
import polars as pl

from ..runs.dataset import SweepResult, _part_files, read_manifest, scan_dataset, sweep_to_dataset
from ..errors import RestitutionTypeError
from ..runs.distributions import check_seed
from ..runs.ensemble import EnsembleSpec
from ..runs.sweep import MAX_IN_MEMORY_CASES, run_in_memory
from ..scene import Scene
from . import stats

#: The quantities a summary describes unless told otherwise.
QUANTITIES = ("e_n", "e_t", "e_kin", "omega_out")
#: Stream of the bootstrap's random numbers (apart from every drawn parameter's).
_BOOT_KEY = 0xB007


class Ensemble:
    """The draws of an ensemble and their outcomes; statistics and plots per point.

    Made by :func:`restitution.ensemble` (in memory) or :func:`read_ensemble` (a dataset, read
    lazily: a summary reads only the columns it needs).
    """

    def __init__(self, samples: pl.DataFrame | pl.LazyFrame, *, point_names: Sequence[str],
                 vary: Mapping[str, Any], n: int, seed: int, files: Sequence[Path] = ()) -> None:
        self._samples = samples
        self._files = list(files)  # a dataset's chunk files, in case order: read block by block
        self.point_names: tuple[str, ...] = tuple(point_names)
        """The swept axes: one distribution per combination of their values."""
        self.vary = dict(vary)
        """The drawn parameters and their distributions."""
        self.n = int(n)
        """Draws per point."""
        self.seed = int(seed)
        """The draws' seed."""

    @property
    def samples(self) -> pl.DataFrame:
        """One row per draw: the swept axes, ``draw``, the drawn parameters, the record's
        columns and ``refused`` (null, or why the engine refused the draw)."""
        if isinstance(self._samples, pl.LazyFrame):
            return self._samples.collect()
        return self._samples

    def __repr__(self) -> str:
        vary = ", ".join(f"{k}={v!r}" for k, v in self.vary.items())
        return f"Ensemble(n={self.n} per point, points over {list(self.point_names)}, seed={self.seed}, {vary})"

    def summary(self, quantities: Sequence[str] = QUANTITIES, *, level: float = 0.95, n_boot: int = 1000,
                seed: int | None = None) -> pl.DataFrame:
        """Statistics of each quantity at each point, with confidence intervals.

        One row per point and quantity: the point's axes, ``quantity``, ``n`` (records used:
        separated impacts with a defined value), ``n_refused`` and ``n_timed_out`` (draws left
        out), then ``mean``, ``sd``, ``q05`` ... ``q95`` each with ``_lo`` and ``_hi``
        (percentile bootstrap at ``level``), and ``p_neg`` = P(quantity < 0) with Wilson's
        interval. The estimators: :mod:`restitution.study.stats`, docs/model.md section 16.1.

        Parameters
        ----------
        quantities : sequence of str
            Record columns (default e_n, e_t, e_kin, omega_out).
        level : float
            Confidence level of the intervals.
        n_boot : int
            Bootstrap resamples per point and quantity (0: no intervals). Costs about
            n_boot * n element operations per point and quantity.
        seed : int, optional
            Seeds the bootstrap (default: the ensemble's seed; the intervals are reproducible).
        """
        if isinstance(quantities, str):
            raise RestitutionTypeError("quantities", f"str {quantities!r}", f"a list of column names, e.g. "
                                       f"[{quantities!r}]")
        quantities = list(quantities)
        names = self._check_quantities(quantities)
        rng = np.random.default_rng(np.random.SeedSequence(self.seed if seed is None else check_seed(seed),
                                                           spawn_key=(_BOOT_KEY,)))
        rows = []
        for part in self._points([*self.point_names, *quantities, "timed_out", "refused"]):
            point = {name: part[name][0] for name in self.point_names}
            n_refused = int(part["refused"].is_not_null().sum())
            timed_out = part["timed_out"].fill_null(False)
            for q in quantities:
                values = part.filter(~timed_out)[q].drop_nulls().to_numpy().astype(np.float64)
                d = stats.describe(values, level=level, n_boot=n_boot, rng=rng)
                rows.append({**point, "quantity": q, "n": int(values.size), "n_refused": n_refused,
                             "n_timed_out": int(timed_out.sum()), **{k: d.get(k) for k in stats.COLUMNS[1:]}})
        schema = {**{name: names[name] for name in self.point_names}, "quantity": pl.String, "n": pl.Int64,
                  "n_refused": pl.Int64, "n_timed_out": pl.Int64, **{k: pl.Float64 for k in stats.COLUMNS[1:]}}
        return pl.DataFrame(rows, schema=schema)

    def _points(self, columns: list[str]) -> Iterator[pl.DataFrame]:
        """The samples' rows point by point, reading a block at a time: a point's rows are
        contiguous and its draws count up from 0 (case order), so a point begins where ``draw``
        does not grow (two points with the same axes' values stay two), and memory holds one
        block and one point, whatever the size."""
        carry: pl.DataFrame | None = None
        for block in self._blocks([*columns, "draw"]):
            frame = block if carry is None else pl.concat([carry, block])
            point = (frame["draw"].diff().fill_null(1) <= 0).cum_sum()
            last = point[-1]
            done, carry = frame.filter(point < last), frame.filter(point == last)
            if done.height:
                yield from done.with_columns(_point=point.filter(point < last)).partition_by(
                    "_point", maintain_order=True, include_key=False)
        if carry is not None and carry.height:
            yield carry

    def _blocks(self, columns: list[str]) -> Iterator[pl.DataFrame]:
        if self._files:
            for f in self._files:
                yield pl.read_parquet(f, columns=columns)
        else:
            yield from self.samples.select(columns).iter_slices(65536)

    def _check_quantities(self, quantities: list[str]) -> dict[str, Any]:
        """The samples' schema, once every quantity is one of its columns."""
        frame = self._samples if isinstance(self._samples, pl.LazyFrame) else self._samples.lazy()
        schema = dict(frame.collect_schema())
        unknown = [q for q in quantities if q not in schema]
        if unknown:
            raise ValueError(f"`quantities` has columns the samples lack: {unknown}; e.g. {', '.join(QUANTITIES)}")
        return schema

    def _columns(self, quantities: list[str]) -> pl.DataFrame:
        self._check_quantities(quantities)
        frame = self._samples if isinstance(self._samples, pl.LazyFrame) else self._samples.lazy()
        return frame.select(*self.point_names, *quantities, "timed_out", "refused").collect()

    def plot_quantiles(self, quantities: Sequence[str] = QUANTITIES, *, x: str = "theta_deg",
                       summary: pl.DataFrame | None = None, path: Any = None) -> Any:
        """Median and 25-75 % and 5-95 % ribbons of each quantity against ``x`` (one line per
        combination of the other axes); saved to ``path`` if given. Returns the figure."""
        from .ensemble_plots import quantile_ribbons

        if x not in self.point_names:
            raise ValueError(f"require `x` a swept axis: one of {list(self.point_names)} (found {x!r})")
        s = summary if summary is not None else self.summary(quantities, n_boot=0)
        return quantile_ribbons(s, list(quantities), x=x, group=[c for c in self.point_names if c != x], path=path,
                                title=f"Ensemble of {self.n} draws per point: median, 25-75 % and 5-95 % quantiles")

    def plot_histograms(self, quantity: str = "e_t", *, at: Sequence[float] | None = None, x: str = "theta_deg",
                        bins: int = 40, path: Any = None) -> Any:
        """Histograms (as densities) of ``quantity`` at up to six values of ``x`` (default:
        spread over its range); saved to ``path`` if given. Returns the figure."""
        from .ensemble_plots import histograms

        frame = self._columns([quantity])
        return histograms(frame, quantity, x=x if x in self.point_names else None, at=at, bins=bins, path=path)


def ensemble(scene: Scene, n: int, *, vary: Mapping[str, Any], seed: int, cases: pl.DataFrame | None = None,
             on_refused: str = "raise", sampling: str = "random", threads: int | None = None,
             progress: bool | None = None, chunk_size: int | None = None, **axes: Any) -> Ensemble:
    """Draws ``n`` impacts at every point of ``axes`` (or row of ``cases``), ``vary`` drawn.

    Parameters
    ----------
    scene : Scene
        Values of every parameter that is neither swept nor drawn.
    n : int
        Draws per point.
    vary : mapping
        Parameter (any sweep axis: ``phi0_deg``, ``omega_in``, ``mu``, ``v``, ``theta_deg``,
        ``gamma``, ``n``, ...) to its distribution: ``rs.Uniform(lo, hi)``,
        ``rs.Normal(mean, sd, lo=None, hi=None)``, ``rs.LogNormal(mean_log, sd_log, lo=None,
        hi=None)``, ``rs.Choice(values, p=None)``.
    seed : int
        The draws' seed: the samples are reproducible from it on any thread count and chunk size.
    cases : polars.DataFrame, optional
        Points as an explicit table instead of ``axes``.
    on_refused : {"raise", "skip"}
        Draws the engine refuses: raise before anything runs (default), or keep them as rows
        with null records and the reason in ``refused`` (:mod:`restitution.runs.ensemble`).
    sampling : {"random", "stratified"}
        Independent draws (default), or stratified ones: each parameter's n draws fall one in
        each of n equal-probability strata (a Latin hypercube), so means over them converge much
        faster (docs/model.md, section 16.1); the bootstrap intervals are then conservative.
    threads, progress, chunk_size :
        As for :func:`restitution.sweep`; the samples do not depend on them.
    **axes
        Swept axes, as for :func:`restitution.sweep` (``theta_deg`` required unless drawn).

    Returns
    -------
    Ensemble
    """
    spec = EnsembleSpec(scene, n=n, vary=vary, seed=seed, axes=axes, cases=cases, on_refused=on_refused,
                        sampling=sampling, max_cases=MAX_IN_MEMORY_CASES, progress=progress)
    frame = run_in_memory(spec, threads=threads, progress=progress, chunk_size=chunk_size)
    return Ensemble(frame, point_names=spec.point_names, vary=spec.vary, n=spec.n_draws, seed=spec.seed)


def ensemble_to_dataset(scene: Scene | EnsembleSpec, out: str | Path, n: int | None = None, *,
                        vary: Mapping[str, Any] | None = None, seed: int | None = None,
                        cases: pl.DataFrame | None = None, on_refused: str = "raise", sampling: str = "random",
                        chunk_size: int | None = None,
                        threads: int | None = None, progress: bool | None = None, resume: bool = False,
                        scheduler: Any = None, wait: bool = False, **axes: Any) -> SweepResult:
    """:func:`ensemble`, streamed chunk by chunk to the Parquet dataset ``out`` (flat memory),
    resumable, on threads or a Dask cluster: :func:`restitution.sweep_to_dataset`'s layout,
    with ``n``, ``seed`` and the distributions in the manifest. Read it back with
    :func:`read_ensemble`. ``scene`` may be a ready :class:`~restitution.runs.ensemble.EnsembleSpec`
    (from :func:`restitution.runs.ensemble.load_config`; then nothing else describes the draws)."""
    if isinstance(scene, EnsembleSpec):
        if n is not None or vary is not None or seed is not None or axes or cases is not None:
            raise ValueError("give either an EnsembleSpec or a scene with n, vary, seed and axes, not both")
        spec = scene
    else:
        if n is None or vary is None or seed is None:
            raise ValueError("require `n`, `vary` and `seed` with a scene")
        spec = EnsembleSpec(scene, n=n, vary=vary, seed=seed, axes=axes, cases=cases, on_refused=on_refused,
                            sampling=sampling, progress=progress)
    return sweep_to_dataset(spec, out, chunk_size=chunk_size, threads=threads, progress=progress, resume=resume,
                            scheduler=scheduler, wait=wait)


def read_ensemble(path: str | Path, *, allow_partial: bool = False) -> Ensemble:
    """The ensemble dataset at ``path`` (read lazily; ``samples`` collects it)."""
    m = read_manifest(path)
    ens = m.get("spec", {}).get("ensemble")
    if ens is None:
        raise ValueError(f"{path} holds a sweep, not an ensemble (its manifest has no `ensemble` table): "
                         "read it with restitution.read_dataset")
    from ..runs.distributions import from_dict

    vary = {k: from_dict(v) for k, v in m["spec"]["vary"].items()}
    points = [a for a in m["axes"] if a != "draw" and a not in vary]
    lazy = scan_dataset(path, allow_partial=allow_partial)  # refuses an unfinished dataset unless allowed
    parts = _part_files(Path(path))
    files = [parts[k] for k in sorted(parts) if k < m["n_chunks"]]
    return Ensemble(lazy, point_names=points, vary=vary, n=ens["n"], seed=ens["seed"], files=files)


__all__ = ["Ensemble", "QUANTITIES", "ensemble", "ensemble_to_dataset", "read_ensemble"]
