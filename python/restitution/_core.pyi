"""Type stubs for the compiled engine ``restitution._core`` (private: use the package API)."""

from typing import Mapping

import numpy as np
import numpy.typing as npt

__all__ = ["__version__", "max_dt_factor_for", "run_cases", "trace_case"]

__version__: str

def run_cases(
    columns: Mapping[str, npt.NDArray[np.float64] | npt.NDArray[np.int64]],
    vertices: npt.NDArray[np.float64] | None,
    normal_law: str,
    inertia: str,
    threads: int,
    overlap: str = "auto",
) -> dict[str, np.ndarray]:
    """One impact per row of ``columns``; returns record columns (GIL released)."""

def trace_case(
    columns: Mapping[str, npt.NDArray[np.float64] | npt.NDArray[np.int64]],
    vertices: npt.NDArray[np.float64] | None,
    normal_law: str,
    inertia: str,
    overlap: str = "auto",
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """The single case in ``columns``: (record columns, per-step trace columns)."""

def max_dt_factor_for(
    columns: Mapping[str, npt.NDArray[np.float64] | npt.NDArray[np.int64]],
    vertices: npt.NDArray[np.float64] | None,
    normal_law: str,
    inertia: str,
    explain: bool = False,
) -> tuple[npt.NDArray[np.float64], list[str] | None]:
    """Largest accepted dt_factor of each case: its integrator's stability bound for that case's
    stiffness and damping (the ``dt_factor`` column itself is ignored); with ``explain``, also
    what sets each bound, in words (else None)."""
