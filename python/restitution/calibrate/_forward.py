"""The forward model of a calibration: many parameter sets at many measured points, in one call.

A fit evaluates every walker of every iteration at every data point; going through
:func:`restitution.sweep` would build a cases frame, a spec and a result frame each time
(measured on 320 Kharaz impacts: 19 ms through ``rs.sweep`` against the engine's 9 ms, on a
loaded machine). :func:`predict` writes the engine's columns
itself and reads back only the quantities asked for.
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


def check_names(params: Sequence[str], quantities: Sequence[str]) -> None:
    """Raises :class:`RestitutionError` naming the first unknown parameter or quantity."""
    for name in params:
        if name not in PARAMETERS:
            raise RestitutionError("free", repr(name), "scene fields a calibration can vary: " + ", ".join(PARAMETERS))
    for q in quantities:
        if q not in QUANTITIES:
            raise RestitutionError("quantity", repr(q), "a measurable record field: " + ", ".join(QUANTITIES))


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
    check_names(list(params), quantities)
    if "theta_deg" not in points.columns:
        raise RestitutionError("points.theta_deg", "missing", "a column of the points")
    arrays = {name: np.atleast_1d(np.asarray(a, dtype=np.float64)) for name, a in params.items()}
    sizes = {a.shape for a in arrays.values()}
    if len(sizes) > 1 or any(len(s) != 1 for s in sizes):
        raise RestitutionError("params", sorted(sizes), "1-D arrays of one length S")
    n_sets = next(iter(sizes))[0] if sizes else 1
    n_points = points.height
    per_case = {name: np.repeat(a, n_points) for name, a in arrays.items()}  # set s slowest, point fastest
    per_case["theta_deg"] = np.tile(points["theta_deg"].cast(pl.Float64).to_numpy(), n_sets)
    if "omega_in" in points.columns:
        per_case["omega_in"] = np.tile(points["omega_in"].cast(pl.Float64).to_numpy(), n_sets)
    if tol is not None:
        per_case["tol"] = np.full(n_sets * n_points, float(tol))
    n = n_sets * n_points
    if n == 0:
        return {q: np.empty((n_sets, n_points)) for q in quantities}
    raw = _engine.run(_engine.columns(scene.engine_values(), per_case, n), scene.template_vertices(), 0)
    lost = raw["timed_out"].astype(bool)
    out = {}
    for q in quantities:
        values = np.array(raw[q], dtype=np.float64)
        valid = raw.get(f"{q}_valid")
        values[lost if valid is None else lost | ~valid.astype(bool)] = np.nan
        out[q] = values.reshape(n_sets, n_points)
    return out


__all__ = ["PARAMETERS", "predict"]
