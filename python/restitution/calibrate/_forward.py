"""The forward model of a calibration: many parameter sets at many measured points, in one
engine call.

Every statistical method of :mod:`restitution.calibrate` asks the same question: what does
the engine predict for S parameter sets at P points (angles and spins)? :func:`predict`
answers it with one sweep over an S x P table of cases, so no Python loop ever runs per impact.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import polars as pl

from .. import _engine
from ..errors import RestitutionError
from ..runs.sweep import sweep
from ..scene import Scene

#: What a prediction may be of: every numeric record column (``stop`` is a name).
QUANTITIES: tuple[str, ...] = tuple(name for name in _engine.RECORD_COLUMNS if name != "stop")

#: Columns a point may carry besides the parameters: where and how the impact happens.
POINT_COLUMNS = ("theta_deg", "omega_in")


def check_quantities(quantities: Sequence[str]) -> list[str]:
    """The quantities as a list; an unknown one is a :class:`RestitutionError` naming it."""
    if isinstance(quantities, str):
        quantities = [quantities]
    out = list(quantities)
    for q in out:
        if q not in QUANTITIES:
            raise RestitutionError("quantities", repr(q), "a numeric record column: " + ", ".join(QUANTITIES))
    if not out:
        raise RestitutionError("quantities", "[]", "at least one record column")
    return out


def check_parameter(name: str, where: str = "params") -> str:
    """A scene field a calibration may vary: a numeric per-case engine column other than the
    points' own (``theta_deg``, ``omega_in``) and the choices; else an error naming ``where``."""
    if name in POINT_COLUMNS or name in _engine.CHOICES or name not in _engine.CASE_COLUMNS:
        allowed = [c for c in _engine.CASE_COLUMNS if c not in POINT_COLUMNS and c not in _engine.CHOICES]
        raise RestitutionError(where, repr(name), "a numeric scene field: " + ", ".join(allowed))
    return name


def check_points(points: pl.DataFrame) -> pl.DataFrame:
    """A frame of points: ``theta_deg`` and optionally ``omega_in``, at least one row."""
    if not isinstance(points, pl.DataFrame):
        raise TypeError(f"`points` must be a polars DataFrame (found {type(points).__name__})")
    if "theta_deg" not in points.columns:
        raise RestitutionError("points", repr(points.columns), "a frame with a `theta_deg` column")
    extra = [c for c in points.columns if c not in POINT_COLUMNS]
    if extra:
        raise RestitutionError("points", repr(extra), "only the columns theta_deg and omega_in")
    if points.height == 0:
        raise RestitutionError("points", "0 rows", "at least one point")
    return points.select(pl.col(c).cast(pl.Float64) for c in points.columns)


def predict(scene: Scene, params: Mapping[str, np.ndarray], points: pl.DataFrame, quantities: Sequence[str], *,
            tol: float | None = None) -> dict[str, np.ndarray]:
    """The engine's predictions for S parameter sets at P points, in one engine call.

    Parameters
    ----------
    scene : Scene
        Every value that is neither a parameter nor a point's.
    params : mapping
        Scene field name -> array of shape (S,): parameter set ``s`` sets each field to its
        ``s``-th value.
    points : polars.DataFrame
        P rows: ``theta_deg`` and optionally ``omega_in`` (default: the scene's, 0).
    quantities : sequence of str
        Record columns to return (``e_n``, ``e_t``, ``e_kin``, ``omega_out``, ...).
    tol : float, optional
        The adaptive path's tolerance for these impacts (default: the scene's).

    Returns
    -------
    dict
        Quantity -> array of shape (S, P); NaN where the record's value is undefined (``e_t``
        head-on).

    Examples
    --------
    >>> import numpy as np, polars as pl, restitution as rs
    >>> out = predict(rs.Scene(), {"mu": np.array([0.0, 0.5])}, pl.DataFrame({"theta_deg": [30.0, 90.0]}),
    ...               ["e_t"])
    >>> out["e_t"].shape, bool(np.isnan(out["e_t"][:, 1]).all())     # no e_t head-on
    ((2, 2), True)
    """
    names = check_quantities(quantities)
    points = check_points(points)
    if not isinstance(params, Mapping) or not params:
        raise RestitutionError("params", repr(params), "a mapping of scene field names to arrays")
    values = {check_parameter(k): np.asarray(v, dtype=np.float64).reshape(-1) for k, v in params.items()}
    sizes = {v.size for v in values.values()}
    if len(sizes) != 1 or 0 in sizes:
        raise RestitutionError("params", repr({k: v.size for k, v in values.items()}),
                               "arrays of one common length S >= 1")
    (n_sets,), n_points = sizes, points.height
    columns: dict[str, np.ndarray] = {c: np.tile(points[c].to_numpy(), n_sets) for c in points.columns}
    columns.update({k: np.repeat(v, n_points) for k, v in values.items()})
    if tol is not None:
        columns["tol"] = np.full(n_sets * n_points, float(tol))
    frame = sweep(scene, cases=pl.DataFrame(columns), progress=False, chunk_size=n_sets * n_points)
    return {q: frame[q].cast(pl.Float64).fill_null(np.nan).to_numpy().reshape(n_sets, n_points) for q in names}
