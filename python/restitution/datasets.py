"""Measured impacts, in the one form calibration reads, and the one check of that form.

A measurement set is a polars frame, one row per measured value:

========== ==============================================================================
column     meaning
========== ==============================================================================
theta_deg  impact angle from the plate, in (0, 90] (as everywhere in the package)
omega_in   incoming spin in rad/s (optional: 0 when the column is absent)
quantity   the record field measured (:data:`QUANTITIES`: e_n, e_t, e_kin, omega_out, ...)
value      the measured value, in the record field's unit
sigma      one standard deviation of ``value``, > 0
========== ==============================================================================

:func:`check_measurements` is the validator that :func:`restitution.calibrate.fit`,
:func:`restitution.calibrate.compare` and ``restitution calibrate`` use; a bad row raises
:class:`restitution.RestitutionError` naming the column (``data.sigma``) and the row (``case``).

Examples
--------
>>> import restitution as rs
>>> df = rs.datasets.kharaz2001()
>>> df.columns, df.height
(['theta_deg', 'omega_in', 'quantity', 'value', 'sigma'], 20)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import polars as pl

from ._engine import RECORD_COLUMNS
from .errors import RestitutionError
from .study import published

#: Record fields that are not outcomes of an impact one can measure: the run's bookkeeping.
_BOOKKEEPING = ("steps", "contacts", "slip_events", "separated", "timed_out", "step_budget", "stop", "err_est",
                "energy_in", "energy_out", "work_normal", "work_friction", "work_damping", "energy_residual",
                "momentum_residual", "angular_momentum_residual")
#: Quantities a measurement may name: every record field that is a measurable outcome.
QUANTITIES: tuple[str, ...] = tuple(c for c in RECORD_COLUMNS if c not in _BOOKKEEPING)
#: The columns of a measurement set, in order.
COLUMNS = ("theta_deg", "omega_in", "quantity", "value", "sigma")


def check_measurements(data: Any) -> pl.DataFrame:
    """The measurement set ``data`` checked and in canonical form (the five :data:`COLUMNS`, in
    order, ``omega_in`` filled with 0 when absent, numbers as float64).

    Raises :class:`restitution.RestitutionError` naming the column and the row (``case``) of the
    first bad value: a missing column, an unknown quantity, a value that is not finite, sigma
    <= 0, theta_deg outside (0, 90], e_t head-on (where the record leaves it undefined).
    """
    if not isinstance(data, pl.DataFrame):
        raise TypeError(f"measurements must be a polars DataFrame (found {type(data).__name__})")
    for name in COLUMNS:
        if name not in data.columns and name != "omega_in":
            raise RestitutionError(f"data.{name}", "missing", "a column of the measurements (" + ", ".join(COLUMNS)
                                   + "; omega_in optional)")
    if data.height == 0:
        raise RestitutionError("data", "0 rows", "at least one measurement")
    if "omega_in" not in data.columns:
        data = data.with_columns(pl.lit(0.0).alias("omega_in"))
    quantity = data["quantity"].cast(pl.String, strict=False).to_list()
    for row, q in enumerate(quantity):
        if q not in QUANTITIES:
            raise RestitutionError("data.quantity", repr(q), "a measurable record field: " + ", ".join(QUANTITIES),
                                   case=row)
    numbers = {name: _floats(data, name) for name in ("theta_deg", "omega_in", "value", "sigma")}
    for name, expected, ok in (
            ("theta_deg", "in (0, 90]", lambda x: (x > 0.0) & (x <= 90.0)),
            ("omega_in", "finite", np.isfinite), ("value", "finite", np.isfinite),
            ("sigma", "finite and > 0", lambda x: np.isfinite(x) & (x > 0.0))):
        bad = np.flatnonzero(~ok(numbers[name]))
        if bad.size:
            raise RestitutionError(f"data.{name}", float(numbers[name][bad[0]]), expected, case=int(bad[0]))
    head_on_e_t = np.flatnonzero((numbers["theta_deg"] == 90.0) & (np.asarray(quantity) == "e_t"))
    if head_on_e_t.size:
        raise RestitutionError("data.theta_deg", 90.0, "< 90 for e_t (undefined head-on)", case=int(head_on_e_t[0]))
    return pl.DataFrame({"theta_deg": numbers["theta_deg"], "omega_in": numbers["omega_in"],
                         "quantity": pl.Series(quantity, dtype=pl.String), "value": numbers["value"],
                         "sigma": numbers["sigma"]})


def _floats(data: pl.DataFrame, name: str) -> np.ndarray:
    """A column as float64, a null or a non-number as NaN (so the range check names its row)."""
    col = data[name]
    if not (col.dtype.is_numeric() or col.dtype == pl.Null):
        raise RestitutionError(f"data.{name}", str(col.dtype), "a column of numbers")
    return col.cast(pl.Float64).fill_null(float("nan")).to_numpy().astype(np.float64)


def scatter_sigma(x: np.ndarray, y: np.ndarray, degree: int = 4) -> float:
    """The scatter of ``y`` about a smooth curve: the residual standard deviation of a
    least-squares polynomial of ``degree`` in ``x`` (n - degree - 1 degrees of freedom)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    dof = x.size - degree - 1
    if dof < 1:
        raise RestitutionError("degree", degree, f"< {x.size - 1} (the number of points - 1)")
    resid = y - np.polyval(np.polyfit(x, y, degree), x)
    return math.sqrt(float(resid @ resid) / dof)


def kharaz2001() -> pl.DataFrame:
    """Kharaz, Gorham & Salman (2001): 5 mm alumina spheres on a soda-lime glass anvil at 3.9 m/s,
    no incoming spin; the tangential restitution e_t (10 angles) and the rebound spin omega_out
    (rad/s, negative: forward rolling; 10 angles).

    Provenance: A. H. Kharaz, D. A. Gorham, A. D. Salman, "An experimental study of the elastic
    rebound of spheres", Powder Technology 120 (2001) 281-291, as reprinted in Chung & Ooi (2011),
    Granular Matter 13:643-656, Test 4. The numbers are the third-party digitisation of those
    printed figures in :mod:`restitution.study.published` (about +-0.01 in e_t, +-10 rad/s, +-1
    deg), the same numbers ``restitution validate`` overlays; the paper's angles from the normal
    are turned into ``theta_deg`` = 90 - angle. The contact-patch rebound angle of the same
    figures is left out: it is not a record field (the record's ``rebound_angle_deg`` is the
    centre's).

    How sigma was set: the figures carry no per-point error bars, so each quantity's sigma is the
    scatter of its points about a smooth curve, :func:`scatter_sigma` with a quartic in the angle
    (the lowest degree past which the residual stops falling: 0.015 for e_t, 32 rad/s for
    omega_out), the same for every point of a quantity. It is larger than the digitisation's
    resolution, so it measures the experiment's scatter; it includes no systematic error (e.g. of
    the angle), so read a posterior's width as a lower bound.
    """
    frames = []
    for quantity, table in (("e_t", published.TEST4_E_T), ("omega_out", published.TEST4_OMEGA)):
        angle, value = (np.asarray(c, dtype=float) for c in table["experiment"])
        sigma = scatter_sigma(angle, value)
        frames.append(pl.DataFrame({"theta_deg": np.round(90.0 - angle, 10), "omega_in": np.zeros(angle.size),
                                    "quantity": [quantity] * angle.size, "value": value,
                                    "sigma": np.full(angle.size, sigma)}))
    return check_measurements(pl.concat(frames))


__all__ = ["COLUMNS", "QUANTITIES", "check_measurements", "kharaz2001", "scatter_sigma"]
