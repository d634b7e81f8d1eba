"""scipy, the ``calibrate`` extra's dependency: imported on first use with a message naming the
extra, and its seeding keyword (``rng`` from scipy 1.15, ``random_state`` / ``seed`` before)."""

from __future__ import annotations

import inspect
from typing import Any

#: What to install when scipy is missing.
INSTALL = 'pip install "restitution[calibrate]"'


def stats() -> Any:
    """``scipy.stats``, or an ImportError saying which extra provides it."""
    try:
        import scipy.stats
    except ImportError as err:
        raise ImportError(f"restitution.calibrate needs scipy >= 1.11: {INSTALL}") from err
    if not hasattr(scipy.stats, "sobol_indices"):  # pragma: no cover
        raise ImportError(f"restitution.calibrate needs scipy >= 1.11 (found {scipy.__version__}): {INSTALL}")
    return scipy.stats


def seeded(fn: Any, old_name: str, generator: Any) -> dict[str, Any]:
    """The keyword argument that seeds ``fn`` with ``generator``, in this scipy's spelling."""
    return {"rng" if "rng" in inspect.signature(fn).parameters else old_name: generator}
