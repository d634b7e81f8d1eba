"""Type stubs for the compiled engine ``restitution._core`` (private: use the package API)."""

from typing import Mapping

import numpy as np
import numpy.typing as npt

__all__ = ["__version__", "max_dt_factor", "run_cases", "trace_case"]

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

def max_dt_factor(integrator: str) -> float:
    """Largest accepted dt_factor of an integrator."""
