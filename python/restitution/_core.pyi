"""Type stubs for the compiled engine ``restitution._core`` (private: use the package API).

Columns are dicts of 1-D float64 arrays keyed by the names of ``CASE_COLUMNS``; a choice holds
the index of its name in ``CHOICES``, an unset optional parameter NaN. Invalid values raise
``restitution.RestitutionError`` naming the parameter, the value and the case (row)."""

from typing import Any, Mapping, Sequence

import numpy as np
import numpy.typing as npt

__all__ = [
    "CASE_COLUMNS",
    "CHOICES",
    "RECORD_COLUMNS",
    "TRACE_COLUMNS",
    "__version__",
    "check_case",
    "check_cases",
    "check_shape",
    "check_theta",
    "convex_template",
    "hertz_beta",
    "last_call_diagnostics",
    "max_dt_factor_for",
    "run_case",
    "run_cases",
    "trace_case",
]

__version__: str
CASE_COLUMNS: tuple[str, ...]
RECORD_COLUMNS: tuple[str, ...]
TRACE_COLUMNS: tuple[str, ...]
CHOICES: dict[str, tuple[str, ...]]

_Columns = Mapping[str, npt.NDArray[np.float64]]

def run_cases(
    columns: _Columns,
    vertices: npt.NDArray[np.float64] | None,
    threads: int,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> dict[str, np.ndarray]:
    """One impact per row of ``columns``; returns record columns (GIL released)."""

def check_cases(
    columns: _Columns,
    vertices: npt.NDArray[np.float64] | None,
    threads: int = 0,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> None:
    """Every rule of every case, without running it; raises naming the first bad case."""

def check_case(
    row: Sequence[float],
    vertices: npt.NDArray[np.float64] | None,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> None:
    """Every rule of the one case of ``row`` (a value per ``CASE_COLUMNS`` name, in order),
    without running it; raises ``RestitutionError`` naming the parameter."""

def run_case(
    row: Sequence[float],
    vertices: npt.NDArray[np.float64] | None,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> tuple[Any, ...]:
    """The one impact of ``row`` (a value per ``CASE_COLUMNS`` name, in order), on the calling
    thread with the GIL released: its record's values in ``RECORD_COLUMNS`` order (None where
    undefined)."""

def trace_case(
    row: Sequence[float],
    vertices: npt.NDArray[np.float64] | None,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> tuple[tuple[Any, ...], dict[str, np.ndarray]]:
    """The one impact of ``row``, as ``run_case``: (its record's values, per-step trace columns)."""

def max_dt_factor_for(
    columns: _Columns,
    vertices: npt.NDArray[np.float64] | None,
    explain: bool = False,
    partner_vertices: npt.NDArray[np.float64] | None = None,
) -> tuple[npt.NDArray[np.float64], list[str] | None]:
    """Largest accepted dt_factor of each case: its integrator's stability bound for that case's
    stiffness and damping (the ``dt_factor`` column itself is ignored); with ``explain``, also
    what sets each bound, in words (else None)."""

def check_shape(n: float, r: float, phi0_deg: float) -> None:
    """Checks a shape given by its sweep columns (n = 0: exact disc, >= 3: regular n-gon)."""

def check_theta(theta_deg: float) -> None:
    """Checks an impact angle (degrees from the plate, in (0, 90])."""

def convex_template(vertices: npt.NDArray[np.float64]) -> tuple[npt.NDArray[np.float64], float]:
    """A convex polygon checked by the engine: (vertices about the centroid over the circumradius, circumradius)."""

def hertz_beta(cor: float) -> float:
    """The Hertz law's damping ratio beta calibrated to the head-on restitution ``cor`` (in [0.01, 1])."""

def last_call_diagnostics() -> dict[str, float | int]:
    """Diagnostics of the last engine call on this thread (``run_cases``, ``run_case``, ``trace_case``):
    ``engine_s``, the engine's own seconds (measured in Rust), and ``waits_after_engine``, the
    waits for a poll the call made after the engine had returned. For benchmarks and tests."""
