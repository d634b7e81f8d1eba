"""Input checks that name the parameter and the allowed range (worded like polars)."""

from __future__ import annotations

import math
import numbers
from typing import Any


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"`{name}` must be a real number (found {type(value).__name__} {value!r})")
    return float(value)


def check_real(name: str, value: Any) -> float:
    """A real number (bool excluded) as float; range checks are the caller's."""
    return _number(name, value)


def check_finite(name: str, value: Any) -> float:
    x = _number(name, value)
    if not math.isfinite(x):
        raise ValueError(f"require `{name}` finite (found {x})")
    return x


def check_positive(name: str, value: Any) -> float:
    x = _number(name, value)
    if not (math.isfinite(x) and x > 0.0):
        raise ValueError(f"require `{name}` finite and > 0 (found {x})")
    return x


def check_non_negative(name: str, value: Any) -> float:
    x = _number(name, value)
    if not (math.isfinite(x) and x >= 0.0):
        raise ValueError(f"require `{name}` finite and >= 0 (found {x})")
    return x


def check_theta(value: Any, name: str = "theta_deg") -> float:
    x = _number(name, value)
    if not (math.isfinite(x) and 0.0 < x <= 90.0):
        raise ValueError(f"require `{name}` in (0, 90] degrees, measured from the plate (found {x})")
    return x


def check_int(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"`{name}` must be an integer (found {type(value).__name__} {value!r})")
    if int(value) < minimum:
        raise ValueError(f"require `{name}` >= {minimum} (found {value})")
    return int(value)


def check_choice(name: str, value: Any, choices: tuple[str, ...]) -> str:
    if value not in choices:
        allowed = ", ".join(f'"{c}"' for c in choices)
        raise ValueError(f"require `{name}` one of {allowed} (found {value!r})")
    return str(value)
