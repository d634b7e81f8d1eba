"""The forward model of a calibration: many parameter sets at many measured points, in one call.

Every statistical method of :mod:`restitution.calibrate` (the fit, the sensitivity indices, the
experiment design) asks the same question: what does the engine predict for S parameter sets at
P points (angles and spins)? :func:`predict` answers it with one engine call over the S x P
cases, so no Python loop ever runs per impact. A fit asks it at every iteration; going through
:func:`restitution.sweep` would build a cases frame, a spec and a result frame each time
(measured on 320 Kharaz impacts: 19 ms through ``rs.sweep`` against the engine's 9 ms, on a
loaded machine), so :func:`predict` writes the engine's columns itself and reads back only the
quantities asked for. The checks of its arguments are the ones every method uses.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import polars as pl

from .. import _engine
from ..datasets import QUANTITIES
from ..errors import RestitutionError
from ..scene import Scene

#: Scene fields a calibration may vary: the engine's numeric per-case columns that are not the
#: impact's own axes (a choice or the shape's vertex count is not a continuous parameter).
PARAMETERS: tuple[str, ...] = tuple(c for c in _engine.CASE_COLUMNS
                                    if c not in _engine.CHOICES and c not in (
                                        "theta_deg", "omega_in", "n", "partner_n", "tol", "error_estimate",
                                        "max_steps", "body", "partner_body"))

#: Columns a point may carry: where and how the impact happens.
POINT_COLUMNS = ("theta_deg", "omega_in")


def check_quantities(quantities: Sequence[str], where: str = "quantities") -> list[str]:
    """The quantities as a list; an unknown one is a :class:`RestitutionError` naming ``where``."""
    out = [quantities] if isinstance(quantities, str) else list(quantities)
    for q in out:
        if q not in QUANTITIES:
            raise RestitutionError(where, repr(q), "a measurable record field: " + ", ".join(QUANTITIES))
    if not out:
        raise RestitutionError(where, "[]", "at least one record field")
    return out


def check_parameter(name: str, where: str = "params") -> str:
    """A scene field a calibration may vary (:data:`PARAMETERS`); else an error naming ``where``."""
    if name not in PARAMETERS:
        raise RestitutionError(where, repr(name), "scene fields a calibration can vary: " + ", ".join(PARAMETERS))
    return name


def check_names(params: Sequence[str], quantities: Sequence[str]) -> None:
    """A fit's free fields and measured quantities, each error naming ``free`` or ``quantity``."""
    for name in params:
        check_parameter(name, "free")
    check_quantities(quantities, "quantity")


def check_points(points: pl.DataFrame) -> pl.DataFrame:
    """A frame of points: ``theta_deg`` and optionally ``omega_in``, at least one row, as float64."""
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
    """Each quantity of each of S parameter sets at each of P points, from one engine call.

    Parameters
    ----------
    scene : Scene
        Every field that ``params`` does not set.
    params : mapping
        Scene field name -> array of shape (S,): parameter set ``s`` is ``{name: a[s]}``.
    points : polars.DataFrame
        P rows with ``theta_deg`` and optionally ``omega_in`` (default 0).
    quantities : sequence of str
        Record fields to return (:data:`restitution.datasets.QUANTITIES`).
    tol : float, optional
        Overrides the scene's ``tol`` (the adaptive path's accuracy target).

    Returns
    -------
    dict
        Quantity -> array (S, P); NaN where the record leaves the value undefined (e_t head-on)
        or the impact ran out of steps (``timed_out``).

    Examples
    --------
    >>> import numpy as np, polars as pl, restitution as rs
    >>> out = predict(rs.Scene(), {"mu": np.array([0.0, 0.2])}, pl.DataFrame({"theta_deg": [30.0, 90.0]}), ["e_t"])
    >>> out["e_t"].shape, bool(np.isnan(out["e_t"][:, 1]).all())     # e_t is undefined head-on
    ((2, 2), True)
    """
    names = check_quantities(quantities)
    points = check_points(points)
    arrays = {check_parameter(name): np.atleast_1d(np.asarray(a, dtype=np.float64)) for name, a in params.items()}
    sizes = {a.shape for a in arrays.values()}
    if len(sizes) > 1 or any(len(s) != 1 for s in sizes):
        raise RestitutionError("params", sorted(sizes), "1-D arrays of one length S")
    n_sets = next(iter(sizes))[0] if sizes else 1
    n_points = points.height
    n = n_sets * n_points
    if n == 0:
        return {q: np.empty((n_sets, n_points)) for q in names}
    per_case = {name: np.repeat(a, n_points) for name, a in arrays.items()}  # set s slowest, point fastest
    per_case.update({c: np.tile(points[c].to_numpy(), n_sets) for c in points.columns})
    if tol is not None:
        per_case["tol"] = np.full(n, float(tol))
    raw = _engine.run(_engine.columns(scene.engine_values(), per_case, n), scene.template_vertices(), 0)
    lost = raw["timed_out"].astype(bool)
    out = {}
    for q in names:
        values = np.array(raw[q], dtype=np.float64)
        valid = raw.get(f"{q}_valid")
        values[lost if valid is None else lost | ~valid.astype(bool)] = np.nan
        out[q] = values.reshape(n_sets, n_points)
    return out


__all__ = ["PARAMETERS", "POINT_COLUMNS", "check_names", "check_parameter", "check_points", "check_quantities",
           "predict"]
