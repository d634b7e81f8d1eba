"""The engine seen from Python: its one schema and its one validator.

The compiled engine names every per-case input column (``CASE_COLUMNS``), every record column
(``RECORD_COLUMNS``) and every choice (``CHOICES``); this module uses those names, never a
copy of them. Every rule on values lives in the engine (``_core.check_cases``, and again when a
case runs); Python checks only what the engine cannot know: that a value is a number at all,
and that a choice's name exists (the engine takes its index).
"""

from __future__ import annotations

import numbers
from typing import Any, Mapping, Sequence

import numpy as np
import polars as pl

from . import _core
from .errors import RestitutionError, RestitutionTypeError

#: Per-case input columns, in the engine's order (all float64; a choice holds its code).
CASE_COLUMNS: tuple[str, ...] = tuple(_core.CASE_COLUMNS)
#: Each case column's position in a row.
COLUMN_INDEX: dict[str, int] = {name: k for k, name in enumerate(CASE_COLUMNS)}
#: Record columns, in output order.
RECORD_COLUMNS: tuple[str, ...] = tuple(_core.RECORD_COLUMNS)
#: Per-step trace columns.
TRACE_COLUMNS: tuple[str, ...] = tuple(_core.TRACE_COLUMNS)
#: Every choice: name -> its public names, in code order.
CHOICES: dict[str, tuple[str, ...]] = {k: tuple(v) for k, v in _core.CHOICES.items()}
#: Optional parameters: None in Python, NaN ("unset") in the engine's columns; their range.
OPTIONAL = {"kn": "> 0", "cn": ">= 0", "kt": "> 0", "nu": "in (-1, 0.5]", "plate_E": "> 0",
            "plate_nu": "in (-1, 0.5]", "cor": "in [0.01, 1]", "max_steps": "a whole number >= 1",
            "dt_factor": "> 0", "partner_rho": "> 0", "partner_E": "> 0",
            "partner_nu": "in (-1, 0.5]"}

#: Flags: bool in Python, 0 / 1 in the engine's columns.
FLAGS = ("error_estimate",)


def boolean(name: str, value: Any) -> bool:
    """A setting that is True or False (``trace``, ``resume``, ``allow_partial``): nothing else,
    since ``bool("no")`` is True."""
    if not isinstance(value, (bool, np.bool_)):
        raise RestitutionTypeError(name, _found(value), "True or False")
    return bool(value)


def flag(name: str, value: Any) -> float:
    """A flag (bool, or the engine's 0 / 1) as 0.0 or 1.0."""
    if isinstance(value, (bool, np.bool_)) or (isinstance(value, numbers.Real) and value in (0, 1)):
        return float(bool(value))
    raise RestitutionTypeError(name, _found(value), "True or False")


#: What a numeric parameter accepts, in words (the rule of :func:`is_real`).
REAL = "a real number (not a bool or a string)"


def is_real(value: Any) -> bool:
    """The one type rule of a numeric parameter: a real number, bools (Python's or numpy's) excluded."""
    return _real_type(type(value))


def _real_type(kind: type) -> bool:
    return issubclass(kind, numbers.Real) and not issubclass(kind, (bool, np.bool_))


def _found(value: Any) -> str:
    return f"{type(value).__name__} {value!r:.80}"


def real(name: str, value: Any) -> float:
    """A real number (bool and str refused: :func:`is_real`) as float; the engine checks its range."""
    if type(value) is float:  # the common case, without the checks below (a scene's hot path)
        return value
    if not is_real(value):
        raise RestitutionTypeError(name, _found(value), REAL)
    return float(value)


def reals(name: str, values: Any, *, cases: bool = False) -> np.ndarray:
    """The values of a numeric sweep axis or ``cases`` column as float64, each by :func:`is_real`
    (a list holding a bool or a numeric string is refused, not converted). With ``cases``, the
    values are a cases table's rows and the error carries the row as ``.case``."""
    return _typed(name, values, cases, "iuf", _real_type, REAL)


def _integer_type(kind: type) -> bool:
    """An integer type, bools excluded (a shape's count of corners)."""
    return issubclass(kind, numbers.Integral) and not issubclass(kind, (bool, np.bool_))


def integers(name: str, values: Any, *, cases: bool = False) -> np.ndarray:
    """:func:`reals` for an integer parameter (``n``): integers, bools excluded."""
    return _typed(name, values, cases, "iu", _integer_type, "an integer (not a bool, a float or a string)")


def _typed(name: str, values: Any, cases: bool, kinds: str, ok: Any, rule: str) -> np.ndarray:
    if isinstance(values, np.ndarray) and values.dtype.kind in kinds:
        return values.astype(np.float64)
    try:
        a = np.asarray(values, dtype=object)
    except (TypeError, ValueError):  # ragged nests of arrays
        raise RestitutionTypeError(name, f"{values!r:.80}", f"{rule}, or a 1-D array of them") from None
    flat = a.ravel()
    if all(ok(kind) for kind in set(map(type, flat))):  # the rule is on types: each type checked once
        return a.astype(np.float64)
    at = next(i for i, v in enumerate(flat) if not ok(type(v)))
    if cases:
        raise RestitutionTypeError(name, _found(flat[at]), rule, case=at)
    where = f" at position {at}" if a.ndim else ""
    raise RestitutionTypeError(name, _found(flat[at]) + where, rule)


def optional(name: str, value: Any) -> float:
    """An optional parameter: None is the engine's NaN ("unset"), so an explicit NaN is refused."""
    if value is None:
        return float("nan")
    x = real(name, value)
    if x != x:
        raise RestitutionError(name, x, f"finite and {OPTIONAL[name]}, or None for the default")
    return x


def integer(name: str, value: Any, minimum: int) -> int:
    """An integer >= ``minimum`` (the shapes' counts, which Python builds before the engine)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise RestitutionTypeError(name, _found(value), "an integer (not a bool)")
    if int(value) < minimum:
        raise RestitutionError(name, value, f">= {minimum}")
    return int(value)


def code(name: str, value: Any) -> int:
    """The engine's code of a choice's name."""
    names = CHOICES[name]
    if isinstance(value, str) and value in names:  # the hot path: a scene's few choices, no message built
        return names.index(value)
    allowed = "one of " + ", ".join(f'"{c}"' for c in names)
    if not isinstance(value, str):
        raise RestitutionTypeError(name, _found(value), f"a name, {allowed}")
    raise RestitutionError(name, repr(value), allowed)


def columns(base: Mapping[str, float], per_case: Mapping[str, np.ndarray], n: int) -> dict[str, np.ndarray]:
    """Engine columns of length ``n``: per-case arrays where given, ``base`` values elsewhere."""
    out = {}
    for name in CASE_COLUMNS:
        v = per_case.get(name)
        out[name] = (np.ascontiguousarray(v, dtype=np.float64) if v is not None
                     else np.full(n, base[name], dtype=np.float64))
    return out


def row(values: Mapping[str, float]) -> tuple[float, ...]:
    """One case as a row: its value of every engine column, in ``CASE_COLUMNS`` order."""
    return tuple(values[name] for name in CASE_COLUMNS)


def with_values(base: tuple[float, ...], **values: float) -> list[float]:
    """A copy of the row ``base`` with some columns set (each named by its ``CASE_COLUMNS`` name)."""
    out = list(base)
    for name, value in values.items():
        out[COLUMN_INDEX[name]] = value
    return out


#: A scene's vertex templates (``Scene.template_vertices``): the particle's convex polygon's
#: unit-circumradius vertices or None, or, with a ConvexPolygon partner, the pair (particle's or
#: None, partner's).
Templates = Any


def _split(vertices: Templates) -> tuple[np.ndarray | None, np.ndarray | None]:
    """(the particle's vertices, the partner's) of ``vertices``."""
    return vertices if isinstance(vertices, tuple) else (vertices, None)


def check(cols: Mapping[str, np.ndarray], vertices: Templates) -> None:
    """Every rule of every case, without running it: raises :class:`RestitutionError` naming
    the parameter, its value and the case (the row of ``cols``)."""
    own, partner = _split(vertices)
    _core.check_cases(cols, own, partner_vertices=partner)


def check_one(row: Sequence[float], vertices: Templates) -> None:
    """Every rule of the one case of ``row`` (in ``CASE_COLUMNS`` order), without running it:
    raises :class:`RestitutionError` naming the parameter and its value."""
    own, partner = _split(vertices)
    _core.check_case(row, own, partner_vertices=partner)


def run(cols: Mapping[str, np.ndarray], vertices: Templates, threads: int) -> dict[str, np.ndarray]:
    """Runs one impact per row (GIL released); the record columns."""
    own, partner = _split(vertices)
    return dict(_core.run_cases(cols, own, threads, partner_vertices=partner))


def run_one(row: Sequence[float], vertices: Templates) -> tuple[Any, ...]:
    """Runs the one case of ``row`` (GIL released, on this thread): its record's values in
    ``RECORD_COLUMNS`` order, None where undefined."""
    own, partner = _split(vertices)
    return _core.run_case(row, own, partner_vertices=partner)


def trace_one(row: Sequence[float], vertices: Templates) -> tuple[tuple[Any, ...], pl.DataFrame]:
    """Runs the one case of ``row``: (its record's values as :func:`run_one`, per-step trace frame)."""
    own, partner = _split(vertices)
    values, tr = _core.trace_case(row, own, partner_vertices=partner)
    return values, pl.DataFrame({name: tr[name] for name in TRACE_COLUMNS})


def dt_bounds(cols: Mapping[str, np.ndarray], vertices: Templates,
              explain: bool = False) -> tuple[np.ndarray, list[str] | None]:
    """Each case's largest ``dt_factor`` (one formula, in the engine); with ``explain``, what sets it."""
    own, partner = _split(vertices)
    return _core.max_dt_factor_for(cols, own, explain, partner_vertices=partner)


def records_frame(raw: Mapping[str, np.ndarray]) -> pl.DataFrame:
    """Record columns as a polars frame; an undefined value (``<name>_valid`` false) is null, never NaN.

    Built from one Series per column, nulls scattered into the optional ones: a frame from the
    dict of columns with the nulls set by a ``when/then`` query took 0.35-0.4 ms per call, most
    of a one-impact :func:`restitution.simulate` and a fixed cost of every sweep chunk (0.24 ms now).
    """
    return pl.DataFrame([_record_series(raw, name) for name in RECORD_COLUMNS])


def _record_series(raw: Mapping[str, np.ndarray], name: str) -> pl.Series:
    series = pl.Series(name, raw[name])
    valid = raw.get(f"{name}_valid")
    if valid is None or valid.all():
        return series
    return series.scatter(np.flatnonzero(~valid), None)
